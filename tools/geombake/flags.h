// The flags geombake's bake, info and volume share, parsed in one place: how
// an input is imported (geom/import.h), the pipeline's settings
// (geom/pipeline.h) and the per-input limits (geombake/fault.h).
#pragma once
#include <cstdint>
#include <set>
#include <string>

#include "cli/args.h"
#include "geom/import.h"
#include "geom/pipeline.h"

namespace geombake {

enum FlagGroup : unsigned {
  kImportFlags = 1,    // --patch-level N, --md3-frame N, --max-triangles N, --allow-outside-uris
  kPipelineFlags = 2,  // --weld-tolerance T, --coplanar-degrees D
  kLimitFlags = 4,     // --max-memory N, --timeout S
};

struct SharedFlags {
  geom::ImportOptions import;
  geom::PipelineOptions pipeline;  // its settings; the buffers asked for are the command's
  uint64_t max_memory = 0;         // --max-memory (also import.max_bytes); 0: no limit
  double timeout = 0;              // --timeout, seconds; 0: none
};

// `own` with the switches (`valued` false) or the flags taking a value of
// `groups` added, for cli::Args.
std::set<std::string> with_shared_flags(std::set<std::string> own, unsigned groups, bool valued);

// Parses the flags of `groups` into `out`; false after an `Error:` line. With
// a limit given, turns the budgets on (geombake/fault.h enable_budgets).
bool parse_shared_flags(const cli::Args& args, unsigned groups, SharedFlags& out);

}  // namespace geombake
