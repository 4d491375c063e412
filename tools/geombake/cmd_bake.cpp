// geombake bake INPUT... -o OUT: import, weld, analyse and write each input as a
// baked container (geom/bake.h, format in geom/baked_reader.h). Inputs are baked
// in parallel (-j); each output is a pure function of its input and the flags,
// whatever the thread count. A failed input prints `Error: FILE: ...`, leaves no
// output file, and makes the exit status 1 while the other inputs still get baked.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "geom/atomic_file.h"
#include "geom/bake.h"
#include "geombake/args.h"
#include "geombake/command.h"
#include "geombake/inputs.h"

namespace geombake {
namespace {

const char* kBakeHelp =
    "usage: geombake bake [options] INPUT... -o OUT\n"
    "  Writes one baked container per input: -o FILE for one input, -o DIR for several\n"
    "  (DIR/NAME.gbake, created if missing). INPUT may be ARCHIVE.pk3:path/inside.bsp,\n"
    "  ARCHIVE.pk3 for every map inside, or a directory for every mesh file inside.\n"
    "options:\n"
    "  -o OUT              output file (one input) or directory\n"
    "  -j N                bake N inputs at once (default: the number of cores)\n"
    "  -v                  sections, bytes and topology of each input on stdout\n"
    "  --json              one JSON object per input, one per line, on stdout\n"
    "  --depfile FILE      write a Makefile depfile (OUTPUT: INPUT) for build systems\n"
    "  --no-positions      omit the welded positions\n"
    "  --no-indices        omit the welded index buffer\n"
    "  --no-remap          omit the weld remap (source vertex -> welded vertex)\n"
    "  --no-planes         omit the face planes\n"
    "  --no-topology       omit the topology report\n"
    "  --no-esm            omit the extended-shadow-map quads\n"
    "  --no-volume         omit the generic shadow volume (sides, caps)\n"
    "  --one-sided-closed  classic one-sided volumes for closed components (lights outside them only)\n"
    "  --no-adjacency      omit the triangles-with-adjacency index buffer\n"
    "  --light X,Y,Z,W     also bake the exact shadow volume of this static light (repeatable;\n"
    "                      W = 1 a point, W = 0 a direction towards X,Y,Z; input coordinates)\n"
    "  --no-scene-lights   no exact volumes for the file's KHR_lights_punctual lights\n"
    "  --weld-tolerance T  merge vertices closer than T (default 0: exact positions)\n"
    "  --coplanar-degrees D  normals closer than D degrees make a coplanar edge (default 0.01)\n"
    "  --patch-level N     Bezier patch tessellation of Quake 3 maps (default 4)\n"
    "  --md3-frame N       MD3 frame to import (default 0)\n"
    "  --max-triangles N   refuse inputs with more triangles\n";

constexpr const char* kExtension = ".gbake";

// "dir/mesh.obj" -> "mesh", "maps.pk3:maps/q3dm1.bsp" -> "q3dm1".
std::string stem_of(const std::string& input) {
  size_t slash = input.find_last_of("/\\:");
  std::string base = slash == std::string::npos ? input : input.substr(slash + 1);
  size_t dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

// The file an input depends on: the archive for an archive member.
std::string dependency_of(const std::string& input) {
  for (const char* ext : {".pk3:", ".zip:"}) {
    size_t at = input.find(ext);
    if (at != std::string::npos) return input.substr(0, at + 4);
  }
  return input;
}

std::string make_escape(const std::string& path) {
  std::string o;
  for (char c : path) {
    if (c == ' ' || c == '#' || c == '\\') o += '\\';
    if (c == '$') o += '$';
    o += c;
  }
  return o;
}

// What the report says of a written section; the bytes themselves are dropped
// as soon as the file is written, so a run over many inputs holds one bake per thread.
struct SectionInfo {
  std::string name;
  geom::baked::SectionType type;
  geom::baked::Format format;
  uint32_t stride, item;
  uint64_t count, bytes;
  uint32_t crc;
};

SectionInfo info_of(const geom::BakedSection& s) {
  return {s.name, s.type,  s.format,       s.stride,
          s.item, s.count, s.bytes.size(), geom::baked::crc32c(s.bytes.data(), s.bytes.size())};
}

nlohmann::ordered_json section_json(const SectionInfo& s) {
  return {{"name", s.name},
          {"type", geom::baked::type_name(s.type)},
          {"format", geom::baked::format_name(s.format)},
          {"item", s.item},
          {"stride", s.stride},
          {"count", s.count},
          {"bytes", s.bytes},
          {"crc32c", s.crc}};
}

struct Job {
  std::string input, output, error;  // error: why no output was planned, or the bake's error
  geom::BakeResult result;           // without its sections' bytes once written
  std::vector<SectionInfo> sections;
  bool done = false;
};

int run_bake(const std::vector<std::string>& argv) {
  Args args(argv,
            {"--json", "-v", "--help", "-h", "--no-positions", "--no-indices", "--no-remap", "--no-planes",
             "--no-topology", "--no-esm", "--no-volume", "--no-adjacency", "--no-scene-lights", "--one-sided-closed"},
            {"-o", "-j", "--depfile", "--light", "--weld-tolerance", "--coplanar-degrees", "--patch-level",
             "--md3-frame", "--max-triangles"});
  if (args.has("--help") || args.has("-h")) {
    std::fputs(kBakeHelp, stdout);
    return 0;
  }
  if (!args.error().empty()) {
    std::fprintf(stderr, "Error: %s\n%s", args.error().c_str(), kBakeHelp);
    return 2;
  }
  geom::ImportOptions import_options;
  geom::BakeOptions options;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  if (!parse_number(args, "--weld-tolerance", options.weld_tolerance) ||
      !parse_number(args, "--coplanar-degrees", options.planes.coplanar_degrees) ||
      !parse_number(args, "--patch-level", import_options.patch_level) ||
      !parse_number(args, "--md3-frame", import_options.md3_frame) ||
      !parse_number(args, "--max-triangles", import_options.max_triangles) || !parse_number(args, "-j", threads))
    return 2;
  options.positions = !args.has("--no-positions");
  options.indices = !args.has("--no-indices");
  options.weld_remap = !args.has("--no-remap");
  options.face_planes = !args.has("--no-planes");
  options.topology_report = !args.has("--no-topology");
  options.esm = !args.has("--no-esm");
  options.volume = !args.has("--no-volume");
  options.adjacency = !args.has("--no-adjacency");
  options.volume_options.one_sided_closed = args.has("--one-sided-closed");
  options.scene_lights = !args.has("--no-scene-lights");
  options.topology.coplanar_degrees = options.planes.coplanar_degrees;
  for (const std::string& text : args.all("--light")) {
    float l[4];
    if (!parse_floats(text, 4, l) || !std::isfinite(l[0]) || !std::isfinite(l[1]) || !std::isfinite(l[2]) ||
        !std::isfinite(l[3]) || (l[0] == 0 && l[1] == 0 && l[2] == 0 && l[3] == 0)) {
      std::fprintf(stderr, "Error: option --light: '%s' is not X,Y,Z,W (finite, not all zero)\n", text.c_str());
      return 2;
    }
    options.lights.push_back({l[0], l[1], l[2], l[3]});
  }

  std::vector<std::string> inputs;
  if (!expand_inputs(args.positional(), inputs)) return 2;
  if (inputs.empty()) {
    std::fprintf(stderr, "Error: no input file\n%s", kBakeHelp);
    return 2;
  }
  if (!args.has("-o")) {
    std::fprintf(stderr, "Error: no output: -o FILE (one input) or -o DIR (several)\n");
    return 2;
  }
  namespace fs = std::filesystem;
  const std::string out = args.get("-o");
  std::error_code ec;
  const bool out_is_dir = fs::is_directory(out, ec) || inputs.size() > 1 || (!out.empty() && out.back() == '/');
  if (out_is_dir && !fs::is_directory(out, ec)) {
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out)) {
      std::fprintf(stderr, "Error: %s: cannot create the output directory%s%s\n", out.c_str(), ec ? ": " : "",
                   ec ? ec.message().c_str() : "");
      return 1;
    }
  }

  std::vector<Job> jobs(inputs.size());
  std::map<std::string, size_t> claimed;  // output -> first input writing it
  for (size_t i = 0; i < inputs.size(); ++i) {
    Job& job = jobs[i];
    job.input = inputs[i];
    job.output = out_is_dir ? (fs::path(out) / (stem_of(job.input) + kExtension)).string() : out;
    auto [it, fresh] = claimed.emplace(job.output, i);
    if (!fresh) job.error = job.input + ": its output " + job.output + " is also the output of " + inputs[it->second];
  }

  // Bake in parallel; each job writes only its own slot.
  std::atomic<size_t> next{0}, finished{0};
  std::mutex progress_mutex;
  const bool progress = ::isatty(2) && jobs.size() > 1;
  auto worker = [&] {
    for (size_t i; (i = next++) < jobs.size();) {
      Job& job = jobs[i];
      if (job.error.empty()) {
        job.result = geom::bake_file(job.input, job.output, options, import_options);
        job.done = job.result.ok;
        if (!job.result.ok) job.error = job.result.error;
        for (const auto& sec : job.result.sections) job.sections.push_back(info_of(sec));
        std::vector<geom::BakedSection>().swap(job.result.sections);
      }
      size_t n = ++finished;
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        std::fprintf(stderr, "\r\033[K[%zu/%zu] %s", n, jobs.size(), job.input.c_str());
        if (n == jobs.size()) std::fputs("\r\033[K", stderr);
        std::fflush(stderr);
      }
    }
  };
  threads = unsigned(std::min<size_t>(std::max(1u, threads), jobs.size()));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();

  // Report in input order.
  int failed = 0;
  std::string depfile;
  for (const Job& job : jobs) {
    if (!job.done) {
      std::fprintf(stderr, "Error: %s\n", job.error.c_str());
      ++failed;
    } else {
      depfile += make_escape(job.output) + ": " + make_escape(dependency_of(job.input)) + "\n";
      if (!args.has("--json"))
        for (const std::string& w : job.result.report.warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
    }
    if (args.has("--json")) {
      nlohmann::ordered_json j = {{"input", job.input}, {"output", job.output}, {"ok", job.done}};
      if (!job.done) {
        j["error"] = job.error;
      } else {
        uint64_t total = 0;
        j["sections"] = nlohmann::ordered_json::array();
        for (const auto& s : job.sections) {
          j["sections"].push_back(section_json(s));
          total += s.bytes;
        }
        j["section_bytes"] = total;
        j["topology"] = nlohmann::ordered_json::parse(geom::report_json(job.result.report));
        if (!job.result.silhouette.empty()) j["silhouette"] = nlohmann::ordered_json::parse(job.result.silhouette);
      }
      std::printf("%s\n", j.dump().c_str());
    } else if (args.has("-v") && job.done) {
      uint64_t total = 0;
      for (const auto& s : job.sections) total += s.bytes;
      std::printf("%s -> %s: %zu sections, %llu bytes of buffers\n", job.input.c_str(), job.output.c_str(),
                  job.sections.size(), (unsigned long long)total);
      for (const auto& s : job.sections)
        std::printf("  %-13s %-4u %-7s %10llu x %-3u = %12llu bytes\n", s.name.c_str(), s.item,
                    geom::baked::format_name(s.format), (unsigned long long)s.count, s.stride,
                    (unsigned long long)s.bytes);
      const geom::EsmStats& e = job.result.esm;
      const geom::ShadowVolumeStats& sv = job.result.volume;
      if (options.esm)
        std::printf(
            "  esm         %llu quads on %llu of %llu candidate edges (%llu coplanar, %llu concave skipped), "
            "%llu bytes against %llu naive\n",
            (unsigned long long)e.quads, (unsigned long long)e.emitted_edges, (unsigned long long)e.candidate_edges,
            (unsigned long long)e.skipped_coplanar, (unsigned long long)e.skipped_concave, (unsigned long long)e.bytes,
            (unsigned long long)e.naive_bytes);
      if (options.volume)
        std::printf(
            "  volume      %llu sides, %llu caps (%llu coplanar edges skipped), %llu bytes against %llu naive\n",
            (unsigned long long)sv.sides, (unsigned long long)sv.caps, (unsigned long long)sv.skipped_coplanar,
            (unsigned long long)sv.bytes, (unsigned long long)sv.naive_bytes);
      std::fputs(geom::report_text(job.result.report).c_str(), stdout);
    }
  }
  if (args.has("--depfile")) {
    std::string error;
    if (!geom::write_file_atomically(args.get("--depfile"), depfile, error)) {
      std::fprintf(stderr, "Error: %s\n", error.c_str());
      return 1;
    }
  }
  return failed ? 1 : 0;
}

GEOMBAKE_COMMAND("bake", "write the baked GPU buffers of each input (-o FILE or DIR)", run_bake);

}  // namespace
}  // namespace geombake
