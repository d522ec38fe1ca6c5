#pragma once
// Ctrl-C (SIGINT) and SIGTERM as a request to stop cleanly.
#include <atomic>

namespace lccp::app {

// Installs the handlers for the whole process; main calls it before any other
// work, so a signal from the first millisecond on is a stop request. The first
// signal only stores an atomic (async-signal-safe); a second one restores the
// default action and re-raises it, so a second Ctrl-C ends a stuck run at once.
void install_stop_handlers();

// The stop request set by those handlers, for the commands that watch it.
class StopOnSignal {
 public:
  const std::atomic<bool>& flag() const;
  bool requested() const { return flag().load(); }
};

}  // namespace lccp::app
