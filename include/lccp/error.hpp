#pragma once
#include <stdexcept>
#include <string>

namespace lccp {

// Every failure the user can cause (bad file, bad parameter, empty cloud) is an
// lccp::Error whose message is one line naming the problem; the CLI prints it
// and exits non-zero.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace lccp
