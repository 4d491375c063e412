// Each input a fault domain: whatever goes wrong while one input is
// imported and baked (an exception, bad_alloc included, its memory limit, its
// time limit) becomes that input's `Error: FILE: cause`, and the others go on.
//
// Memory: geombake replaces the global operator new (fault.cpp). Once budgets
// are enabled, every allocation a thread makes is charged to the Budget that
// thread works for (malloc_usable_size bytes; a free on that thread credits
// it), and an allocation that would take it past its limit throws bad_alloc
// instead: --max-memory bounds what the process really allocates for an
// input, whatever the format claims, not an estimate. A cancelled budget (the
// input's --timeout expired) throws at its next allocation, so abandoned work
// unwinds and gives its memory back instead of running on.
// Memory that libraries take with malloc() directly (libzip) is not counted.
// No allocation is refused while an exception unwinds the stack (destructors
// allocate too). A refusal in a function that may not throw (a destructor on
// the normal path: nlohmann::json's flattening one allocates) would end the
// process in std::terminate; on a thread whose budget refused, the terminate
// handler parks that thread for good instead (Budget::parked) and its owner
// reports the input as the refusal says and goes on. A parked thread keeps
// its memory until the process ends.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace geombake {

struct Budget {
  uint64_t limit = 0;                  // bytes; 0 = no limit
  std::atomic<int64_t> used{0};        // bytes charged (may dip below 0: frees of older blocks)
  std::atomic<int64_t> peak{0};        // the most `used` reached
  std::atomic<bool> cancelled{false};  // set by a watchdog: the next allocation throws
  std::atomic<bool> exceeded{false};   // an allocation was refused for the limit
  std::atomic<bool> parked{false};     // its thread is blocked for good (a refusal reached a noexcept frame)
};

// The one-line cause of a budget's refusal: "FILE: needs more memory than
// allowed, ... (--max-memory)", "FILE: abandoned (--timeout)" or "FILE: out of memory".
std::string refusal_cause(const std::string& input, const Budget& budget);

// Turns the accounting on for the rest of the process (off: operator new costs
// nothing more than malloc). Call before any budget is used.
void enable_budgets();

// Charges the calling thread's allocations to `b` (nullptr: to nothing) while
// it lives; restores the previous budget after.
class BudgetScope {
 public:
  explicit BudgetScope(Budget* b);
  ~BudgetScope();
  BudgetScope(const BudgetScope&) = delete;
  BudgetScope& operator=(const BudgetScope&) = delete;

 private:
  Budget* previous_;
};

// Runs `work` for `input` as a fault domain: returns "" if it returned "", else
// the one-line cause ("FILE: cause"): what `work` returned, or what it threw
// (bad_alloc becomes "out of memory", or "needs more memory than allowed,
// over the limit of N (--max-memory)" when the budget refused it).
std::string guarded(const std::string& input, Budget& budget, const std::function<std::string()>& work);

// Runs `work` (as guarded() does) on a thread of its own and waits for it at
// most `timeout` seconds (0: no limit). On a timeout the work's budget is
// cancelled, its thread is left to unwind on its own, `timed_out` is set and
// the cause is "FILE: timed out after S s (--timeout)". A parked thread is
// left too, with refusal_cause() as the cause. After a timeout the caller must
// end the process with _Exit rather than return from main (the thread may
// still be running). `work` must own what it uses (capture by value).
std::string guarded_with_timeout(const std::string& input, uint64_t max_memory, double timeout,
                                 std::function<std::string()> work, bool& timed_out);

std::string seconds_text(double s);

// "1048576", "64K", "300M", "2G" -> bytes; false on anything else.
bool parse_bytes(const std::string& text, uint64_t& bytes);

}  // namespace geombake
