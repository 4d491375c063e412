// What `geombake bake` leaves when its inputs are done: no stale output (a
// failed input's earlier output removed; with --prune, the .gbake files under
// -o DIR that no input of the run maps to), the depfile, the JSON report (-r),
// --json and -v on stdout, and the summary line; and the exit status.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "geombake/bake_job.h"
#include "geombake/bake_plan.h"
#include "geombake/bake_schedule.h"

namespace geombake {

// Removes the earlier output of each failed input (an unlink: atomic), and
// with --prune the unclaimed .gbake files under -o DIR (`pruned` gets their
// paths). False after an `Error:` line for a file that could not be removed.
bool settle_outputs(std::vector<Job>& jobs, const BakeConfig& config, std::vector<std::string>& pruned);

// The depfile's text: a rule per input (OUTPUT: FILES READ), failed inputs
// included so the next build retries them; with --depfile-target NAME one rule
// NAME: every file read. `problems` gets an `Error:` line per name no depfile
// can hold (a newline), `warnings` a `Warning:` line per name that Make or
// Ninja would misread.
std::string depfile_text(const std::vector<Job>& jobs, const BakeConfig& config, std::string& problems,
                         std::string& warnings);

// Everything after the bake (the outputs settled first); returns the exit status.
int report_run(std::vector<Job>& jobs, const BakeConfig& config, const ScheduleStats& stats, int64_t t0_ns);

}  // namespace geombake
