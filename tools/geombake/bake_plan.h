// `geombake bake`'s plan, everything decided before any input is read: the
// flags parsed into a BakeConfig, each input's output path, and the checks
// that make it safe as a build step: no output (a baked file, -r, --depfile)
// is an input or a file an input reads (after resolving symlinks, `..` and
// hard links), an existing mesh file or archive that this run does not read,
// or another output; and every output folder is writable.
#pragma once
#include <string>
#include <vector>

#include "geom/bake.h"
#include "geom/import.h"
#include "geombake/bake_job.h"
#include "geombake/tree.h"

namespace geombake {

enum class Progress { Auto, Plain, None };  // --progress=tty|plain|none (Auto: a line when stderr is a terminal)

struct BakeConfig {
  geom::BakeOptions options;
  geom::ImportOptions import;
  JobLimits limits;
  WriteOptions write;
  unsigned threads = 1;
  bool quiet = false, json = false, verbose = false, prune = false, stable = false;
  Progress progress = Progress::Auto;
  std::string out;  // -o
  bool has_out = false, out_is_dir = false;
  std::string report, depfile, depfile_target;  // -r, --depfile, --depfile-target ("": not given)
  std::vector<std::string> named;               // the inputs as given (arguments, then --list files)
  std::vector<std::string> skipped;             // what the tree walk skipped, one warning each
};

// Parses `argv` (the bake subcommand's arguments) into `config`. Returns -1 to
// go on, else the exit status to end with (0 after --help, 2 after an `Error:`).
// `help` is the text --help prints.
int parse_bake_flags(const std::vector<std::string>& argv, const char* help, BakeConfig& config);

// The CPUs this process may run on: its affinity mask (sched_getaffinity), cut
// to the cgroup's CPU quota (cpu.max, or cpu.cfs_quota_us / cpu.cfs_period_us)
// rounded up; at least 1.
unsigned available_cpus();

// Decides whether -o names a file or a directory (`folder`: an input is a
// directory or a whole archive) and checks it; returns -1 to go on, else 2
// after an `Error:` line. Creates nothing.
int plan_output(BakeConfig& config, bool folder);

// One job per input, with its output path (-o FILE, or DIR/rel.gbake); an
// input whose output another input already claims gets its error here.
void plan_jobs(const std::vector<TreeInput>& inputs, const BakeConfig& config, std::vector<Job>& jobs);

// The checks above, with an `Error:` line per problem; false if any. Creates
// nothing.
bool check_outputs(const std::vector<Job>& jobs, const BakeConfig& config);

// The same checks for a command that writes one file `path` (given with
// `flag`, as `info -o`) from `inputs`.
bool check_output_file(const std::vector<std::string>& inputs, const std::string& flag, const std::string& path);

}  // namespace geombake
