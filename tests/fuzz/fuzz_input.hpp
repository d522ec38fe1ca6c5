#pragma once
// Shared by the fuzz targets: a thrown lccp::Error is the normal answer to bad
// input; any other exception escapes LLVMFuzzerTestOneInput, terminates the
// process and so counts as a finding, like a crash or a sanitizer report.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>

#include "lccp/error.hpp"

namespace lccp::fuzz {

inline std::span<const std::uint8_t> bytes_of(const std::uint8_t* data, std::size_t size) { return {data, size}; }

inline std::string_view text_of(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Calls `parse` and swallows lccp::Error only.
template <class F>
int expect_success_or_lccp_error(F&& parse) {
  try {
    parse();
  } catch (const Error&) {
  }
  return 0;
}

// The input written to one file per process (so parallel fuzzing jobs do not
// share it), for entry points that take a path; removed at exit.
class InputFile {
 public:
  explicit InputFile(const std::string& suffix)
      : path_(std::filesystem::temp_directory_path() /
              ("lccp_fuzz_" + std::to_string(::getpid()) + suffix)) {}
  ~InputFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path_;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace lccp::fuzz
