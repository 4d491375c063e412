// `geombake bake`'s scheduling: the inputs baked on a pool of worker threads,
// each job writing only its own slot; the main thread is the watchdog of
// --timeout (it gives up on a job over the limit, and starts a worker in
// place of the one left with it). As each input finishes: its `Error:` or
// warnings, then the progress (a line cut to the terminal's width when stderr
// is one; with --progress=plain a line when the first input finishes, then at
// most one every kPlainProgressSeconds, for logs that are not a terminal).
#pragma once
#include <vector>

#include "geombake/bake_job.h"
#include "geombake/bake_plan.h"

namespace geombake {

constexpr double kPlainProgressSeconds = 5;

struct ScheduleStats {
  unsigned threads = 0;  // worker threads at the start
  size_t timed_out = 0;  // jobs given up on (their workers may still run: end with _Exit)
};

ScheduleStats run_jobs(std::vector<Job>& jobs, const BakeConfig& config);

}  // namespace geombake
