// geombake info FILE...: the topology report of each input, for people or (with
// --json) one JSON object per line, for machines. An archive (.pk3) given
// without ":member" expands to every .bsp map inside it.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "cli/args.h"
#include "geom/atomic_file.h"
#include "geom/import.h"
#include "geom/process.h"
#include "geom/report.h"
#include "geombake/bake_plan.h"
#include "geombake/command.h"
#include "geombake/error_kind.h"
#include "geombake/fault.h"
#include "geombake/flags.h"
#include "geombake/inputs.h"
#include "geombake/names.h"

namespace geombake {
namespace {

const char* kInfoHelp =
    "usage: geombake info [options] FILE...\n"
    "  Prints the topology report of each input (after an exact weld, or --weld-tolerance).\n"
    "  FILE may be ARCHIVE.pk3:path/inside.bsp, or ARCHIVE.pk3 for every map inside.\n"
    "options:\n"
    "  --json              one JSON object per input, one per line, failed inputs included:\n"
    "                      {\"input\": ..., \"ok\": false, \"error\": ..., \"error_kind\": ...}\n"
    "                      (error kinds: docs/build-step.md)\n"
    "  -o FILE             write the report to FILE (atomically) instead of stdout\n"
    "  -v                  timing and peak memory per stage\n"
    "  --weld-tolerance T  merge vertices closer than T (default 0: exact positions)\n"
    "  --coplanar-degrees D  normals closer than D degrees make a coplanar edge (default 0.01)\n"
    "  --patch-level N     Bezier patch tessellation of Quake 3 maps (default 4)\n"
    "  --md3-frame N       MD3 frame to import (default 0)\n"
    "  --max-triangles N   refuse inputs with more triangles\n"
    "  --max-memory N      refuse inputs that would need more than N bytes (suffix K, M or G)\n"
    "  --timeout S         refuse inputs that take longer than S seconds (the others go on)\n"
    "  --allow-outside-uris  read glTF buffers outside the asset's folder too\n";

// What every input is read and analysed with.
struct InfoSettings {
  geom::ImportOptions import;
  geom::PipelineOptions pipeline;
  uint64_t max_memory = 0;
  double timeout = 0;
  bool json = false, verbose = false;
};

// One input's outcome: the text to print for it (empty: nothing, as for a
// failed input without --json, whose error is on stderr already).
struct InfoEntry {
  std::string text;
  bool failed = false, timed_out = false;
};

// Each input a fault domain (fault.h), on a thread of its own under --timeout.
// The work captures copies and shared buffers: a timed-out thread may outlive this call.
InfoEntry info_one(const std::string& input, const InfoSettings& s) {
  auto text = std::make_shared<std::string>();
  auto warnings = std::make_shared<std::vector<std::string>>();
  InfoEntry entry;
  const std::string error = guarded_with_timeout(
      input, s.max_memory, s.timeout,
      [=] {
        auto t0 = std::chrono::steady_clock::now();
        geom::ImportResult imported = geom::import_file(input, s.import);
        if (!imported.ok) return imported.error;
        geom::Report report;
        report.file = input;
        if (s.verbose)
          report.stages.push_back({"import",
                                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                                   geom::peak_rss_bytes()});
        geom::analyze(imported.scene, s.pipeline, report);
        *warnings = report.warnings;
        *text = s.json ? geom::report_json(report) + "\n" : geom::report_text(report);
        return std::string();
      },
      entry.timed_out);
  if (!error.empty()) {
    std::fprintf(stderr, "Error: %s\n", error.c_str());
    entry.failed = true;
    if (!s.json) return entry;
    const ErrorKind kind = entry.timed_out ? ErrorKind::Timeout : classify_import_error(input, error);
    entry.text = "{\"input\":" + json_quote(input) + ",\"ok\":false,\"error\":" + json_quote(error) +
                 ",\"error_kind\":\"" + error_kind_name(kind) + "\"}\n";
    return entry;
  }
  if (s.json) {  // the report's object, its input and "ok" first
    entry.text = "{\"input\":" + json_quote(input) + ",\"ok\":true," + text->substr(1);
    return entry;
  }
  for (const std::string& w : *warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
  entry.text = *text;
  return entry;
}

int run_info(const std::vector<std::string>& argv) {
  constexpr unsigned kShared = kImportFlags | kPipelineFlags | kLimitFlags;
  cli::Args args(argv, with_shared_flags({"--json", "-v", "--help", "-h"}, kShared, false),
                 with_shared_flags({"-o"}, kShared, true));
  if (args.has("--help") || args.has("-h")) {
    std::fputs(kInfoHelp, stdout);
    return 0;
  }
  if (!args.error().empty()) {
    std::fprintf(stderr, "Error: %s\n%s", args.error().c_str(), kInfoHelp);
    return 2;
  }
  SharedFlags shared;
  if (!parse_shared_flags(args, kShared, shared)) return 2;
  std::vector<std::string> inputs;
  if (!expand_inputs(args.positional(), inputs)) return 2;
  if (inputs.empty()) {
    std::fprintf(stderr, "Error: no input file\n%s", kInfoHelp);
    return 2;
  }
  if (args.has("-o") && !check_output_file(inputs, "-o", args.get("-o"))) return 2;  // never an input
  InfoSettings settings{shared.import,  shared.pipeline,    shared.max_memory,
                        shared.timeout, args.has("--json"), args.has("-v")};
  settings.pipeline.timing = settings.verbose;
  std::string out;
  int failed = 0;
  bool any_timed_out = false;
  for (const std::string& input : inputs) {
    const InfoEntry entry = info_one(input, settings);
    failed += entry.failed;
    any_timed_out = any_timed_out || entry.timed_out;
    if (entry.failed && !settings.json) continue;
    if (args.has("-o"))
      out += entry.text;
    else
      std::fputs(entry.text.c_str(), stdout), std::fflush(stdout);
  }
  if (args.has("-o")) {
    std::string error;
    if (!geom::write_file_atomically(args.get("-o"), out, error)) {
      std::fprintf(stderr, "Error: %s\n", error.c_str());
      failed = 1;
    }
  }
  if (any_timed_out) {  // a thread may still be unwinding an abandoned input: end now
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(failed ? 1 : 0);
  }
  return failed ? 1 : 0;
}

GEOMBAKE_COMMAND("info", "print the topology report of each input (--json for machines)", run_info);

}  // namespace
}  // namespace geombake
