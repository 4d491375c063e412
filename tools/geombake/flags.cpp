// The shared flags of bake, info and volume (geombake/flags.h).
#include "geombake/flags.h"

#include <cstdio>

#include "geombake/fault.h"
#include "geombake/inputs.h"

namespace geombake {

std::set<std::string> with_shared_flags(std::set<std::string> own, unsigned groups, bool valued) {
  if (valued && (groups & kPipelineFlags)) own.insert({"--weld-tolerance", "--coplanar-degrees"});
  if (valued && (groups & kImportFlags)) own.insert({"--patch-level", "--md3-frame", "--max-triangles"});
  if (valued && (groups & kLimitFlags)) own.insert({"--max-memory", "--timeout"});
  if (!valued && (groups & kImportFlags)) own.insert("--allow-outside-uris");
  return own;
}

bool parse_shared_flags(const cli::Args& args, unsigned groups, SharedFlags& out) {
  if ((groups & kPipelineFlags) && (!parse_number(args, "--weld-tolerance", out.pipeline.weld_tolerance) ||
                                    !parse_number(args, "--coplanar-degrees", out.pipeline.coplanar_degrees)))
    return false;
  if ((groups & kImportFlags) && (!parse_number(args, "--patch-level", out.import.patch_level) ||
                                  !parse_number(args, "--md3-frame", out.import.md3_frame) ||
                                  !parse_number(args, "--max-triangles", out.import.max_triangles)))
    return false;
  if (groups & kImportFlags) out.import.allow_outside_uris = args.has("--allow-outside-uris");
  if (!(groups & kLimitFlags)) return true;
  if (!parse_number(args, "--timeout", out.timeout)) return false;
  if (args.has("--max-memory")) {
    if (!parse_bytes(args.get("--max-memory"), out.max_memory) || out.max_memory == 0) {
      std::fprintf(stderr, "Error: option --max-memory: '%s' is not a byte count (N, NK, NM or NG)\n",
                   args.get("--max-memory").c_str());
      return false;
    }
    out.import.max_bytes = out.max_memory;
  }
  if (out.max_memory || out.timeout > 0) enable_budgets();  // real accounting; cancellation of abandoned work
  return true;
}

}  // namespace geombake
