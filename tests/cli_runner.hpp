#pragma once
// Runs the real `lccp` binary for end-to-end tests: stdout, stderr and the exit
// status captured, a timeout against hangs, and checks for the one-line errors.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "test_files.hpp"

extern char** environ;

namespace lccp::test {

namespace fs = std::filesystem;

inline const fs::path kBinary = LCCP_BINARY;

// Limits against hangs, not measures of speed: generous enough that a loaded machine or
// a sanitizer build (several times slower) never reaches them.
inline constexpr int kRunTimeoutSeconds = 240;   // any run
inline constexpr int kQuickTimeoutSeconds = 60;  // a run that fails at once or does little

struct RunResult {
  std::string command;  // for failure messages
  int exit_code = -1;   // -1 if the process did not exit normally
  int signal = 0;       // the signal that killed it, 0 if none
  std::string out;
  std::string err;
};



// Starts argv_text[0] (searched on PATH) with the other words as arguments,
// without a shell: stdin from /dev/null, stdout and stderr into the given files
// (created or truncated; "/dev/null" discards). Returns the pid, or -1 after
// recording a test failure.
inline pid_t spawn_process(std::vector<std::string> argv_text, const fs::path& out_path, const fs::path& err_path) {
  std::vector<char*> argv;
  for (std::string& arg : argv_text) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int error = posix_spawnp(&pid, argv_text[0].c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error == 0) return pid;
  ADD_FAILURE() << "cannot start " << argv_text[0] << ": " << std::strerror(error);
  return -1;
}

// Runs `timeout SECONDS lccp ARGS...` without a shell, stdin from /dev/null and
// stdout/stderr into files under `capture_dir`. timeout(1) re-raises a signal
// that killed lccp, so a crash shows up as `signal`; a hang exits 124.
inline RunResult run_lccp(const fs::path& capture_dir, const std::vector<std::string>& args,
                          int timeout_seconds = kRunTimeoutSeconds) {
  RunResult result;
  result.command = kBinary.string();
  for (const std::string& arg : args) result.command += " " + arg;

  static int run_number = 0;
  const std::string tag = std::to_string(run_number++);
  const fs::path out_path = capture_dir / ("stdout" + tag);
  const fs::path err_path = capture_dir / ("stderr" + tag);

  std::vector<std::string> argv_text = {"timeout", "-k", "5", std::to_string(timeout_seconds), kBinary.string()};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  const pid_t pid = spawn_process(std::move(argv_text), out_path, err_path);
  if (pid < 0) return result;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      ADD_FAILURE() << "waitpid failed for " << result.command;
      return result;
    }
  }
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  result.out = read_bytes(out_path);
  result.err = read_bytes(err_path);
  EXPECT_NE(result.exit_code, 124) << "timed out after " << timeout_seconds << " s: " << result.command;
  return result;
}

inline std::string describe(const RunResult& r) {
  return r.command + "\n  exit " + std::to_string(r.exit_code) + ", signal " + std::to_string(r.signal) +
         "\n  stdout: [" + r.out + "]\n  stderr: [" + r.err + "]";
}

// An lccp::Error: exit 1, nothing on stdout, exactly one stderr line
// "lccp: error: ..." containing every phrase.
inline void expect_error(const RunResult& r, std::initializer_list<std::string> phrases) {
  SCOPED_TRACE(describe(r));
  EXPECT_EQ(r.signal, 0) << "killed by a signal";
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err.rfind("lccp: error: ", 0), 0u) << "stderr does not start with 'lccp: error: '";
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr is not exactly one line";
  EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << "stderr does not end with a newline";
  for (const std::string& phrase : phrases) {
    EXPECT_NE(r.err.find(phrase), std::string::npos) << "stderr does not mention '" << phrase << "'";
  }
}

// A usage error: exit 2, nothing on stdout, exactly one stderr line
// "lccp: error: ..." containing every phrase.
inline void expect_usage_error(const RunResult& r, std::initializer_list<std::string> phrases = {}) {
  SCOPED_TRACE(describe(r));
  EXPECT_EQ(r.signal, 0) << "killed by a signal";
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err.rfind("lccp: error: ", 0), 0u) << "stderr does not start with 'lccp: error: '";
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr is not exactly one line";
  for (const std::string& phrase : phrases) {
    EXPECT_NE(r.err.find(phrase), std::string::npos) << "stderr does not mention '" << phrase << "'";
  }
}

inline void expect_success(const RunResult& r) {
  SCOPED_TRACE(describe(r));
  EXPECT_EQ(r.signal, 0) << "killed by a signal";
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
}

inline std::set<std::string> list_dir(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

// "key value" from a line like "..., supervoxels 2468, segments 3 | ...".
inline unsigned long summary_count(const std::string& summary, const std::string& key) {
  std::smatch match;
  const std::regex pattern("\\b" + key + " ([0-9]+)");
  if (!std::regex_search(summary, match, pattern)) {
    ADD_FAILURE() << "no '" << key << " N' in summary: " << summary;
    return 0;
  }
  return std::stoul(match[1]);
}

// The number after "key": in one-line JSON output.
inline double json_number(const std::string& json, const std::string& key) {
  std::smatch match;
  const std::regex pattern("\"" + key + "\": *(-?[0-9][0-9.eE+-]*)");
  if (!std::regex_search(json, match, pattern)) {
    ADD_FAILURE() << "no number \"" << key << "\" in: " << json;
    return -1.0;
  }
  return std::stod(match[1]);
}

// The counts of a run's JSON (summary.json, report.json) add up (received +
// sensor gaps = completed + failed + dropped), and `text` (stdout, report.html)
// says the same numbers the way the summary line does.
inline void expect_counts_add_up(const std::string& json, const std::string& text) {
  const auto n = [&](const char* key) { return static_cast<long>(json_number(json, key)); };
  EXPECT_EQ(n("frames_received") + n("sensor_gaps"), n("frames_completed") + n("frames_failed") + n("frames_dropped"))
      << json;
  const std::string counts = std::to_string(n("frames_received")) + " received + " + std::to_string(n("sensor_gaps")) +
                             " sensor gaps = " + std::to_string(n("frames_completed")) + " completed + " +
                             std::to_string(n("frames_failed")) + " failed + " + std::to_string(n("frames_dropped")) +
                             " dropped";
  EXPECT_NE(text.find(counts), std::string::npos) << "no '" << counts << "' in: " << text;
}

// A test that runs the binary, with a fresh scratch folder (scratch_dir): work/ for
// the test's files, capture/ for the runs' stdout and stderr.
class LccpBinaryTest : public ::testing::Test {
 protected:
  explicit LccpBinaryTest(std::string prefix) : prefix_(std::move(prefix)) {}

  void SetUp() override {
    root_ = scratch_dir(prefix_);
    work_ = root_ / "work";
    capture_ = root_ / "capture";
    fs::create_directories(work_);
    fs::create_directories(capture_);
  }
  RunResult run(const std::vector<std::string>& args, int timeout_seconds = kRunTimeoutSeconds) {
    return run_lccp(capture_, args, timeout_seconds);
  }

  std::string prefix_;
  fs::path root_, work_, capture_;
};

}  // namespace lccp::test
