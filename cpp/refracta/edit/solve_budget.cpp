// SolveBudget (edit_settings.h): the limits one edit solve shares between its stages, the
// watcher that interrupts traces at the time limit or on cancel, and the solve's progress.
#include "refracta/edit/edit_settings.h"

#include <cmath>
#include <limits>

namespace refracta {

namespace {

// The watcher looks at the caller's cancel flag and the clock this often: Ctrl-C and the time
// limit stop a running trace within about this long.
constexpr auto kWatchInterval = std::chrono::milliseconds(20);

}  // namespace

const char* stop_reason_name(StopReason reason) {
  switch (reason) {
    case StopReason::kIterations: return "iteration limit";
    case StopReason::kEvaluations: return "evaluation limit";
    case StopReason::kTimeLimit: return "time limit";
    case StopReason::kNone: break;
  }
  return "";
}

SolveBudget::SolveBudget(const SolveSettings& settings, WorkControl& control)
    : control_(control), max_iterations_(settings.max_iterations), max_evaluations_(settings.max_evaluations),
      time_limit_(settings.time_limit), begin_(std::chrono::steady_clock::now()) {
  control_.total = kProgressTotal;
  control_.done = 0;
  watcher_ = std::thread([this] {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done_) {
      wake_.wait_for(lock, kWatchInterval);
      if (control_.cancel.load()) interrupt_ = true;
      if (time_limit_ > 0.0 && seconds() >= time_limit_ && !timed_out_.exchange(true)) interrupt_ = true;
      update_progress();
    }
  });
}

SolveBudget::~SolveBudget() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  watcher_.join();
}

void SolveBudget::check_cancelled() const {
  if (control_.cancel.load()) throw Cancelled();
}

void SolveBudget::spend_iterations(int n) {
  iterations_.fetch_add(n);
  update_progress();
}

void SolveBudget::spend_evaluations(int64_t n) {
  evaluations_.fetch_add(n);
  update_progress();
}

double SolveBudget::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
}

double SolveBudget::seconds_left() const {
  if (time_limit_ <= 0.0) return std::numeric_limits<double>::infinity();
  return std::max(0.0, time_limit_ - seconds());
}

StopReason SolveBudget::exhausted() const {
  if (timed_out_.load() || (time_limit_ > 0.0 && seconds() >= time_limit_)) return StopReason::kTimeLimit;
  if (evaluations_left() == 0) return StopReason::kEvaluations;
  if (iterations_left() == 0) return StopReason::kIterations;
  return StopReason::kNone;
}

void SolveBudget::resume_for_measurement() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!control_.cancel.load()) {
    timed_out_ = true;  // the watcher does not raise the interrupt again
    interrupt_ = false;
  }
}

void SolveBudget::finish() { control_.done = kProgressTotal; }

void SolveBudget::update_progress() {
  double used = std::max(double(iterations_.load()) / max_iterations_, double(evaluations_.load()) / max_evaluations_);
  if (time_limit_ > 0.0) used = std::max(used, seconds() / time_limit_);
  // min first: a time_limit of 1e-20 s makes `used` ~1e16, past an int64 once scaled.
  const int64_t done = std::min(kProgressTotal - 1, int64_t(std::min(used, 1.0) * kProgressTotal));  // the end reports the total
  int64_t before = control_.done.load();
  while (done > before && !control_.done.compare_exchange_weak(before, done)) {
  }
}

}  // namespace refracta
