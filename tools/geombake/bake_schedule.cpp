// `geombake bake`'s scheduling (bake_schedule.h).
#include "geombake/bake_schedule.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "geombake/bake_output.h"

namespace geombake {
namespace {

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

// What is said on stderr as each input finishes (called under the scheduler's lock).
class Announcer {
 public:
  Announcer(const BakeConfig& config, size_t total)
      : config_(config), total_(total), t0_(now_ns()), last_plain_(t0_ - int64_t(kPlainProgressSeconds * 1e9)) {
    tty_ = !config.quiet && config.progress == Progress::Auto && ::isatty(2) && total > 1;
    plain_ = !config.quiet && config.progress == Progress::Plain && total > 1;
  }

  void finished(const Job& job, size_t count) {
    if (tty_) std::fputs("\r\033[K", stderr);
    if (!job.error.empty()) {
      std::fprintf(stderr, "Error: %s\n", job.error.c_str());
    } else if (!config_.quiet && !config_.json && job.done) {
      for (const std::string& w : job.warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
      const std::string g = geometry_warning(job.input, job.result.report.stats);
      if (!g.empty()) std::fprintf(stderr, "Warning: %s\n", g.c_str());
    }
    if (tty_) {
      const std::string head = "[" + std::to_string(count) + "/" + std::to_string(total_) + "] ";
      const size_t width = size_t(std::max(terminal_width(2) - 1, 8));
      std::fputs(fit_line(head + job.input, width, head.size()).c_str(), stderr);
      if (count == total_) std::fputs("\r\033[K", stderr);
    }
    const int64_t now = now_ns();
    if (plain_ && count < total_ && double(now - last_plain_) * 1e-9 >= kPlainProgressSeconds) {
      last_plain_ = now;
      std::fprintf(stderr, "geombake bake: %zu of %zu inputs done (%.0f%%) after %.0f s\n", count, total_,
                   100.0 * double(count) / double(total_), double(now - t0_) * 1e-9);
    }
    std::fflush(stderr);
  }

 private:
  const BakeConfig& config_;
  size_t total_;
  int64_t t0_, last_plain_;
  bool tty_ = false, plain_ = false;
};

struct Pool {
  std::vector<Job>& jobs;
  const BakeConfig& config;
  Announcer announcer;
  std::atomic<size_t> next{0};
  size_t finished = 0, timed_out = 0;  // under `mutex`
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::thread> threads;
  std::vector<bool> stuck;  // a thread left with a job given up on: detached, never joined

  // Takes jobs until none is left, or until the watchdog gives up on its job.
  void work(size_t self) {
    for (size_t i; (i = next++) < jobs.size();) {
      Job& job = jobs[i];
      Outcome o;
      if (job.error.empty()) {
        job.worker = self;
        job.started_ns = now_ns();
        job.state = kRunning;
        o = bake_one(job, config.options, config.import, config.limits, config.write);
      }
      std::lock_guard<std::mutex> lock(mutex);
      if (job.state == kTimedOut) return;  // given up on: a new worker took this one's place
      const double took = job.error.empty() ? double(now_ns() - job.started_ns) * 1e-9 : 0;
      if (job.state == kRunning && config.limits.timeout > 0 && took > config.limits.timeout && o.error.empty())
        o.error = job.input + ": timed out after " + seconds_text(config.limits.timeout) + " s (--timeout)",
        o.kind = ErrorKind::Timeout;
      job.state = kFinished;
      job.seconds = took;
      job.result = std::move(o.result);
      job.sections = std::move(o.sections);
      job.warnings = std::move(o.warnings);
      job.written = o.written;
      if (job.error.empty()) job.error = o.error, job.kind = o.kind;
      job.done = job.error.empty() && job.result.ok;
      announcer.finished(job, ++finished);
      changed.notify_all();
    }
  }

  // The watchdog's round (under `mutex`): gives up on the jobs over --timeout.
  void watch() {
    const double timeout = config.limits.timeout;
    const int64_t now = now_ns();
    for (Job& job : jobs) {
      int expected = kRunning;
      if (job.state != kRunning || double(now - job.started_ns) * 1e-9 <= timeout ||
          !job.state.compare_exchange_strong(expected, kTimedOut))
        continue;
      job.error = job.input + ": timed out after " + seconds_text(timeout) + " s (--timeout)";
      job.kind = ErrorKind::Timeout;
      job.seconds = double(now - job.started_ns) * 1e-9;
      job.budget.cancelled = true;  // its next allocation throws: the work unwinds, its memory is freed
      ++timed_out;
      announcer.finished(job, ++finished);
      stuck[job.worker] = true;
      if (next < jobs.size()) start();
    }
  }

  // Gives up on the jobs whose thread a refusal parked (fault.h): failed as the
  // refusal says; a new worker takes the parked one's place (under `mutex`).
  void reap() {
    for (Job& job : jobs) {
      int state = job.state;
      if (!job.budget.parked || (state != kRunning && state != kWriting) ||
          !job.state.compare_exchange_strong(state, kTimedOut))
        continue;
      job.error = refusal_cause(job.input, job.budget);
      job.kind = ErrorKind::LimitMemory;  // a cancelled job is already kTimedOut
      job.seconds = double(now_ns() - job.started_ns) * 1e-9;
      announcer.finished(job, ++finished);
      stuck[job.worker] = true;
      if (next < jobs.size()) start();
    }
  }

  void start() {
    const size_t self = threads.size();
    stuck.push_back(false);
    threads.emplace_back([this, self] { work(self); });
  }
};

}  // namespace

ScheduleStats run_jobs(std::vector<Job>& jobs, const BakeConfig& config) {
  ScheduleStats stats;
  Pool pool{jobs, config, Announcer(config, jobs.size())};
  stats.threads = unsigned(std::min<size_t>(std::max(1u, config.threads), std::max<size_t>(1, jobs.size())));
  {
    std::unique_lock<std::mutex> lock(pool.mutex);
    for (unsigned t = 0; t < stats.threads; ++t) pool.start();
    while (pool.finished < jobs.size()) {
      pool.changed.wait_for(lock, std::chrono::milliseconds(config.limits.timeout > 0 ? 10 : 200));
      if (config.limits.timeout > 0) pool.watch();
      pool.reap();
    }
  }
  for (size_t t = 0; t < pool.threads.size(); ++t) pool.stuck[t] ? pool.threads[t].detach() : pool.threads[t].join();
  stats.timed_out = pool.timed_out;
  return stats;
}

}  // namespace geombake
