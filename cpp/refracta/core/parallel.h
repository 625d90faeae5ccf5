// Parallel loops over oneTBB with a shared control block: a cancel flag the caller may set from
// another thread (Ctrl-C in Python) and a counter of finished items for progress reports.
//
// Cancellation reaches deep work without being passed down: each thread keeps the chain of cancel
// flags it works under (CancelScope: run_interruptible's, then each enclosing parallel_for_each's),
// and anything that may run long -- a ray's integration steps, a pixel's samples, a table's levels
// -- calls poll_cancel(), which throws Cancelled once any flag in the chain is set.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include <atomic>
#include <cstdint>
#include <stdexcept>

namespace refracta {

struct WorkControl {
  std::atomic<bool> cancel{false};
  std::atomic<int64_t> done{0};
  std::atomic<int64_t> total{0};  // set by the workers while the caller's thread reports progress
};

// Thrown out of work whose control was cancelled.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

// Puts `flag` in force on this thread for the scope's lifetime, inside the chain `outer` (by
// default the thread's current one). Scopes nest and unwind in stack order.
class CancelScope {
 public:
  explicit CancelScope(const std::atomic<bool>& flag) : CancelScope(flag, innermost()) {}
  CancelScope(const std::atomic<bool>& flag, const CancelScope* outer)
      : flag_(&flag), outer_(outer), saved_(innermost()) {
    innermost() = this;
  }
  ~CancelScope() { innermost() = saved_; }
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

  // The innermost scope in force on this thread (null outside any).
  static const CancelScope*& innermost() {
    static thread_local const CancelScope* scope = nullptr;
    return scope;
  }
  bool requested() const {
    for (const CancelScope* s = this; s; s = s->outer_) {
      if (s->flag_->load(std::memory_order_relaxed)) return true;
    }
    return false;
  }

 private:
  const std::atomic<bool>* flag_;
  const CancelScope* outer_;
  const CancelScope* saved_;
};

// True once a cancel flag in force on this thread (or `extra`, when given) is set.
inline bool cancel_requested(const std::atomic<bool>* extra = nullptr) {
  if (extra && extra->load(std::memory_order_relaxed)) return true;
  const CancelScope* scope = CancelScope::innermost();
  return scope && scope->requested();
}

// Throws Cancelled once cancel_requested(extra). Cheap (a thread-local read and an atomic load
// per enclosing scope): call it at every unit of work that can take a millisecond or more.
inline void poll_cancel(const std::atomic<bool>* extra = nullptr) {
  if (cancel_requested(extra)) throw Cancelled();
}

// Puts this thread's floating-point mode in IEEE 754's default for the scope's lifetime --
// subnormals kept (no flush-to-zero, no denormals-are-zero), round to nearest, exceptions masked
// -- and restores the mode it found. Every task of refracta's parallel loops runs under one, so
// that results do not depend on the thread that runs them. Embree's rtcCommitScene sets FTZ and
// DAZ in MXCSR while it builds the BVH on the TBB pool, and TBB workers that joined the build kept
// them for the next tasks they ran: the first render of a scene (the one that commits it) had
// part of its pixels shaded with subnormals flushed to zero (a Water ground's Beckmann D at
// grazing angles underflows to subnormals), so it differed from every later render of the scene.
class DefaultFloatingPointMode {
 public:
#if defined(__SSE__) || defined(__x86_64__)
  // 0x1f80: all six exceptions masked, round to nearest, FTZ and DAZ off (the status flags clear).
  static constexpr unsigned kIeeeDefault = 0x1f80u;
  DefaultFloatingPointMode() : saved_(_mm_getcsr()) { _mm_setcsr(kIeeeDefault); }
  ~DefaultFloatingPointMode() { _mm_setcsr(saved_); }
#else
  DefaultFloatingPointMode() = default;
#endif
  DefaultFloatingPointMode(const DefaultFloatingPointMode&) = delete;
  DefaultFloatingPointMode& operator=(const DefaultFloatingPointMode&) = delete;

#if defined(__SSE__) || defined(__x86_64__)
 private:
  unsigned saved_;
#endif
};

// Whether a loop's count is the work's whole progress total (kSet), or the caller set a total
// for several loops run one after the other (kKeep: the bar must not reach its end after the first).
enum class ProgressTotal { kSet, kKeep };

// Calls body(i) for i in [0, count) on the TBB pool, `grain` items per task at least. The body
// runs under control.cancel and every flag in force on the calling thread: cancelling either
// stops the loop (throws Cancelled) at the next item or the next poll_cancel() inside one.
// Each finished item adds one to control.done; a loop that sets the total (kSet) starts it at 0,
// so that a phase's progress never shows more done than its total (render_raster's rasterizing
// and shadow maps before its shading reported 1038 of 16).
template <class Body>
void parallel_for_each(int64_t count, int64_t grain, WorkControl& control, const Body& body,
                       ProgressTotal total = ProgressTotal::kSet) {
  if (total == ProgressTotal::kSet) {
    control.done = 0;
    control.total = count;
  }
  const CancelScope* outer = CancelScope::innermost();  // the caller's chain, alive while we block
  tbb::parallel_for(tbb::blocked_range<int64_t>(0, count, grain),
                    [&](const tbb::blocked_range<int64_t>& range) {
                      const DefaultFloatingPointMode fp_mode;
                      const CancelScope scope(control.cancel, outer);
                      for (int64_t i = range.begin(); i != range.end(); ++i) {
                        if (scope.requested()) throw Cancelled();
                        body(i);
                        control.done.fetch_add(1, std::memory_order_relaxed);
                      }
                    });
}

}  // namespace refracta
