// glog -> a queue of records (the only glog user).
#include "refracta/edit/ceres_log.h"

#include <glog/logging.h>

#include <deque>
#include <mutex>

namespace refracta {

namespace {

// At most this many records wait for the Python thread; older ones are dropped (a runaway solve
// logging every iteration from a thread must not grow memory without bound).
constexpr size_t kMaxQueued = 10000;

class QueueSink : public google::LogSink {
 public:
  void send(google::LogSeverity severity, const char* /*full_filename*/, const char* base_filename, int line,
            const google::LogMessageTime& /*time*/, const char* message, size_t message_len) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (records_.size() == kMaxQueued) records_.pop_front();
    records_.push_back({int(severity), std::string(base_filename) + ":" + std::to_string(line) + "] " +
                                           std::string(message, message_len)});
  }
  std::vector<LibraryLogRecord> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<LibraryLogRecord> out(records_.begin(), records_.end());
    records_.clear();
    return out;
  }

 private:
  std::mutex mutex_;
  std::deque<LibraryLogRecord> records_;
};

QueueSink& sink() {
  static QueueSink* instance = new QueueSink;  // never destroyed: glog may log during exit
  return *instance;
}

}  // namespace

void capture_ceres_log() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (!google::IsGoogleLoggingInitialized()) {
      // Before InitGoogleLogging glog writes everything to stderr; after it, to log files and to
      // stderr from FLAGS_stderrthreshold up. Neither: the queue is the only destination.
      FLAGS_logtostderr = false;
      FLAGS_alsologtostderr = false;
      FLAGS_stderrthreshold = google::NUM_SEVERITIES;
      google::InitGoogleLogging("refracta");
      for (int severity = 0; severity < google::NUM_SEVERITIES; ++severity) {
        google::SetLogDestination(severity, "");  // "" = no log file for this severity
      }
    }
    google::AddLogSink(&sink());
  });
}

std::vector<LibraryLogRecord> take_ceres_log() { return sink().take(); }

}  // namespace refracta
