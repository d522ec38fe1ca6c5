#pragma once
// Ctrl-C (SIGINT) and SIGTERM as a stop request on one std::stop_source.
#include <stop_token>
#include <thread>

namespace lccp::app {

// Owned by main, created before any other work, so a signal from the first
// millisecond on is a stop request. The handler only writes a byte to a pipe
// (async-signal-safe, signal-safety(7)); a thread blocked reading the pipe
// requests the stop, so every wait on the token wakes at once and nothing
// polls. A second signal restores the default action and re-raises it: a
// second Ctrl-C ends a stuck run at once.
class SignalStop {
 public:
  SignalStop();
  ~SignalStop();
  SignalStop(const SignalStop&) = delete;
  SignalStop& operator=(const SignalStop&) = delete;

  std::stop_token token() const { return stop_.get_token(); }

 private:
  std::stop_source stop_;
  int pipe_[2] = {-1, -1};
  std::thread waiter_;
};

}  // namespace lccp::app
