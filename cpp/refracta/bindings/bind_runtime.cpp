// Process-wide settings of the library: how many threads oneTBB may use, and where the messages of
// the libraries underneath (Ceres' glog, OpenImageIO) go: to Python's logging, never the terminal.
#include "refracta/bindings/bindings.h"
#include "refracta/core/memory.h"
#include "refracta/edit/ceres_log.h"
#include "refracta/scene/oiio_messages.h"

#include <tbb/global_control.h>

#include <memory>
#include <optional>
#include <thread>

namespace refracta {

namespace {

// The limit set by set_threads, held for the life of the module (none: oneTBB's default, every
// core the process may use).
std::unique_ptr<tbb::global_control>& thread_limit() {
  static auto* limit = new std::unique_ptr<tbb::global_control>();  // leaked: outlives the last task
  return *limit;
}

// Python logging level of a glog severity. Ceres' WARNING and ERROR lines report why a solve
// stopped, which EditResult.message already says (its FATAL never returns): INFO, shown only when
// the user asks for refracta's log. Its INFO lines are progress: DEBUG.
int python_level(int severity) {
  constexpr int kDebug = 10, kInfo = 20, kCritical = 50;  // logging.DEBUG, INFO, CRITICAL
  return severity == 0 ? kDebug : severity < 3 ? kInfo : kCritical;
}

}  // namespace

void warn(const std::string& message) {
  if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 2) != 0) throw py::error_already_set();
}

void emit_library_log() {
  std::vector<LibraryLogRecord> records = take_ceres_log();
  if (records.empty()) return;
  py::object logger = py::module_::import("logging").attr("getLogger")("refracta.ceres");
  for (const auto& record : records) logger.attr("log")(python_level(record.severity), "%s", record.message);
}

void bind_runtime(py::module_& m) {
  capture_ceres_log();
  silence_oiio_debug_output();
  m.def(
      "set_threads",
      [](std::optional<int> n) {
        // oneTBB keeps at most 256 workers (get_threads said 1000000, then 257, after set_threads(10**6)).
        constexpr int kMostThreads = 256;
        if (n && (*n < 0 || *n > kMostThreads)) {
          throw_invalid("set_threads: n must be in [0, ", kMostThreads, "] or None (got ", *n, "; this machine has ",
                        std::thread::hardware_concurrency(), " hardware threads)");
        }
        thread_limit().reset();  // one limit at a time: the newest is the one in force
        limit_oiio_threads(n.value_or(0));
        if (n && *n > 0) {
          thread_limit() = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(*n));
        }
      },
      py::arg("n"), R"doc(
Limit refracta's parallel work (oneTBB: render, trace_rays, render_raster, solve's pair traces,
Embree's BVH builds; OpenImageIO's image and texture work) to n threads, n in [0, 256]; n = None or 0 restores the default, every core. Results do
not depend on it: every parallel loop writes each item's result to its own slot.)doc");
  m.def(
      "get_threads",
      [] { return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)); },
      "The number of threads refracta's parallel work may use (see set_threads).");
  m.def("physical_memory_bytes", &physical_memory_bytes,
        "This machine's physical memory [bytes] (0 if unknown), by which refracta refuses work too large to allocate.");
}

}  // namespace refracta
