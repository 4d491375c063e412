// geombake bake INPUT... -o OUT: import, weld, analyse and write each input as a
// baked container (geom/bake.h, format in geom/baked_reader.h). Inputs are baked
// in parallel (-j); each output is a pure function of its input and the flags,
// whatever the thread count. A failed input prints `Error: FILE: ...`, leaves no
// output file, and makes the exit status 1 while the other inputs still get baked.
//
// At pipeline scale (issue 8): inputs also come from list files (--list); a
// progress line shows on stderr when it is a terminal; a summary ends a run of
// several inputs; --depfile names each output's inputs (a glTF's external
// buffers and an archive member's archive included). Limits per input:
//   --max-triangles N  the import refuses more triangles;
//   --max-memory N     the file's size and what the importer would allocate
//                      (ImportOptions::max_bytes), then the bake's own estimate
//                      (kBakeBytesPerTriangle, measured, and per light) must fit
//                      in N bytes; and every allocation of the input's work is
//                      counted against N (its Budget, geombake/fault.h);
//   --timeout S        an input that takes longer than S seconds is refused. A
//                      watchdog (the main thread) gives up on it at once: its
//                      worker is replaced so the others go on, and it never
//                      writes its output. Its budget is cancelled, so the worker
//                      unwinds at its next allocation; once everything else is
//                      reported the process ends with _Exit instead of waiting.
// Issue 15: each input is a fault domain (any exception, bad_alloc included,
// is its `Error:`); an input that is its own output and a bad -o are refused;
// stale temporary files of a killed run are swept from the output folder;
// --json and -r hold any file name (names.h); glTF buffers outside the asset's
// folder are read only with --allow-outside-uris.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/args.h"
#include "geom/atomic_file.h"
#include "geom/bake.h"
#include "geom/version.h"
#include "geombake/bake_output.h"
#include "geombake/command.h"
#include "geombake/fault.h"
#include "geombake/flags.h"
#include "geombake/inputs.h"
#include "geombake/names.h"
#include "geombake/tree.h"

namespace geombake {
namespace {

const char* kBakeHelp =
    "usage: geombake bake [options] INPUT... -o OUT\n"
    "  Writes one baked container per input: -o FILE for one input file; -o DIR (created\n"
    "  if missing) when there are several inputs, an input is a directory or an archive,\n"
    "  --list is given, or OUT is a directory or ends in '/'. Under DIR the outputs mirror\n"
    "  the input tree and keep the input's extension: DIR/sub/pig.off.gbake for sub/pig.off\n"
    "  of a directory input (or a relative path as given); an absolute path or one outside\n"
    "  the working directory gives DIR/pig.off.gbake. INPUT may be a mesh file,\n"
    "  ARCHIVE.pk3:path/inside.bsp, ARCHIVE.pk3 for every map inside, or a directory,\n"
    "  walked recursively for every mesh file (what is skipped is said in a warning).\n"
    "  An output holds no path of the machine: the source name stored is the file's base\n"
    "  name, or its path inside the directory or archive given.\n"
    "options:\n"
    "  -o OUT              output file (one input) or directory\n"
    "  -j N, -jN           bake N inputs at once (default: the number of cores)\n"
    "  -q, --quiet         errors only on stderr (no warnings, progress or summary)\n"
    "  --force             rewrite outputs whose bytes would not change (default: left\n"
    "                      untouched, mtime kept; with Ninja use `restat = 1`)\n"
    "  -r FILE             write the JSON report of the whole run to FILE\n"
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
    "                      W = 1 a point, W = 0 a direction towards X,Y,Z, other W the point\n"
    "                      X/W,Y/W,Z/W; input coordinates)\n"
    "  --no-scene-lights   no exact volumes for the file's KHR_lights_punctual lights\n"
    "  --weld-tolerance T  merge vertices closer than T (default 0: exact positions)\n"
    "  --coplanar-degrees D  normals closer than D degrees make a coplanar edge (default 0.01)\n"
    "  --patch-level N     Bezier patch tessellation of Quake 3 maps (default 4)\n"
    "  --md3-frame N       MD3 frame to import (default 0)\n"
    "  --max-triangles N   refuse inputs with more triangles\n"
    "  --max-memory N      refuse inputs that would need more than N bytes (suffix K, M or G): the\n"
    "                      estimate first, then every allocation of the input's work counted\n"
    "  --timeout S         refuse inputs that take longer than S seconds (the others go on)\n"
    "  --list FILE         more inputs, one per line (blank lines and # comments skipped)\n"
    "  --allow-outside-uris  read glTF buffers outside the asset's folder too (default: refused)\n"
    "  Warnings and errors print as each input finishes; a progress line, cut to the\n"
    "  terminal's width, shows on stderr when it is a terminal; several inputs end with a summary.\n";

constexpr const char* kExtension = ".gbake";

// The file an input depends on: the archive for an archive member.
std::string dependency_of(const std::string& input) {
  for (const char* ext : {".pk3:", ".zip:"}) {
    size_t at = input.find(ext);
    if (at != std::string::npos) return input.substr(0, at + 4);
  }
  return input;
}

// What baking one triangle costs at the peak, beyond the imported scene: the
// weld, the topology's edge table, the planes, the ESM quads, the volume, the
// adjacency, their sections and the serialized file. Measured (peak RSS of
// `geombake bake -j 1` less the 12 MB of an empty run, over the triangles, the
// import included): 2CylinderEngine.glb (121,496 triangles) 550 B, OpenArena's
// oa_ctf2 (19,193) 370 B; rounded up with a margin. The process's own ~12 MB
// is not counted.
constexpr uint64_t kBakeBytesPerTriangle = 1024;
// And per triangle per exact light volume (--light, KHR_lights_punctual): at
// most a side quad per edge and two caps per triangle, 16-byte vertices, as a
// lower bound (the budget of fault.h counts the real allocations).
constexpr uint64_t kBakeBytesPerTrianglePerLight = 256;

// Reads a list file's inputs; false (after an `Error:` line) if it cannot be read.
bool read_list(const std::string& path, std::vector<std::string>& inputs) {
  std::ifstream f(path);
  if (!f) {
    std::fprintf(stderr, "Error: %s: cannot read the list file\n", path.c_str());
    return false;
  }
  for (std::string line; std::getline(f, line);) {
    const size_t a = line.find_first_not_of(" \t\r"), b = line.find_last_not_of(" \t\r");
    if (a == std::string::npos || line[a] == '#') continue;
    inputs.push_back(line.substr(a, b - a + 1));
  }
  return true;
}

// The non-fatal geometry problems of a baked input, as one warning ("" if none).
std::string geometry_warning(const std::string& input, const geom::TopologyStats& t) {
  std::string w;
  auto add = [&](uint64_t n, const char* what) {
    if (n) w += (w.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(t.collapsed_triangles, "collapsed triangles");
  add(t.zero_area_triangles, "zero-area triangles");
  add(t.non_manifold_edges, "non-manifold edges");
  add(t.inconsistent_edges, "edges with inconsistent winding");
  add(t.duplicate_triangles, "duplicate triangles");
  return w.empty() ? w : input + ": " + w + " (baked; counted in the report)";
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

// `crc`: the section's CRC-32C as the writer computed it (never a second time);
// the section's bytes are gone (written as made), its count x stride is its size.
SectionInfo info_of(const geom::BakedSection& s, uint32_t crc) {
  return {s.name, s.type, s.format, s.stride, s.item, s.count, s.count * s.stride, crc};
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
  std::string name;                  // the source name stored in the output (geombake/tree.h)
  geom::BakeResult result;           // without its sections' bytes once written
  std::vector<SectionInfo> sections;
  std::vector<std::string> warnings;  // the importer's, naming the input as given
  Written written = Written::Failed;
  bool done = false;
  // Watchdog state (--timeout): kPending -> kRunning -> kWriting -> kFinished,
  // or kRunning -> kTimedOut (set by the watchdog: the worker's result is dropped).
  std::atomic<int> state{0};
  std::atomic<int64_t> started_ns{0};  // steady clock, when state became kRunning
  size_t worker = 0;                   // the worker thread that runs it
  Budget budget;                       // its memory (--max-memory); cancelled when it times out
};
enum { kPending, kRunning, kWriting, kFinished, kTimedOut };

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// One input, start to end: import (within the limits), the memory estimate,
// the bake, then the write, which happens only if the watchdog has not given
// up on the job (kRunning -> kWriting) and the time limit still holds.
struct Outcome {
  geom::BakeResult result;
  std::string error;
  std::vector<SectionInfo> sections;
  std::vector<std::string> warnings;
  Written written = Written::Failed;
};

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  if (from.empty() || from == to) return;
  for (size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
    text.replace(at, from.size(), to);
}

struct WriteOptions {
  bool force = false;         // --force
  bool make_parents = false;  // -o DIR: outputs mirrored into subdirectories
};

Outcome bake_unguarded(Job& job, const geom::BakeOptions& options, const geom::ImportOptions& import_options,
                       uint64_t max_memory, double timeout, const WriteOptions& write) {
  Outcome o;
  geom::ImportResult imported = geom::import_file(job.input, import_options);
  if (!imported.ok) {
    o.error = imported.error;
    return o;
  }
  if (max_memory) {
    // The estimate refuses at once what cannot fit; the budget (fault.h) bounds the rest.
    const uint64_t tris = imported.scene.triangle_count();
    const uint64_t lights = options.lights.size() + (options.scene_lights ? imported.scene.lights.size() : 0);
    const uint64_t need = tris * kBakeBytesPerTriangle + lights * tris * kBakeBytesPerTrianglePerLight;
    if (need > max_memory) {
      o.error = job.input + ": baking " + std::to_string(tris) + " triangles" +
                (lights ? " with " + std::to_string(lights) + " exact light volumes" : std::string()) +
                " needs about " + std::to_string(need) + " bytes, over the limit of " + std::to_string(max_memory) +
                " (--max-memory)";
      return o;
    }
  }
  // The output holds the stored name, never the path as typed (hermetic bytes):
  // the importer's warnings are stored with it too, and shown with the path.
  o.warnings = imported.scene.warnings;
  for (std::string& w : imported.scene.warnings) replace_all(w, job.input, job.name);
  std::string error;
  if (write.make_parents && !make_parent_directories(job.output, error)) {
    o.error = job.input + ": cannot write " + job.output + ": " + error;
    return o;
  }
  // Each section goes to the output (a temporary file until finished) as soon
  // as it is made, its buffer freed: the bake's peak holds no finished section.
  geom::BakedFileWriter writer;
  writer.open(job.output, !write.force);  // an output there: compared as it comes, left untouched if the same
  o.result = geom::bake_scene(std::move(imported.scene), job.name, options, writer);  // its triangles freed once welded
  imported = geom::ImportResult();
  if (!o.result.ok) {
    o.error = o.result.error;
    if (!writer.error().empty())
      o.error = job.input + ": cannot write " + job.output + ": " + writer.error();
    else if (o.error.rfind(job.name + ":", 0) == 0)
      o.error = job.input + o.error.substr(job.name.size());
    return o;
  }
  int expected = kRunning;
  if (timeout > 0 && double(now_ns() - job.started_ns.load()) * 1e-9 > timeout) return o;  // the caller times it out
  if (!job.state.compare_exchange_strong(expected, kWriting)) return o;                    // given up on: write nothing
  std::vector<uint32_t> crcs;
  bool unchanged = false;
  if (writer.finish(unchanged, &crcs)) {
    o.written = unchanged ? Written::Unchanged : Written::New;
  } else {
    o.result.ok = false;
    o.error = job.input + ": cannot write " + job.output + ": " + writer.error();
  }
  crcs.resize(o.result.sections.size(), 0);
  for (size_t i = 0; i < o.result.sections.size(); ++i) o.sections.push_back(info_of(o.result.sections[i], crcs[i]));
  std::vector<geom::BakedSection>().swap(o.result.sections);
  return o;
}

// bake_unguarded() as a fault domain (fault.h): whatever it throws, bad_alloc
// and its --max-memory budget included, is this input's error.
Outcome bake_one(Job& job, const geom::BakeOptions& options, const geom::ImportOptions& import_options,
                 uint64_t max_memory, double timeout, const WriteOptions& write) {
  Outcome o;
  job.budget.limit = max_memory;
  std::string error = guarded(job.input, job.budget, [&] {
    o = bake_unguarded(job, options, import_options, max_memory, timeout, write);
    return o.error;
  });
  if (!error.empty()) o = Outcome(), o.error = error;
  return o;
}

// One input's entry in --json and the -r report.
nlohmann::ordered_json job_json(const Job& job) {
  nlohmann::ordered_json j = {{"input", job.input}, {"output", job.output}, {"ok", job.done}};
  if (!job.done) {
    j["error"] = job.error;
    return j;
  }
  j["written"] = job.written == Written::New;
  j["warnings"] = job.warnings;
  uint64_t total = 0;
  j["sections"] = nlohmann::ordered_json::array();
  for (const auto& s : job.sections) {
    j["sections"].push_back(section_json(s));
    total += s.bytes;
  }
  j["section_bytes"] = total;
  j["topology"] = json_text(geom::report_json(job.result.report));  // any name in it (names.h)
  if (!job.result.silhouette.empty()) j["silhouette"] = json_text(job.result.silhouette);
  return j;
}

// -v: sections, bytes and topology of one baked input on stdout.
void print_verbose(const Job& job, const geom::BakeOptions& options) {
  uint64_t total = 0;
  for (const auto& s : job.sections) total += s.bytes;
  std::printf("%s -> %s: %zu sections, %llu bytes of buffers%s\n", job.input.c_str(), job.output.c_str(),
              job.sections.size(), (unsigned long long)total,
              job.written == Written::Unchanged ? " (unchanged, left untouched)" : "");
  for (const auto& s : job.sections)
    std::printf("  %-13s %-4u %-7s %10llu x %-3u = %12llu bytes\n", s.name.c_str(), s.item,
                geom::baked::format_name(s.format), (unsigned long long)s.count, s.stride, (unsigned long long)s.bytes);
  const geom::EsmStats& e = job.result.esm;
  const geom::ShadowVolumeStats& sv = job.result.volume;
  if (options.pipeline.esm)
    std::printf(
        "  esm         %llu quads on %llu of %llu candidate edges (%llu coplanar, %llu concave skipped), "
        "%llu bytes against %llu naive\n",
        (unsigned long long)e.quads, (unsigned long long)e.emitted_edges, (unsigned long long)e.candidate_edges,
        (unsigned long long)e.skipped_coplanar, (unsigned long long)e.skipped_concave, (unsigned long long)e.bytes,
        (unsigned long long)e.naive_bytes);
  if (options.pipeline.volume)
    std::printf("  volume      %llu sides, %llu caps (%llu coplanar edges skipped), %llu bytes against %llu naive\n",
                (unsigned long long)sv.sides, (unsigned long long)sv.caps, (unsigned long long)sv.skipped_coplanar,
                (unsigned long long)sv.bytes, (unsigned long long)sv.naive_bytes);
  std::fputs(geom::report_text(job.result.report).c_str(), stdout);
}

// "-j4" -> "-j", "4" (as make and ninja take it); anything else as it is.
std::vector<std::string> split_jobs_flag(const std::vector<std::string>& argv) {
  std::vector<std::string> out;
  for (const std::string& a : argv) {
    if (a == "--") {
      out.insert(out.end(), &a, argv.data() + argv.size());
      break;
    }
    if (a.size() > 2 && a.compare(0, 2, "-j") == 0 && a.find_first_not_of("0123456789", 2) == std::string::npos) {
      out.push_back("-j");
      out.push_back(a.substr(2));
    } else {
      out.push_back(a);
    }
  }
  return out;
}

int run_bake(const std::vector<std::string>& argv) {
  constexpr unsigned kShared = kImportFlags | kPipelineFlags | kLimitFlags;
  cli::Args args(split_jobs_flag(argv),
                 with_shared_flags({"--json", "-v", "--help", "-h", "--no-positions", "--no-indices", "--no-remap",
                                    "--no-planes", "--no-topology", "--no-esm", "--no-volume", "--no-adjacency",
                                    "--no-scene-lights", "--one-sided-closed", "-q", "--quiet", "--force"},
                                   kShared, false),
                 with_shared_flags({"-o", "-j", "--depfile", "--light", "--list", "-r"}, kShared, true));
  if (args.has("--help") || args.has("-h")) {
    std::printf("geombake %s\n", GEOM_VERSION);
    std::fputs(kBakeHelp, stdout);
    return 0;
  }
  if (!args.error().empty()) {
    std::fprintf(stderr, "Error: %s\n%s", args.error().c_str(), kBakeHelp);
    return 2;
  }
  geom::keep_memory_across_bakes();  // each input reuses the pages of the ones before
  SharedFlags shared;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  if (!parse_shared_flags(args, kShared, shared) || !parse_number(args, "-j", threads)) return 2;
  const geom::ImportOptions& import_options = shared.import;
  const uint64_t max_memory = shared.max_memory;
  const double timeout = shared.timeout;
  geom::BakeOptions options;
  options.pipeline = shared.pipeline;
  options.positions = !args.has("--no-positions");
  options.indices = !args.has("--no-indices");
  options.weld_remap = !args.has("--no-remap");
  options.pipeline.face_planes = !args.has("--no-planes");
  options.topology_report = !args.has("--no-topology");
  options.pipeline.esm = !args.has("--no-esm");
  options.pipeline.volume = !args.has("--no-volume");
  options.pipeline.adjacency = !args.has("--no-adjacency");
  options.pipeline.volume_options.one_sided_closed = args.has("--one-sided-closed");
  options.scene_lights = !args.has("--no-scene-lights");
  for (const std::string& text : args.all("--light")) {
    float l[4];
    if (!cli::parse_floats(text, 4, l) || !std::isfinite(l[0]) || !std::isfinite(l[1]) || !std::isfinite(l[2]) ||
        !std::isfinite(l[3]) || (l[0] == 0 && l[1] == 0 && l[2] == 0 && l[3] == 0)) {
      std::fprintf(stderr, "Error: option --light: '%s' is not X,Y,Z,W (finite, not all zero)\n", text.c_str());
      return 2;
    }
    const double h[4] = {l[0], l[1], l[2], l[3]};
    options.lights.push_back(geom::light_from_homogeneous(h));
  }

  std::vector<std::string> named = args.positional();
  for (const std::string& list : args.all("--list"))
    if (!read_list(list, named)) return 2;
  const bool quiet = args.has("-q") || args.has("--quiet");
  std::vector<TreeInput> inputs;
  std::vector<std::string> skipped;
  bool folder = !args.all("--list").empty();
  if (!expand_tree_inputs(named, inputs, skipped, folder)) return 2;
  if (!quiet)
    for (const std::string& w : skipped) std::fprintf(stderr, "Warning: %s\n", w.c_str());
  if (inputs.empty()) {
    std::fprintf(stderr, "Error: no input file%s\n%s", named.empty() ? "" : " (no mesh file in the inputs given)",
                 named.empty() ? kBakeHelp : "");
    return 2;
  }
  if (!args.has("-o")) {
    std::fprintf(stderr, "Error: no output: -o FILE (one input file) or -o DIR (several, or a directory)\n");
    return 2;
  }
  namespace fs = std::filesystem;
  const std::string out = args.get("-o");
  if (out.empty()) {
    std::fprintf(stderr, "Error: -o: the output path is empty\n");
    return 2;
  }
  std::error_code ec;
  const bool out_is_dir =
      fs::is_directory(out, ec) || named.size() > 1 || folder || (!out.empty() && out.back() == '/');
  if (out_is_dir && !fs::is_directory(out, ec)) {
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out)) {
      std::fprintf(stderr, "Error: %s: cannot create the output directory%s%s\n", out.c_str(), ec ? ": " : "",
                   ec ? ec.message().c_str() : "");
      return 1;
    }
  }
  if (!out_is_dir) {
    const std::string problem = output_problem(out);
    if (!problem.empty()) {
      std::fprintf(stderr, "Error: -o %s: %s\n", out.c_str(), problem.c_str());
      return 2;
    }
  }
  // Temporary files a killed run left in the output folder (geom/atomic_file.h).
  const size_t slash = out.find_last_of('/');
  geom::remove_stale_temp_files(out_is_dir ? out : slash == std::string::npos ? "." : out.substr(0, slash + 1));
  WriteOptions write;
  write.force = args.has("--force");
  write.make_parents = out_is_dir;

  std::vector<Job> jobs(inputs.size());
  std::map<std::string, size_t> claimed;  // output -> first input writing it
  for (size_t i = 0; i < inputs.size(); ++i) {
    Job& job = jobs[i];
    job.input = inputs[i].path;
    job.name = inputs[i].name;
    job.output = out_is_dir ? (fs::path(out) / (inputs[i].rel + kExtension)).string() : out;
    auto [it, fresh] = claimed.emplace(job.output, i);
    if (!fresh)
      job.error = job.input + ": its output " + job.output + " is also the output of " + jobs[it->second].input +
                  " (give their folder or relative paths: outputs mirror the input tree)";
    if (job.error.empty() && same_file(dependency_of(job.input), job.output))
      job.error = job.input + ": is its own output (-o " + job.output + "): not baked";
  }

  // Bake in parallel; each job writes only its own slot. The main thread is
  // the watchdog: it gives up on jobs over --timeout and starts a worker in
  // place of each one it gives up on.
  const auto t0 = std::chrono::steady_clock::now();
  std::atomic<size_t> next{0};
  size_t finished = 0, timed_out = 0;  // under `mutex`
  std::mutex mutex;
  std::condition_variable changed;
  const bool progress = !quiet && ::isatty(2) && jobs.size() > 1;
  const bool json = args.has("--json");
  // As each input finishes (under `mutex`): its error or warnings, then the progress line.
  auto announce = [&](const Job& job) {
    if (progress) std::fputs("\r\033[K", stderr);
    if (!job.error.empty()) {
      std::fprintf(stderr, "Error: %s\n", job.error.c_str());
    } else if (!quiet && !json && job.done) {
      for (const std::string& w : job.warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
      const std::string g = geometry_warning(job.input, job.result.report.stats);
      if (!g.empty()) std::fprintf(stderr, "Warning: %s\n", g.c_str());
    }
    if (progress) {
      const std::string count = "[" + std::to_string(finished) + "/" + std::to_string(jobs.size()) + "] ";
      const size_t width = size_t(std::max(terminal_width(2) - 1, 8));
      std::fputs(fit_line(count + job.input, width, count.size()).c_str(), stderr);
      if (finished == jobs.size()) std::fputs("\r\033[K", stderr);
    }
    std::fflush(stderr);
  };
  auto worker = [&](size_t self) {
    for (size_t i; (i = next++) < jobs.size();) {
      Job& job = jobs[i];
      Outcome o;
      if (job.error.empty()) {
        job.worker = self;
        job.started_ns = now_ns();
        job.state = kRunning;
        o = bake_one(job, options, import_options, max_memory, timeout, write);
      }
      std::lock_guard<std::mutex> lock(mutex);
      if (job.state == kTimedOut) return;  // given up on: a new worker took this one's place
      if (job.state == kRunning && timeout > 0 && double(now_ns() - job.started_ns) * 1e-9 > timeout && o.error.empty())
        o.error = job.input + ": timed out after " + seconds_text(timeout) + " s (--timeout)";
      job.state = kFinished;
      job.result = std::move(o.result);
      job.sections = std::move(o.sections);
      job.warnings = std::move(o.warnings);
      job.written = o.written;
      if (job.error.empty()) job.error = o.error;
      job.done = job.error.empty() && job.result.ok;
      ++finished;
      announce(job);
      changed.notify_all();
    }
  };
  threads = unsigned(std::min<size_t>(std::max(1u, threads), jobs.size()));
  std::vector<std::thread> pool;
  std::vector<bool> stuck;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker, size_t(t)), stuck.push_back(false);
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (finished < jobs.size()) {
      changed.wait_for(lock, std::chrono::milliseconds(timeout > 0 ? 10 : 200));
      if (timeout <= 0) continue;
      const int64_t now = now_ns();
      for (Job& job : jobs) {
        int expected = kRunning;
        if (job.state != kRunning || double(now - job.started_ns) * 1e-9 <= timeout ||
            !job.state.compare_exchange_strong(expected, kTimedOut))
          continue;
        job.error = job.input + ": timed out after " + seconds_text(timeout) + " s (--timeout)";
        job.budget.cancelled = true;  // its next allocation throws: the work unwinds, its memory is freed
        ++finished, ++timed_out;
        announce(job);
        stuck[job.worker] = true;
        if (next < jobs.size()) pool.emplace_back(worker, pool.size()), stuck.push_back(false);
      }
    }
  }
  for (size_t t = 0; t < pool.size(); ++t) stuck[t] ? pool[t].detach() : pool[t].join();

  // Report in input order.
  int failed = 0;
  size_t unchanged = 0;
  std::string depfile, depfile_error;
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  for (const Job& job : jobs) {
    if (!job.done) {
      ++failed;
    } else {
      unchanged += job.written == Written::Unchanged;
      std::string rule, escaped;
      bool ok = make_escape(job.output, escaped);
      rule = escaped + ":";
      for (const std::string& d : geom::input_dependencies(job.input))
        ok = make_escape(d, escaped) && ok, rule += " " + escaped;
      if (ok)
        depfile += rule + "\n";
      else if (args.has("--depfile"))
        depfile_error += "Error: " + job.input +
                         ": a newline in its name or its output's cannot be written in a "
                         "depfile (Make has no escape for it)\n";
    }
    if (json || args.has("-r")) {
      nlohmann::ordered_json j = job_json(job);
      if (json) std::printf("%s\n", dump_json(j).c_str());  // any name (names.h)
      if (args.has("-r")) results.push_back(std::move(j));
    }
    if (!json && args.has("-v") && job.done) print_verbose(job, options);
  }
  int status = failed ? 1 : 0;
  if (!depfile_error.empty()) std::fputs(depfile_error.c_str(), stderr), status = 1;
  if (args.has("--depfile")) {
    std::string error;
    if (!geom::write_file_atomically(args.get("--depfile"), depfile, error)) {
      std::fprintf(stderr, "Error: %s\n", error.c_str());
      status = 1;
    }
  }
  if (args.has("-r")) {
    nlohmann::ordered_json report = {{"geombake", GEOM_VERSION},     {"output", out},
                                     {"inputs", jobs.size()},        {"baked", jobs.size() - size_t(failed)},
                                     {"unchanged", unchanged},       {"failed", failed},
                                     {"timed_out", timed_out},       {"skipped", skipped},
                                     {"results", std::move(results)}};
    std::string error;
    if (!geom::write_file_atomically(args.get("-r"), dump_json(report, 1) + "\n", error)) {
      std::fprintf(stderr, "Error: %s\n", error.c_str());
      status = 1;
    }
  }
  if (!quiet && (jobs.size() > 1 || args.has("-v"))) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "geombake bake: %zu baked, %d failed of %zu inputs", jobs.size() - size_t(failed), failed,
                 jobs.size());
    if (unchanged) std::fprintf(stderr, " (%zu unchanged, left untouched)", unchanged);
    if (timed_out) std::fprintf(stderr, " (%zu timed out)", timed_out);
    std::fprintf(stderr, " in %.2f s with %u threads\n", seconds, threads);
  }
  if (timed_out) {  // workers still busy with abandoned inputs cannot be joined: end now
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(status);
  }
  return status;
}

GEOMBAKE_COMMAND("bake", "write the baked GPU buffers of each input (-o FILE or DIR)", run_bake);

}  // namespace
}  // namespace geombake
