// Fault domains (fault.h): the accounting operator new, and the guarded runs.
#include "geombake/fault.h"

#include <malloc.h>

#include <cctype>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <new>
#include <thread>

namespace geombake {
namespace {

std::atomic<bool> g_enabled{false};
thread_local Budget* t_budget = nullptr;

// Charges `p` (just allocated) to the thread's budget; false (and `p` freed)
// if the budget refuses it.
// Never while an exception unwinds the stack: destructors allocate too
// (nlohmann::json's does), and a throw from one would end the process.
inline bool charge(void* p) {
  Budget* b = t_budget;
  if (!b) return true;
  if (b->cancelled.load(std::memory_order_relaxed) && std::uncaught_exceptions() == 0) {
    std::free(p);
    return false;
  }
  const int64_t size = int64_t(malloc_usable_size(p));
  const int64_t used = b->used.fetch_add(size, std::memory_order_relaxed) + size;
  if (b->limit && used > int64_t(b->limit) && std::uncaught_exceptions() == 0) {
    b->used.fetch_sub(size, std::memory_order_relaxed);
    b->exceeded.store(true, std::memory_order_relaxed);
    std::free(p);
    return false;
  }
  if (used > b->peak.load(std::memory_order_relaxed)) b->peak.store(used, std::memory_order_relaxed);
  return true;
}

std::terminate_handler g_previous_terminate = nullptr;

// std::terminate on a thread whose budget refused: a refusal reached a frame
// that may not throw. The work is over but the process is not: the thread is
// marked parked and blocked for good (fault.h); any other terminate is the
// default one.
[[noreturn]] void park_or_terminate() {
  Budget* b = t_budget;
  if (b && (b->cancelled.load() || b->exceeded.load())) {
    b->parked.store(true);
    for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
  }
  if (g_previous_terminate) g_previous_terminate();
  std::abort();
}

}  // namespace

void enable_budgets() {
  if (!g_enabled.exchange(true)) g_previous_terminate = std::set_terminate(&park_or_terminate);
}

std::string refusal_cause(const std::string& input, const Budget& budget) {
  if (budget.cancelled) return input + ": abandoned (--timeout)";
  if (budget.exceeded)
    return input + ": needs more memory than allowed, over the limit of " + std::to_string(budget.limit) +
           " (--max-memory)";
  return input + ": out of memory";
}

BudgetScope::BudgetScope(Budget* b) : previous_(t_budget) { t_budget = b; }
BudgetScope::~BudgetScope() { t_budget = previous_; }

std::string seconds_text(double s) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", s);
  return b;
}

bool parse_bytes(const std::string& text, uint64_t& bytes) {
  size_t digits = 0;
  while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
  if (digits == 0 || digits > 15 || text.size() > digits + 1) return false;
  uint64_t v = std::stoull(text.substr(0, digits));
  if (digits < text.size()) {
    const char unit = char(std::toupper(static_cast<unsigned char>(text[digits])));
    const int shift = unit == 'K' ? 10 : unit == 'M' ? 20 : unit == 'G' ? 30 : -1;
    if (shift < 0 || v > (UINT64_MAX >> shift)) return false;
    v <<= shift;
  }
  bytes = v;
  return true;
}

std::string guarded(const std::string& input, Budget& budget, const std::function<std::string()>& work) {
  std::string error;
  try {
    BudgetScope scope(&budget);
    error = work();
  } catch (const std::bad_alloc&) {
    return refusal_cause(input, budget);  // the scope has ended: the message itself is not charged
  } catch (const std::exception& e) {
    return input + ": " + e.what();
  } catch (...) {
    return input + ": unknown exception";
  }
  // A library that caught the bad_alloc itself (the importers do) said "out of memory": say which limit.
  if (!error.empty() && budget.exceeded) return refusal_cause(input, budget);
  return error;
}

std::string guarded_with_timeout(const std::string& input, uint64_t max_memory, double timeout,
                                 std::function<std::string()> work, bool& timed_out) {
  timed_out = false;
  struct State {
    Budget budget;
    std::mutex mutex;
    std::condition_variable done_cv;
    bool done = false;
    std::string error;
  };
  auto state = std::make_shared<State>();
  state->budget.limit = max_memory;
  std::thread thread([state, input, work = std::move(work)] {
    std::string error = guarded(input, state->budget, work);
    std::lock_guard<std::mutex> lock(state->mutex);
    state->error = std::move(error);
    state->done = true;
    state->done_cv.notify_all();
  });
  // Waits in short rounds: a thread parked by a refusal (fault.h) never says it is done.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  std::unique_lock<std::mutex> lock(state->mutex);
  while (!state->done_cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return state->done; })) {
    if (state->budget.parked) {
      lock.unlock();
      thread.detach();
      return refusal_cause(input, state->budget);
    }
    if (timeout > 0 && std::chrono::steady_clock::now() >= deadline) {
      state->budget.cancelled = true;
      lock.unlock();
      thread.detach();
      timed_out = true;
      return input + ": timed out after " + seconds_text(timeout) + " s (--timeout)";
    }
  }
  lock.unlock();
  thread.join();
  return state->error;
}

}  // namespace geombake

// The global allocation functions of geombake: malloc, plus the charge.
void* operator new(size_t size) {
  void* p = std::malloc(size ? size : 1);
  if (!p || (geombake::g_enabled.load(std::memory_order_relaxed) && !geombake::charge(p))) throw std::bad_alloc();
  return p;
}
void* operator new[](size_t size) { return operator new(size); }
void operator delete(void* p) noexcept {
  if (!p) return;
  if (geombake::g_enabled.load(std::memory_order_relaxed))
    if (geombake::Budget* b = geombake::t_budget)
      b->used.fetch_sub(int64_t(malloc_usable_size(p)), std::memory_order_relaxed);
  std::free(p);
}
void operator delete[](void* p) noexcept { operator delete(p); }
void operator delete(void* p, size_t) noexcept { operator delete(p); }
void operator delete[](void* p, size_t) noexcept { operator delete(p); }
