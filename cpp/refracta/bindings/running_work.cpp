// The registry of running work (running_work.h).
#include "refracta/bindings/running_work.h"

#include <Python.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace refracta {

namespace {

struct Registry {
  std::mutex mutex;
  std::condition_variable changed;
  struct Call {
    WorkControl* control;
    unsigned long thread_id;  // the Python thread that made the call
  };
  std::vector<Call> running;
  std::vector<unsigned long> cancelled_threads;  // cancel_thread_work's, until end_thread_cancel
  bool shutting_down = false;
};

// Never destroyed: threads parked at exit may still hold its mutex when static destructors run.
Registry& registry() {
  static Registry* instance = new Registry;
  return *instance;
}

void remove(Registry& r, WorkControl& control) {
  std::lock_guard<std::mutex> lock(r.mutex);
  r.running.erase(std::remove_if(r.running.begin(), r.running.end(),
                                 [&](const Registry::Call& call) { return call.control == &control; }),
                  r.running.end());
  r.changed.notify_all();
}

}  // namespace

void enter_running_work(WorkControl& control) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (r.shutting_down) throw std::runtime_error("refracta: the Python interpreter is shutting down");
  const unsigned long thread_id = PyThread_get_thread_ident();
  r.running.push_back({&control, thread_id});
  const auto& cancelled = r.cancelled_threads;
  if (std::find(cancelled.begin(), cancelled.end(), thread_id) != cancelled.end()) control.cancel = true;
}

void leave_running_work(WorkControl& control) { remove(registry(), control); }

bool python_is_shutting_down() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.shutting_down;
}

void park_if_shutting_down(WorkControl& control) {
  if (!python_is_shutting_down()) return;
  remove(registry(), control);
  for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
}

int cancel_thread_work(const std::vector<unsigned long>& thread_ids) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.cancelled_threads.insert(r.cancelled_threads.end(), thread_ids.begin(), thread_ids.end());
  int cancelled = 0;
  for (const Registry::Call& call : r.running) {
    if (std::find(thread_ids.begin(), thread_ids.end(), call.thread_id) != thread_ids.end()) {
      call.control->cancel = true;
      ++cancelled;
    }
  }
  return cancelled;
}

void end_thread_cancel(unsigned long thread_id) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  auto& cancelled = r.cancelled_threads;
  cancelled.erase(std::remove(cancelled.begin(), cancelled.end(), thread_id), cancelled.end());
}

void shutdown_running_work(double timeout_seconds) {
  Registry& r = registry();
  std::unique_lock<std::mutex> lock(r.mutex);
  r.shutting_down = true;
  for (const Registry::Call& call : r.running) call.control->cancel = true;
  r.changed.wait_for(lock, std::chrono::duration<double>(timeout_seconds), [&] { return r.running.empty(); });
}

}  // namespace refracta
