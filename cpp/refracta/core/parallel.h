// Parallel loops over oneTBB with a shared control block: a cancel flag the caller may set from
// another thread (Ctrl-C in Python) and a counter of finished items for progress reports.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstdint>
#include <stdexcept>

namespace refracta {

struct WorkControl {
  std::atomic<bool> cancel{false};
  std::atomic<int64_t> done{0};
  int64_t total = 0;
};

// Thrown out of a parallel loop whose control was cancelled.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

// Calls body(i) for i in [0, count) on the TBB pool, `grain` items per task at least.
template <class Body>
void parallel_for_each(int64_t count, int64_t grain, WorkControl& control, const Body& body) {
  control.total = count;
  tbb::parallel_for(tbb::blocked_range<int64_t>(0, count, grain),
                    [&](const tbb::blocked_range<int64_t>& range) {
                      for (int64_t i = range.begin(); i != range.end(); ++i) {
                        if (control.cancel.load(std::memory_order_relaxed)) throw Cancelled();
                        body(i);
                        control.done.fetch_add(1, std::memory_order_relaxed);
                      }
                    });
}

}  // namespace refracta
