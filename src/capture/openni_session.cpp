#include "lccp/capture/openni_session.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <mutex>

#include <OpenNI.h>

#include "lccp/error.hpp"

namespace lccp {
namespace {

// Points stdout at /dev/null for its lifetime.
class SilencedStdout {
 public:
  SilencedStdout() {
    std::fflush(stdout);
    saved_ = ::dup(STDOUT_FILENO);
    const int null_fd = ::open("/dev/null", O_WRONLY);
    if (saved_ >= 0 && null_fd >= 0) ::dup2(null_fd, STDOUT_FILENO);
    if (null_fd >= 0) ::close(null_fd);
  }
  ~SilencedStdout() {
    std::fflush(stdout);
    if (saved_ >= 0) {
      ::dup2(saved_, STDOUT_FILENO);
      ::close(saved_);
    }
  }
  SilencedStdout(const SilencedStdout&) = delete;
  SilencedStdout& operator=(const SilencedStdout&) = delete;

 private:
  int saved_ = -1;
};

void initialize_once() {
  const std::filesystem::path working_directory = std::filesystem::current_path();
  openni::Status status;
  {
    SilencedStdout silenced;
    status = openni::OpenNI::initialize();
  }
  std::error_code ignored;
  std::filesystem::current_path(working_directory, ignored);
  if (status != openni::STATUS_OK) throw Error("OpenNI2 failed to initialize: " + openni_error());
}

}  // namespace

void initialize_openni() {
  static std::once_flag once;
  std::call_once(once, initialize_once);  // a throw leaves the flag unset: the next call retries
}

std::string openni_error() {
  std::string message = openni::OpenNI::getExtendedError();
  for (char& c : message) {
    if (c == '\t' || c == '\n' || c == '\r') c = ' ';
  }
  const auto first = message.find_first_not_of(' ');
  const auto last = message.find_last_not_of(' ');
  return first == std::string::npos ? std::string("unknown OpenNI2 error") : message.substr(first, last - first + 1);
}

}  // namespace lccp
