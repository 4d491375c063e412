// `geombake bake`'s plan (bake_plan.h).
#include "geombake/bake_plan.h"

#include <fcntl.h>
#include <sched.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <thread>

#include "cli/args.h"
#include "geom/focus.h"
#include "geom/version.h"
#include "geombake/flags.h"
#include "geombake/inputs.h"
#include "geombake/names.h"

namespace geombake {
namespace fs = std::filesystem;
namespace {

constexpr const char* kExtension = ".gbake";

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

// Reads a list file's inputs ("-": standard input); false (after an `Error:`
// line) if it cannot be read.
bool read_list(const std::string& path, std::vector<std::string>& inputs) {
  std::ifstream file;
  if (path != "-") file.open(path);
  std::istream& in = path == "-" ? std::cin : file;
  if (!in) {
    std::fprintf(stderr, "Error: %s: cannot read the list file\n", path.c_str());
    return false;
  }
  for (std::string line; std::getline(in, line);) {
    const size_t a = line.find_first_not_of(" \t\r"), b = line.find_last_not_of(" \t\r");
    if (a == std::string::npos || line[a] == '#') continue;
    inputs.push_back(line.substr(a, b - a + 1));
  }
  return true;
}

// The buffers asked for (--no-*) and the static lights (--light); false after an `Error:`.
bool parse_bake_options(const cli::Args& args, const SharedFlags& shared, geom::BakeOptions& options) {
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
  if (!args.has("--no-caster-hull")) options.caster_hull = geom::focus_caster_hull;  // the caster_hull section
  for (const std::string& text : args.all("--light")) {
    float l[4];
    if (!cli::parse_floats(text, 4, l) || !std::isfinite(l[0]) || !std::isfinite(l[1]) || !std::isfinite(l[2]) ||
        !std::isfinite(l[3]) || (l[0] == 0 && l[1] == 0 && l[2] == 0 && l[3] == 0)) {
      std::fprintf(stderr, "Error: option --light: '%s' is not X,Y,Z,W (finite, not all zero)\n", text.c_str());
      return false;
    }
    const double h[4] = {l[0], l[1], l[2], l[3]};
    options.lights.push_back(geom::light_from_homogeneous(h));
  }
  return true;
}

// The run's own settings: outputs, reports, progress; false after an `Error:`.
bool parse_run_flags(const cli::Args& args, BakeConfig& c) {
  c.quiet = args.has("-q") || args.has("--quiet");
  c.json = args.has("--json");
  c.verbose = args.has("-v");
  c.prune = args.has("--prune");
  c.stable = args.has("--stable-report");
  c.write.force = args.has("--force");
  if (args.has("-r")) c.report = args.get("-r");
  if (args.has("--depfile")) c.depfile = args.get("--depfile");
  if (args.has("--depfile-target")) c.depfile_target = args.get("--depfile-target");
  const struct {
    const char* flag;
    std::string* value;
  } paths[] = {{"-r", &c.report}, {"--depfile", &c.depfile}, {"--depfile-target", &c.depfile_target}};
  for (const auto& p : paths)
    if (args.has(p.flag) && p.value->empty()) {
      std::fprintf(stderr, "Error: option %s: the path is empty\n", p.flag);
      return false;
    }
  if (!c.depfile_target.empty() && c.depfile.empty()) {
    std::fprintf(stderr, "Error: option --depfile-target: names the target of --depfile, which is not given\n");
    return false;
  }
  if (args.has("--progress")) {
    const std::string p = args.get("--progress");
    if (p != "tty" && p != "plain" && p != "none") {
      std::fprintf(stderr, "Error: option --progress: '%s' is not tty, plain or none\n", p.c_str());
      return false;
    }
    c.progress = p == "plain" ? Progress::Plain : p == "none" ? Progress::None : Progress::Auto;
  }
  return true;
}

}  // namespace

int parse_bake_flags(const std::vector<std::string>& argv, const char* help, BakeConfig& config) {
  constexpr unsigned kShared = kImportFlags | kPipelineFlags | kLimitFlags;
  cli::Args args(
      split_jobs_flag(argv),
      with_shared_flags({"--json",
                         "-v",
                         "--help",
                         "-h",
                         "--no-positions",
                         "--no-indices",
                         "--no-remap",
                         "--no-caster-hull",
                         "--no-planes",
                         "--no-topology",
                         "--no-esm",
                         "--no-volume",
                         "--no-adjacency",
                         "--no-scene-lights",
                         "--one-sided-closed",
                         "-q",
                         "--quiet",
                         "--force",
                         "--prune",
                         "--stable-report"},
                        kShared, false),
      with_shared_flags({"-o", "-j", "--depfile", "--depfile-target", "--light", "--list", "-r", "--progress"}, kShared,
                        true));
  if (args.has("--help") || args.has("-h")) {
    std::printf("geombake %s\n", GEOM_VERSION);
    std::fputs(help, stdout);
    return 0;
  }
  if (!args.error().empty()) {
    std::fprintf(stderr, "Error: %s\n%s", args.error().c_str(), help);
    return 2;
  }
  SharedFlags shared;
  config.threads = available_cpus();
  if (!parse_shared_flags(args, kShared, shared) || !parse_number(args, "-j", config.threads)) return 2;
  config.import = shared.import;
  config.limits.max_memory = shared.max_memory;
  config.limits.timeout = shared.timeout;
  if (!parse_bake_options(args, shared, config.options) || !parse_run_flags(args, config)) return 2;
  config.named = args.positional();
  for (const std::string& list : args.all("--list"))
    if (!read_list(list, config.named)) return 2;
  config.has_out = args.has("-o");
  if (config.has_out) config.out = args.get("-o");
  config.out_is_dir = !args.all("--list").empty();
  return -1;
}

unsigned available_cpus() {
  unsigned n = 0;
  cpu_set_t set;
  if (::sched_getaffinity(0, sizeof set, &set) == 0) n = unsigned(CPU_COUNT(&set));
  if (n == 0) n = std::max(1u, std::thread::hardware_concurrency());
  // The cgroup's quota: v2 cpu.max ("max 100000" or "QUOTA PERIOD"), else v1.
  std::string group;
  std::ifstream self("/proc/self/cgroup");
  for (std::string line; std::getline(self, line);)
    if (line.rfind("0::", 0) == 0) group = line.substr(3);
  double quota = -1, period = 0;
  for (const std::string& dir : {"/sys/fs/cgroup" + group, std::string("/sys/fs/cgroup")}) {
    std::ifstream max(dir + "/cpu.max");
    std::string q;
    if (max >> q >> period) {
      quota = q == "max" ? -1 : std::atof(q.c_str());
      break;
    }
  }
  if (period == 0) {
    std::ifstream q("/sys/fs/cgroup/cpu/cpu.cfs_quota_us"), p("/sys/fs/cgroup/cpu/cpu.cfs_period_us");
    if (!(q >> quota && p >> period)) quota = -1;
  }
  if (quota > 0 && period > 0) n = std::min(n, std::max(1u, unsigned(std::ceil(quota / period))));
  return std::max(1u, n);
}

int plan_output(BakeConfig& config, bool folder) {
  if (!config.has_out) {
    std::fprintf(stderr, "Error: no output: -o FILE (one input file) or -o DIR (several, or a directory)\n");
    return 2;
  }
  const std::string& out = config.out;
  if (out.empty()) {
    std::fprintf(stderr, "Error: -o: the output path is empty\n");
    return 2;
  }
  std::error_code ec;
  config.out_is_dir =
      config.out_is_dir || folder || fs::is_directory(out, ec) || config.named.size() > 1 || out.back() == '/';
  if (!config.out_is_dir) {
    const std::string problem = output_problem(out);
    if (!problem.empty()) {
      std::fprintf(stderr, "Error: -o %s: %s\n", out.c_str(), problem.c_str());
      return 2;
    }
  } else if (fs::exists(out, ec) && !fs::is_directory(out, ec)) {
    std::fprintf(stderr, "Error: -o %s: not a directory, and the outputs of several inputs need one\n", out.c_str());
    return 2;
  }
  return -1;
}

void plan_jobs(const std::vector<TreeInput>& inputs, const BakeConfig& config, std::vector<Job>& jobs) {
  std::vector<Job>(inputs.size()).swap(jobs);
  std::map<std::string, size_t> claimed;  // output -> first input writing it
  for (size_t i = 0; i < inputs.size(); ++i) {
    Job& job = jobs[i];
    job.input = inputs[i].path;
    job.name = inputs[i].name;
    job.reads = geom::input_dependencies(job.input);
    job.output = config.out_is_dir ? (fs::path(config.out) / (inputs[i].rel + kExtension)).string() : config.out;
    auto [it, fresh] = claimed.emplace(job.output, i);
    if (!fresh) {
      job.error = job.input + ": its output " + job.output + " is also the output of " + jobs[it->second].input +
                  " (give their folder or relative paths: outputs mirror the input tree)";
      job.kind = ErrorKind::OutputConflict;
    }
  }
}

}  // namespace geombake
