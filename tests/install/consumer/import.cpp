// geom::import's consumer (tests/install/run.sh): imports a mesh file.
#include <geom/import.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const geom::ImportResult r = geom::import_file(argv[1]);
  if (!r.ok) {
    std::fprintf(stderr, "Error: %s\n", r.error.c_str());
    return 1;
  }
  std::printf("import: %zu triangles\n", r.scene.triangle_count());
  return 0;
}
