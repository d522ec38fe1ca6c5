// lccp_ros's own command line: --help prints the usage and exits 0 at once,
// without contacting a ROS master (there is none here: the master URI names a
// port nobody listens on, where the node would wait for one forever).
#ifdef LCCP_ROS_BINARY
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>

#include "cli_runner.hpp"
#include "test_files.hpp"

namespace lccp {
namespace {

TEST(RosCli, HelpPrintsTheUsageWithoutAMaster) {
  const std::filesystem::path dir = test::scratch_dir("ros_help");
  ::setenv("ROS_MASTER_URI", "http://127.0.0.1:9", 1);  // the discard port: no master
  for (const char* flag : {"--help", "-h"}) {
    SCOPED_TRACE(flag);
    const pid_t pid = test::spawn_process({"timeout", "-k", "5", std::to_string(test::kQuickTimeoutSeconds),
                                           LCCP_ROS_BINARY, flag},
                                          dir / "stdout", dir / "stderr");
    ASSERT_GT(pid, 0);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "124: it waited for a master";
    const std::string out = test::read_bytes(dir / "stdout");
    EXPECT_EQ(out.rfind("Usage: lccp_ros", 0), 0u) << out;
    EXPECT_NE(out.find("~config"), std::string::npos) << out;
    EXPECT_EQ(test::read_bytes(dir / "stderr"), "");
  }
}

}  // namespace
}  // namespace lccp
#endif
