// main() of the test programs: GoogleTest's own, except that a skipped test fails the
// run. GoogleTest skips every test of a fixture whose SetUpTestSuite() fails or throws
// (and a test whose SetUp() calls GTEST_SKIP), and ctest counts a skipped test as
// passing; a test that cannot set up must fail instead (see tests/CMakeLists.txt).
// After a run in which every test passed, the tests' scratch files are removed; after
// a failure they are kept, for a look at what the failing test wrote.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "test_files.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const int status = RUN_ALL_TESTS();
  const int skipped = ::testing::UnitTest::GetInstance()->skipped_test_count();
  const std::filesystem::path scratch = lccp::test::scratch_root();
  std::error_code ignored;
  if (status == 0 && skipped == 0) {
    std::filesystem::remove_all(scratch, ignored);
  } else if (std::filesystem::exists(scratch, ignored)) {
    std::fprintf(stderr, "the tests' scratch files are kept in %s\n", scratch.c_str());
  }
  if (skipped > 0) {
    std::fprintf(stderr,
                 "%d test(s) skipped: a fixture could not set up or a test skipped itself; "
                 "a skipped test fails the run\n",
                 skipped);
    return 1;
  }
  return status;
}
