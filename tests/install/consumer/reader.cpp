// geom::reader's consumer (tests/install/run.sh): the two reader headers and
// the C++ standard library, nothing else; built once through
// find_package(geom COMPONENTS reader) and once with the include path alone.
// Reads a .gbake into memory, validates it, and counts its records.
#include <geom/baked_reader.h>
#include <geom/baked_records.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer FILE.gbake\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  geom::baked::Reader reader;
  if (!reader.open(bytes.data(), bytes.size())) {
    std::fprintf(stderr, "Error: %s: %s\n", argv[1], reader.error().c_str());
    return 1;
  }
  const geom::baked::Section* quads = reader.find(geom::baked::SectionType::EsmQuads);
  const geom::baked::Section* sides = reader.find(geom::baked::SectionType::VolumeSides);
  if (!quads || !sides || quads->stride != sizeof(geom::EsmQuad) || sides->stride != sizeof(geom::SvSide)) {
    std::fprintf(stderr, "Error: %s: no ESM quads or volume sides of the records' size\n", argv[1]);
    return 1;
  }
  std::printf("reader: %zu sections, %llu quads, %llu sides", reader.sections().size(),
              (unsigned long long)quads->count, (unsigned long long)sides->count);
#ifdef SHADER_DIR
  std::printf(", shaders in %s", SHADER_DIR);
#endif
  std::printf("\n");
  return 0;
}
