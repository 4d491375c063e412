// geom::bake's consumer (tests/install/run.sh): bakes a mesh file to a .gbake.
#include <geom/bake.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  const geom::BakeResult r = geom::bake_file(argv[1], argv[2]);
  if (!r.ok) {
    std::fprintf(stderr, "Error: %s\n", r.error.c_str());
    return 1;
  }
  std::printf("bake: %zu sections\n", r.sections.size());
  return 0;
}
