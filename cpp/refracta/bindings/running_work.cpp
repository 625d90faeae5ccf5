// The registry of running work (running_work.h).
#include "refracta/bindings/running_work.h"

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
  std::vector<WorkControl*> running;
  bool shutting_down = false;
};

// Never destroyed: threads parked at exit may still hold its mutex when static destructors run.
Registry& registry() {
  static Registry* instance = new Registry;
  return *instance;
}

void remove(Registry& r, WorkControl& control) {
  std::lock_guard<std::mutex> lock(r.mutex);
  r.running.erase(std::remove(r.running.begin(), r.running.end(), &control), r.running.end());
  r.changed.notify_all();
}

}  // namespace

void enter_running_work(WorkControl& control) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (r.shutting_down) throw std::runtime_error("refracta: the Python interpreter is shutting down");
  r.running.push_back(&control);
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

void shutdown_running_work(double timeout_seconds) {
  Registry& r = registry();
  std::unique_lock<std::mutex> lock(r.mutex);
  r.shutting_down = true;
  for (WorkControl* control : r.running) control->cancel = true;
  r.changed.wait_for(lock, std::chrono::duration<double>(timeout_seconds), [&] { return r.running.empty(); });
}

}  // namespace refracta
