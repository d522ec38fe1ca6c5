#include "stop_signal.hpp"

#include <csignal>

namespace lccp::app {
namespace {

// A signal handler can reach nothing but globals: this flag is the one.
std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void request_stop(int signal_number) {
  if (!stop_requested.exchange(true)) return;
  std::signal(signal_number, SIG_DFL);  // both async-signal-safe (signal-safety(7))
  std::raise(signal_number);
}

}  // namespace

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

const std::atomic<bool>& StopOnSignal::flag() const { return stop_requested; }

}  // namespace lccp::app
