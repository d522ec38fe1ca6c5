#pragma once
// Ctrl-C (SIGINT) and SIGTERM as a request to stop cleanly.
#include <atomic>

namespace lccp::app {

// While alive, SIGINT and SIGTERM set a flag instead of killing the process
// (the handler only stores an atomic, which is async-signal-safe); the previous
// handlers come back on destruction. One instance at a time.
class StopOnSignal {
 public:
  StopOnSignal();
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  const std::atomic<bool>& flag() const;
  bool requested() const { return flag().load(); }
};

}  // namespace lccp::app
