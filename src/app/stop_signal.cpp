#include "stop_signal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <csignal>

#include "lccp/error.hpp"

namespace lccp::app {
namespace {

// A signal handler reaches nothing but globals: the pipe's write end and
// whether a signal came before.
std::atomic<int> signal_pipe{-1};
std::atomic<bool> signalled{false};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free);

extern "C" void on_stop_signal(int signal_number) {
  if (signalled.exchange(true)) {
    std::signal(signal_number, SIG_DFL);  // both async-signal-safe (signal-safety(7))
    std::raise(signal_number);
    return;
  }
  const char byte = 1;
  [[maybe_unused]] const ssize_t written = ::write(signal_pipe.load(), &byte, 1);
}

}  // namespace

SignalStop::SignalStop() {
  if (::pipe2(pipe_, O_CLOEXEC) != 0) throw Error("cannot create the signal pipe");
  signal_pipe.store(pipe_[1]);
  waiter_ = std::thread([this] {
    char byte = 0;
    if (::read(pipe_[0], &byte, 1) == 1 && byte == 1) stop_.request_stop();  // 0 bytes: closed by ~SignalStop
  });
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

SignalStop::~SignalStop() {
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  signal_pipe.store(-1);
  ::close(pipe_[1]);  // the waiter reads end-of-file and returns
  waiter_.join();
  ::close(pipe_[0]);
}

}  // namespace lccp::app
