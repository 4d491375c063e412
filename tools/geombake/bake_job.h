// One input of `geombake bake`, start to end: import within the limits, the
// memory estimate, the bake streamed into its output, and the write, which
// happens only while the watchdog (bake_schedule.h) has not given up on it.
#pragma once
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "geom/bake.h"
#include "geom/import.h"
#include "geombake/bake_output.h"
#include "geombake/error_kind.h"
#include "geombake/fault.h"

namespace geombake {

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

// Watchdog states (--timeout): kPending -> kRunning -> kWriting -> kFinished,
// or kRunning -> kTimedOut (set by the watchdog, or for a thread a refusal
// parked (fault.h): the worker's result is dropped).
enum JobState { kPending, kRunning, kWriting, kFinished, kTimedOut };

struct Job {
  std::string input, output, error;  // error: why no output was planned, or the bake's error
  std::string name;                  // the source name stored in the output (geombake/tree.h)
  std::vector<std::string> reads;    // the files it is made of (geom::input_dependencies), found once
  ErrorKind kind = ErrorKind::None;  // the class of `error`
  geom::BakeResult result;           // without its sections' bytes once written
  std::vector<SectionInfo> sections;
  std::vector<std::string> warnings;  // the importer's, naming the input as given
  Written written = Written::Failed;
  bool done = false;
  double seconds = 0;  // wall time of its bake, write included
  std::atomic<int> state{kPending};
  std::atomic<int64_t> started_ns{0};  // steady clock, when state became kRunning
  size_t worker = 0;                   // the worker thread that runs it
  Budget budget;                       // its memory (--max-memory); cancelled when it times out
};

struct JobLimits {
  uint64_t max_memory = 0;  // --max-memory, bytes; 0: none
  double timeout = 0;       // --timeout, seconds; 0: none
};

struct WriteOptions {
  bool force = false;         // --force
  bool make_parents = false;  // -o DIR: outputs mirrored into subdirectories
};

// The result of one bake, handed to the job under the scheduler's lock.
struct Outcome {
  geom::BakeResult result;
  std::string error;
  ErrorKind kind = ErrorKind::None;
  std::vector<SectionInfo> sections;
  std::vector<std::string> warnings;
  Written written = Written::Failed;
};

// Bakes `job` as a fault domain (fault.h): whatever it throws, bad_alloc and
// its --max-memory budget included, is this input's error.
Outcome bake_one(Job& job, const geom::BakeOptions& options, const geom::ImportOptions& import_options,
                 const JobLimits& limits, const WriteOptions& write);

// Steady clock, nanoseconds.
int64_t now_ns();

}  // namespace geombake
