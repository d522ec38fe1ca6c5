// The binary killed or interrupted at random moments: `kill -9` leaves no
// partial or stray file, and a frame whose cloud exists has all its outputs
// (the cloud is named last: atomic_file.hpp); SIGINT from main's first
// millisecond on ends with a valid summary and whole frames only.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.hpp"
#include "lccp/io/cloud_io.hpp"
#include "test_files.hpp"

extern char** environ;

namespace lccp {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const fs::path kData = LCCP_TEST_DATA_DIR;
const fs::path kRecording = fs::path(LCCP_TEST_DATA_DIR) / ".." / ".." / "recordings" / "mosd_scenes.oni";

// The binary started directly (no timeout wrapper, so signals reach it), its
// output discarded.
pid_t start_lccp(const std::vector<std::string>& args) {
  std::vector<std::string> argv_text{LCCP_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  return test::spawn_process(std::move(argv_text), "/dev/null", "/dev/null");
}

// Waits for the process; returns its exit code, or 1000 + signal if a signal killed it.
int wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

// Runs to the end once; returns the wall time, so kills can fall anywhere in a run.
std::chrono::microseconds full_run(const std::vector<std::string>& args) {
  const auto start = Clock::now();
  EXPECT_EQ(wait_for(start_lccp(args)), 0);
  return std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start);
}

// Whether the process catches the signal yet: SigCgt in /proc/PID/status (proc(5)).
bool catches(pid_t pid, int signal_number) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (signal_number - 1)) & 1;
  }
  return false;
}

// Waits (at most 30 s) until main has installed its handlers: before main the
// dynamic loader runs (about 4 ms unloaded) and no program can catch a signal.
void wait_until_catching(pid_t pid, int signal_number) {
  const auto give_up = Clock::now() + std::chrono::seconds(30);
  while (!catches(pid, signal_number) && Clock::now() < give_up) std::this_thread::sleep_for(std::chrono::microseconds(50));
  EXPECT_TRUE(catches(pid, signal_number)) << "the process never installed its handler";
}

int run_and_signal(const std::vector<std::string>& args, std::chrono::microseconds after, int signal_number) {
  const pid_t pid = start_lccp(args);
  if (signal_number != SIGKILL) wait_until_catching(pid, signal_number);
  std::this_thread::sleep_for(after);
  kill(pid, signal_number);
  return wait_for(pid);
}

bool is_complete_png(const fs::path& path) {
  const std::string bytes = test::read_bytes(path);
  return bytes.size() > 20 && bytes.compare(1, 3, "PNG") == 0 && bytes.compare(bytes.size() - 8, 4, "IEND") == 0;
}

bool is_complete_labelled_pcd(const fs::path& path) {
  try {
    return read_cloud(path).labels.has_value();
  } catch (const std::exception&) {
    return false;
  }
}

// Output stems and their extensions; fails on any file that is not a frame output or the summary.
std::map<std::string, std::set<std::string>> frame_outputs(const fs::path& dir) {
  std::map<std::string, std::set<std::string>> stems;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path name = entry.path().filename();
    if (name == "summary.json") continue;
    const std::string ext = name.extension().string();
    EXPECT_TRUE(ext == ".pcd" || ext == ".png") << "stray file " << name;
    stems[name.stem().string()].insert(ext);
  }
  return stems;
}

// What a kill -9 may leave: whole files, and every frame with a cloud has its image.
void expect_whole_files_and_the_cloud_last(const fs::path& dir) {
  for (const auto& [stem, extensions] : frame_outputs(dir)) {
    if (extensions.contains(".pcd")) {
      EXPECT_TRUE(extensions.contains(".png")) << "frame " << stem << " has its cloud but not its image";
      EXPECT_TRUE(is_complete_labelled_pcd(dir / (stem + ".pcd"))) << stem;
    }
    if (extensions.contains(".png")) {
      EXPECT_TRUE(is_complete_png(dir / (stem + ".png"))) << stem;
    }
  }
}

// What an interrupted run leaves: whole frames only.
void expect_whole_frames(const fs::path& dir) {
  expect_whole_files_and_the_cloud_last(dir);
  for (const auto& [stem, extensions] : frame_outputs(dir)) {
    EXPECT_EQ(extensions, (std::set<std::string>{".pcd", ".png"})) << "frame " << stem << " is incomplete";
  }
}

void expect_valid_summary(const fs::path& path) {
  ASSERT_TRUE(fs::exists(path)) << "no summary";
  const std::string text = test::read_bytes(path);
  EXPECT_NE(text.find("\"frames_completed\""), std::string::npos) << text;
  EXPECT_EQ(text.substr(text.size() - 2), "}\n") << text;
}

TEST(Interrupt, SegmentKilledAtFiftyRandomMomentsLeavesWholeFilesWithTheCloudLast) {
  const fs::path dir = test::scratch_dir("kill_segment");
  const std::vector<std::string> args{"segment", (kData / "mosd_test34.pcd").string(), "-o", (dir / "out.pcd").string(),
                                      "--png", (dir / "out.png").string()};
  const auto run_time = full_run(args);
  std::mt19937 random(9);
  int complete = 0;
  for (int run = 0; run < 50; ++run) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::chrono::microseconds after(std::uniform_int_distribution<long>(0, run_time.count() * 6 / 5)(random));
    run_and_signal(args, after, SIGKILL);
    const auto outputs = frame_outputs(dir);
    SCOPED_TRACE("killed after " + std::to_string(after.count()) + " us");
    if (outputs.empty()) continue;
    expect_whole_files_and_the_cloud_last(dir);
    complete += outputs.begin()->second.size() == 2;
  }
  RecordProperty("runs_with_outputs", complete);
}

TEST(Interrupt, ReplayKilledAtFiftyRandomMomentsLeavesWholeFilesWithTheCloudLast) {
  const fs::path dir = test::scratch_dir("kill_replay");
  const std::vector<std::string> args{"replay", kRecording.string(), "--frames", "4", "--save", "pcd,png",
                                      "-o", dir.string(), "--quiet"};
  const auto run_time = full_run(args);
  std::mt19937 random(11);
  for (int run = 0; run < 50; ++run) {
    fs::remove_all(dir);
    const std::chrono::microseconds after(std::uniform_int_distribution<long>(0, run_time.count() * 6 / 5)(random));
    run_and_signal(args, after, SIGKILL);
    SCOPED_TRACE("killed after " + std::to_string(after.count()) + " us");
    if (!fs::exists(dir)) continue;
    expect_whole_files_and_the_cloud_last(dir);
    if (fs::exists(dir / "summary.json")) expect_valid_summary(dir / "summary.json");
  }
}

TEST(Interrupt, ReplayInterruptedFromTheFirstMillisecondEndsWithAValidSummary) {
  const fs::path dir = test::scratch_dir("sigint_replay");
  const std::vector<std::string> args{"replay", kRecording.string(), "--save", "pcd,png", "-o", dir.string(), "--quiet"};
  for (const int ms : {0, 1, 2, 3, 5, 10, 20, 50, 100, 200, 500, 1000}) {
    SCOPED_TRACE("SIGINT " + std::to_string(ms) + " ms after main installed its handler");
    fs::remove_all(dir);
    const int code = run_and_signal(args, std::chrono::milliseconds(ms), SIGINT);
    EXPECT_TRUE(code == 130 || code == 0) << "exit " << code << " (1000 + n: killed by signal n)";
    expect_valid_summary(dir / "summary.json");
    expect_whole_frames(dir);
  }
}

// Starts the binary with stdout and stderr into files in `dir`; once it catches
// `signal_number` and has written its first frame into dir/out (or 120 s have
// passed), signals it. Returns the exit code (1000 + n: killed by signal n).
int signal_after_first_frame(const std::vector<std::string>& args, const fs::path& dir, int signal_number) {
  std::vector<std::string> argv_text{LCCP_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  const pid_t pid = test::spawn_process(std::move(argv_text), dir / "stdout", dir / "stderr");
  wait_until_catching(pid, signal_number);
  const auto give_up = Clock::now() + std::chrono::seconds(120);
  const auto has_frame = [&] {
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(dir / "out", error))
      if (entry.path().extension() == ".png") return true;
    return false;
  };
  while (!has_frame() && Clock::now() < give_up) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kill(pid, signal_number);
  return wait_for(pid);
}

// README, exit status: 130 "stopped by Ctrl-C or SIGTERM before the end", live
// runs as much as replays, with the same warning.
TEST(Interrupt, LiveStoppedBySigintOrSigtermExits130AndSaysSo) {
  for (const int signal_number : {SIGINT, SIGTERM}) {
    SCOPED_TRACE("signal " + std::to_string(signal_number));
    const fs::path dir = test::scratch_dir("stop_live");
    const int code = signal_after_first_frame({"live", "--uri", "virtual://synthetic", "--seconds", "60", "-o",
                                               (dir / "out").string(), "--quiet"},
                                              dir, signal_number);
    EXPECT_EQ(code, 130) << "(1000 + n: killed by signal n)";
    const std::string err = test::read_bytes(dir / "stderr");
    EXPECT_NE(err.find("interrupted after "), std::string::npos) << err;
    const std::string summary = test::read_bytes(dir / "out" / "summary.json");
    test::expect_counts_add_up(summary, test::read_bytes(dir / "stdout"));
    EXPECT_GE(test::json_number(summary, "frames_completed"), 1) << summary;
  }
}

// A replay never drops a frame, a stopped one included: the frame read while the
// stop came is not received.
TEST(Interrupt, ReplayStoppedMidwayDropsNothing) {
  const fs::path dir = test::scratch_dir("stop_replay");
  const int code = signal_after_first_frame({"replay", kRecording.string(), "-o", (dir / "out").string(), "--quiet"},
                                            dir, SIGINT);
  EXPECT_EQ(code, 130) << "(1000 + n: killed by signal n)";
  const std::string summary = test::read_bytes(dir / "out" / "summary.json");
  const std::string out = test::read_bytes(dir / "stdout");
  test::expect_counts_add_up(summary, out);
  EXPECT_EQ(test::json_number(summary, "frames_dropped"), 0) << summary;
  EXPECT_LT(test::json_number(summary, "frames_completed"), 62) << "the stop came after the end";
  EXPECT_NE(out.find(" + 0 dropped"), std::string::npos) << out;
  EXPECT_NE(test::read_bytes(dir / "stderr").find("interrupted after "), std::string::npos);
}

}  // namespace
}  // namespace lccp
