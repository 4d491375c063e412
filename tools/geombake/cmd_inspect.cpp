// geombake inspect FILE...: verify baked containers (every check of
// geom/baked_reader.h: header, table, alignment, padding, each section's CRC-32C)
// and list their sections. A file that fails prints `Error: FILE: ...` and makes
// the exit status 1.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/args.h"
#include "geom/baked_file.h"
#include "geom/baked_reader.h"
#include "geom/baked_records.h"
#include "geombake/command.h"
#include "geombake/names.h"

namespace geombake {
namespace {

const char* kInspectHelp =
    "usage: geombake inspect [options] FILE...\n"
    "  Verifies each baked file (header, section table, alignment, padding, checksums)\n"
    "  and lists its sections.\n"
    "options:\n"
    "  --json   one JSON object per file, one per line (with the lights, glTF's names)\n"
    "  -v       also print the topology report section (control characters escaped)\n";

std::string type_label(const geom::baked::Section& s) {
  std::string name = geom::baked::type_name(s.type);
  return name == "unknown" ? "type " + std::to_string(uint32_t(s.type)) : name;
}

// Prints `size` bytes of a text section (any size: 64-bit throughout) with
// every control character, DEL and byte over 0x7e escaped (\n, \t, \xNN),
// so a hostile report cannot drive the terminal; written in chunks.
void print_text(const unsigned char* data, uint64_t size) {
  std::string chunk;
  chunk.reserve(1 << 16);
  for (uint64_t i = 0; i < size; ++i) {
    const unsigned char c = data[i];
    if (c == '\n')
      chunk += "\\n";
    else if (c == '\t')
      chunk += "\\t";
    else if (c == '\\')
      chunk += "\\\\";
    else if (c < 0x20 || c >= 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      chunk += b;
    } else {
      chunk += char(c);
    }
    if (chunk.size() >= (1 << 16) - 8) std::fwrite(chunk.data(), 1, chunk.size(), stdout), chunk.clear();
  }
  std::fwrite(chunk.data(), 1, chunk.size(), stdout);
}

// The lights of light_params and light_names as `--json` lists them: glTF's
// names (KHR_lights_punctual), null where the light's type has no such field
// (a directional light's position and range, a point light's direction and
// cone angles; an infinite range). Empty without a light_params section.
nlohmann::ordered_json lights_json(const geom::baked::Reader& r) {
  using geom::LightRecord;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  const geom::baked::Section* params = r.find(geom::baked::SectionType::LightParams);
  const geom::baked::Section* names = r.find(geom::baked::SectionType::LightNames);
  if (!params || params->stride != sizeof(LightRecord)) return list;
  const auto vec3 = [](const double* v) { return nlohmann::ordered_json::array({v[0], v[1], v[2]}); };
  for (uint64_t i = 0; i < params->count; ++i) {
    LightRecord l;
    std::memcpy(&l, params->data + i * sizeof l, sizeof l);
    std::string name;
    if (names && l.name_offset <= names->size && l.name_size <= names->size - l.name_offset)
      name.assign(reinterpret_cast<const char*>(names->data) + l.name_offset, l.name_size);
    const bool point = l.type == LightRecord::kPoint, spot = l.type == LightRecord::kSpot;
    const bool directional = l.type == LightRecord::kDirectional;
    const nlohmann::ordered_json null;
    list.push_back({{"name", name},
                    {"type", directional ? "directional"
                             : point     ? "point"
                             : spot      ? "spot"
                                         : "unknown"},
                    {"position", point || spot ? vec3(l.position) : null},
                    {"direction", directional || spot ? vec3(l.direction) : null},
                    {"range", (point || spot) && l.range > 0 ? nlohmann::ordered_json(l.range) : null},
                    {"color", vec3(l.color)},
                    {"intensity", l.intensity},
                    {"inner_cone_angle", spot ? nlohmann::ordered_json(l.inner_cone_angle) : null},
                    {"outer_cone_angle", spot ? nlohmann::ordered_json(l.outer_cone_angle) : null}});
  }
  return list;
}

int run_inspect(const std::vector<std::string>& argv) {
  cli::Args args(argv, {"--json", "-v", "--help", "-h"}, {});
  if (args.has("--help") || args.has("-h")) {
    std::fputs(kInspectHelp, stdout);
    return 0;
  }
  if (!args.error().empty()) {
    std::fprintf(stderr, "Error: %s\n%s", args.error().c_str(), kInspectHelp);
    return 2;
  }
  if (args.positional().empty()) {
    std::fprintf(stderr, "Error: no input file\n%s", kInspectHelp);
    return 2;
  }
  const bool json = args.has("--json");
  int failed = 0;
  for (const std::string& path : args.positional()) {
    geom::baked::File file;
    // load(), not map(): a mapped file that shrinks under us would be a SIGBUS.
    if (!file.load(path)) {
      std::fprintf(stderr, "Error: %s\n", file.error().c_str());
      if (json)
        std::printf("{\"file\":%s,\"ok\":false,\"error\":%s}\n", json_quote(path).c_str(),
                    json_quote(file.error()).c_str());
      ++failed;
      continue;
    }
    const geom::baked::Reader& r = file.reader();
    if (json) {
      nlohmann::ordered_json j = {
          {"ok", true},
          {"version", std::to_string(r.version_major()) + "." + std::to_string(r.version_minor())},
          {"bytes", r.file_size()},
          {"alignment", r.alignment()},
          {"header_crc32c", r.header_crc()},
          {"sections", nlohmann::ordered_json::array()}};
      for (const auto& s : r.sections())
        j["sections"].push_back({{"name", s.name},
                                 {"type", type_label(s)},
                                 {"item", s.item},
                                 {"format", geom::baked::format_name(s.format)},
                                 {"stride", s.stride},
                                 {"count", s.count},
                                 {"offset", s.offset},
                                 {"bytes", s.size},
                                 {"crc32c", s.crc}});
      j["lights"] = lights_json(r);
      // Light names are the file's bytes: invalid UTF-8 is replaced, never thrown.
      const std::string text = j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
      std::printf("{\"file\":%s,%s\n", json_quote(path).c_str(), text.c_str() + 1);  // any name (names.h)
      continue;
    }
    std::printf("%s: geombake baked file %u.%u, %llu bytes, %llu sections (alignment %u), all checksums verified\n",
                path.c_str(), r.version_major(), r.version_minor(), (unsigned long long)r.file_size(),
                (unsigned long long)r.sections().size(), r.alignment());
    std::printf("  %-3s %-15s %-22s %-4s %-7s %6s %12s %10s %12s  %s\n", "#", "name", "type", "item", "format",
                "stride", "count", "offset", "bytes", "crc32c");
    for (size_t i = 0; i < r.sections().size(); ++i) {
      const auto& s = r.sections()[i];
      std::printf("  %-3llu %-15s %-22s %-4u %-7s %6u %12llu %10llu %12llu  %08x\n", (unsigned long long)i, s.name,
                  type_label(s).c_str(), s.item, geom::baked::format_name(s.format), s.stride,
                  (unsigned long long)s.count, (unsigned long long)s.offset, (unsigned long long)s.size, s.crc);
    }
    if (args.has("-v"))
      if (const auto* t = r.find(geom::baked::SectionType::TopologyReport))
        std::fputs("  topology: ", stdout), print_text(t->data, t->size), std::fputc('\n', stdout);
  }
  return failed ? 1 : 0;
}

GEOMBAKE_COMMAND("inspect", "verify baked files and list their sections", run_inspect);

}  // namespace
}  // namespace geombake
