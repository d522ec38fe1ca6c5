#pragma once
// Whole-file reads and writes for tests that build or inspect files byte by byte.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

namespace lccp::test {

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << "cannot write " << path;
}

// The one folder of this test process's scratch files: <tmp>/lccp_tests_<pid>, so
// tests can run in parallel processes. main() removes it when every test passed and
// keeps it, naming it, when one failed (no_skip_main.cpp).
inline std::filesystem::path scratch_root() {
  return std::filesystem::temp_directory_path() / ("lccp_tests_" + std::to_string(::getpid()));
}

// A fresh, empty folder for the running test: <scratch_root>/<prefix>_<suite>_<test>.
inline std::filesystem::path scratch_dir(const std::string& prefix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      scratch_root() / (prefix + "_" + info->test_suite_name() + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace lccp::test
