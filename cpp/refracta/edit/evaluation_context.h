// What every residual evaluation of an edit shares: the cancel flag, counters, and the first
// failure (a ray reaching n <= 0, parameters a model rejects) so a solver's "evaluation failed"
// can say why.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <string>

namespace refracta {

class EvaluationContext {
 public:
  const std::atomic<bool>* cancel = nullptr;
  std::atomic<int64_t> pair_evaluations{0};   // traced pairs (value or value + derivatives)
  std::atomic<int64_t> field_evaluations{0};  // n and grad n together count as one

  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }

  void record_failure(const std::string& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (failure_.empty()) failure_ = message;
  }
  std::string first_failure() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return failure_;
  }

  // Runs body(); any exception becomes `false` (recorded unless it is a cancellation), because
  // exceptions must not cross Ceres' or nlopt's C frames.
  template <class Body>
  bool guarded(Body&& body) {
    try {
      body();
      return true;
    } catch (const std::exception& error) {
      if (!cancelled()) record_failure(error.what());
      return false;
    }
  }

 private:
  mutable std::mutex mutex_;
  std::string failure_;
};

}  // namespace refracta
