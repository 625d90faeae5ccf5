// Ceres writes its messages through glog, by default straight to stderr. capture_ceres_log()
// redirects glog, once per process, into a queue; the bindings drain it into Python's logging on
// the Python thread (glog messages may come from any of Ceres' worker threads).
#pragma once

#include <string>
#include <vector>

namespace refracta {

struct LibraryLogRecord {
  int severity;         // glog's: 0 INFO, 1 WARNING, 2 ERROR (3 FATAL aborts the process in glog)
  std::string message;  // "file.cc:line] text"
};

// Initialises glog unless the host process already did (then its settings are kept and only the
// queue is added): nothing to stderr, no log files, every message into the queue. Idempotent.
void capture_ceres_log();
// Removes and returns the messages queued since the last call, oldest first. Thread-safe.
std::vector<LibraryLogRecord> take_ceres_log();

}  // namespace refracta
