// main() of the test programs: GoogleTest's own, except that a skipped test fails the
// run. GoogleTest skips every test of a fixture whose SetUpTestSuite() fails or throws
// (and a test whose SetUp() calls GTEST_SKIP), and ctest counts a skipped test as
// passing; a test that cannot set up must fail instead (see tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <cstdio>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const int status = RUN_ALL_TESTS();
  const int skipped = ::testing::UnitTest::GetInstance()->skipped_test_count();
  if (skipped > 0) {
    std::fprintf(stderr,
                 "%d test(s) skipped: a fixture could not set up or a test skipped itself; "
                 "a skipped test fails the run\n",
                 skipped);
    return 1;
  }
  return status;
}
