// geombake bake INPUT... -o OUT: import, weld, analyse and write each input as a
// baked container (geom/bake.h, format in geom/baked_reader.h), as a build step
// can trust it (docs/build-step.md): the plan and its checks before any work
// (bake_plan.h), the inputs baked in parallel, each a fault domain with its
// limits (bake_schedule.h, bake_job.h), then no stale output, the depfile and
// the reports (bake_report.h). Each output is a pure function of its input and
// the flags, whatever the thread count, the path or the machine.
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "geom/atomic_file.h"
#include "geom/bake.h"
#include "geombake/bake_plan.h"
#include "geombake/bake_report.h"
#include "geombake/bake_schedule.h"
#include "geombake/command.h"
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
    "  -j N, -jN           bake N inputs at once (default: the CPUs this process may use: its\n"
    "                      affinity mask and its cgroup's CPU limit)\n"
    "  -q, --quiet         errors only on stderr (no warnings, progress or summary)\n"
    "  --force             rewrite outputs whose bytes would not change (default: left\n"
    "                      untouched, mtime kept; with Ninja use `restat = 1`)\n"
    "  -r FILE             write the JSON report of the whole run to FILE: per input ok, error,\n"
    "                      error_kind, sha256, the files it read (reads), seconds, written\n"
    "  --stable-report     leave out of -r and --json what changes between runs on the same\n"
    "                      inputs (written, seconds, unchanged): the same bytes every run\n"
    "  -v                  sections, bytes and topology of each input on stdout\n"
    "  --json              one JSON object per input, one per line, on stdout\n"
    "  --depfile FILE      write a depfile for Make and Ninja: OUTPUT: FILES READ per input,\n"
    "                      failed inputs included\n"
    "  --depfile-target NAME  one depfile rule NAME: FILES READ of every input (gcc's -MT; a\n"
    "                      stamp file that Make can date)\n"
    "  --prune             remove the .gbake files under -o DIR that no input of this run maps to\n"
    "  --progress MODE     tty (default: a line on stderr when it is a terminal), plain (a line\n"
    "                      at most every 5 s, for CI logs), none\n"
    "  --no-positions      omit the welded positions\n"
    "  --no-indices        omit the welded index buffer\n"
    "  --no-remap          omit the weld remap (source vertex -> welded vertex)\n"
    "  --no-caster-hull    omit the casters' convex hull (the focus's per-frame input)\n"
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
    "  --list FILE         more inputs, one per line (blank lines and # comments skipped; - reads\n"
    "                      standard input)\n"
    "  --allow-outside-uris  read glTF buffers outside the asset's folder too (default: refused)\n"
    "  Warnings and errors print as each input finishes; a progress line, cut to the\n"
    "  terminal's width, shows on stderr when it is a terminal; several inputs end with a summary.\n"
    "As a build step (docs/build-step.md):\n"
    "  - inputs are never written: an output, -r or --depfile that is an input or a file an input\n"
    "    reads (after symlinks, '..' and hard links), or another output, is refused before any work\n"
    "    (exit 2), and so is a folder of theirs that cannot be written;\n"
    "  - no stale output: a failed input's earlier output is removed, its depfile rule kept;\n"
    "  - an output whose bytes would not change is left untouched (mtime kept: Ninja's restat);\n"
    "    Make needs a stamp file (--depfile-target, cmake's geom_bake_assets() does it);\n"
    "  - the bytes depend only on the inputs and the flags: not on -j, paths, time or the CPU;\n"
    "  - exit 0 all baked, 1 an input failed, 2 bad usage or a refused output.\n";

// The inputs as given, expanded (directories walked, archives opened); -1 to
// go on, else the exit status after an `Error:` line.
int expand(BakeConfig& config, std::vector<TreeInput>& inputs, bool& folder) {
  folder = false;
  if (!expand_tree_inputs(config.named, inputs, config.skipped, folder)) return 2;
  if (!config.quiet)
    for (const std::string& w : config.skipped) std::fprintf(stderr, "Warning: %s\n", w.c_str());
  if (inputs.empty()) {
    std::fprintf(stderr, "Error: no input file%s\n%s",
                 config.named.empty() ? "" : " (no mesh file in the inputs given)",
                 config.named.empty() ? kBakeHelp : "");
    return 2;
  }
  return -1;
}

// The output folder of -o DIR, and no temporary file a killed run left in it;
// false after an `Error:` line.
bool prepare_output_folder(const BakeConfig& config) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string& out = config.out;
  if (config.out_is_dir && !fs::is_directory(out, ec)) {
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out)) {
      std::fprintf(stderr, "Error: %s: cannot create the output directory%s%s\n", out.c_str(), ec ? ": " : "",
                   ec ? ec.message().c_str() : "");
      return false;
    }
  }
  const size_t slash = out.find_last_of('/');
  geom::remove_stale_temp_files(config.out_is_dir ? out : slash == std::string::npos ? "." : out.substr(0, slash + 1));
  return true;
}

int run_bake(const std::vector<std::string>& argv) {
  BakeConfig config;
  if (const int status = parse_bake_flags(argv, kBakeHelp, config); status >= 0) return status;
  const int64_t t0 = now_ns();
  std::vector<TreeInput> inputs;
  bool folder = false;
  if (const int status = expand(config, inputs, folder); status >= 0) return status;
  if (const int status = plan_output(config, folder); status >= 0) return status;
  std::vector<Job> jobs;
  plan_jobs(inputs, config, jobs);
  if (!check_outputs(jobs, config)) return 2;
  if (!prepare_output_folder(config)) return 1;
  config.write.make_parents = config.out_is_dir;
  geom::keep_memory_across_bakes();  // each input reuses the pages of the ones before
  const ScheduleStats stats = run_jobs(jobs, config);
  const int status = report_run(jobs, config, stats, t0);
  if (stats.timed_out) {  // workers still busy with abandoned inputs cannot be joined: end now
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(status);
  }
  return status;
}

GEOMBAKE_COMMAND("bake", "write the baked GPU buffers of each input (-o FILE or DIR)", run_bake);

}  // namespace
}  // namespace geombake
