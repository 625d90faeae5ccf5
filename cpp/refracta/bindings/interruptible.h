// Runs long C++ work with the GIL released on a worker thread, while the calling thread wakes
// every 50 ms to check for Ctrl-C (then cancels the work and raises KeyboardInterrupt) and to
// report progress to an optional Python callable progress(done, total); an exception raised by
// the callback cancels the work the same way. Every call is registered (running_work.h) so that
// interpreter exit cancels it and waits for it, and it never takes the GIL of an exiting interpreter.
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/bindings/running_work.h"
#include "refracta/core/parallel.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace refracta {

template <class Work>
void run_interruptible(WorkControl& control, const py::object& progress, Work&& work) {
  std::exception_ptr error;
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false, interrupted = false;
  enter_running_work(control);
  struct Leave {
    WorkControl& control;
    ~Leave() { leave_running_work(control); }  // with the GIL held again, after the block below
  } leave{control};
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        const CancelScope scope(control.cancel);  // deep work polls it (core/parallel.h)
        work();
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex);
      finished = true;
      finished_cv.notify_all();
    });
    std::unique_lock<std::mutex> lock(mutex);
    while (!finished) {
      finished_cv.wait_for(lock, std::chrono::milliseconds(50));
      if (finished) break;
      if (python_is_shutting_down()) {  // interpreter exit: stop, and never take its GIL again
        control.cancel = true;
        continue;
      }
      lock.unlock();
      {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) {
          interrupted = true;
          control.cancel = true;
        } else if (!progress.is_none()) {
          try {
            progress(control.done.load(), control.total.load());
          } catch (py::error_already_set& error) {
            // Raised by the callback: stop like Ctrl-C, re-raised once the worker has finished
            // (waiting here, with the GIL held, would deadlock a worker calling into Python).
            error.restore();
            interrupted = true;
            control.cancel = true;
          }
        }
      }
      lock.lock();
      if (interrupted) {
        finished_cv.wait(lock, [&] { return finished; });
        break;
      }
    }
    lock.unlock();
    worker.join();
    park_if_shutting_down(control);
  }
  if (interrupted) throw py::error_already_set();  // KeyboardInterrupt, or the callback's error
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const Cancelled&) {
      throw std::runtime_error("work was cancelled");
    }
  }
  if (!progress.is_none()) progress(control.done.load(), control.total.load());
}

// What work(control) returns, run by run_interruptible with a control of its own whose total is
// `total` (the progress callback's).
template <class Work>
auto interruptible_result(const py::object& progress, Work&& work, int64_t total = 0) {
  WorkControl control;
  control.total = total;
  decltype(work(control)) result;
  run_interruptible(control, progress, [&] { result = work(control); });
  return result;
}

}  // namespace refracta
