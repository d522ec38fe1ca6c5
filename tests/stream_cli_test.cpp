// End-to-end tests of `lccp record`, `lccp replay` and `lccp live` through the
// real binary and OpenNI2, on the project's virtual sensor.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "test_clouds.hpp"
#include "lccp/io/cloud_io.hpp"
#include "test_files.hpp"

namespace lccp {
namespace {

using namespace test;  // run_lccp, expect_error and the other runner helpers

constexpr int kErrorTimeoutSeconds = kQuickTimeoutSeconds;  // every failure must end within this

// The per-frame outputs in a folder with the given suffix, sorted by name.
std::vector<std::string> frame_files(const fs::path& dir, const std::string& suffix) {
  std::vector<std::string> names;
  for (const std::string& name : list_dir(dir)) {
    if (name.rfind("frame_", 0) == 0 && name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      names.push_back(name);
    }
  }
  return names;
}

// frame_<index>_<timestamp>us.<ext> -> (index, timestamp)
std::pair<std::uint64_t, std::uint64_t> index_and_timestamp(const std::string& name) {
  std::smatch match;
  const std::regex pattern("frame_([0-9]+)_([0-9]+)us\\.");
  if (!std::regex_search(name, match, pattern)) {
    ADD_FAILURE() << "output name without index and timestamp: " << name;
    return {0, 0};
  }
  return {std::stoull(match[1]), std::stoull(match[2])};
}

// One recording of the virtual sensor's synthetic scene, made once with `lccp record`.
class StreamCliTest : public LccpBinaryTest {
 protected:
  StreamCliTest() : LccpBinaryTest("lccp_stream_cli") {}

  static constexpr int kRecordedFrames = 15;

  static void SetUpTestSuite() {
    shared_ = new fs::path(test::scratch_root() / "lccp_stream_cli");
    fs::create_directories(*shared_);
    record_result_ = new RunResult(run_lccp(*shared_, {"record", "--uri", "virtual://synthetic", "-o",
                                                       recording().string(), "--frames", std::to_string(kRecordedFrames),
                                                       "--log-level", "warn"}));
  }
  static void TearDownTestSuite() {
    delete shared_;
    delete record_result_;
  }
  static fs::path recording() { return *shared_ / "synthetic.oni"; }
  // Fails the test (rather than letting it run on no file) if `lccp record` did not
  // make the shared recording.
  static void require_recording() {
    std::error_code error;
    ASSERT_GT(fs::file_size(recording(), error), 0u) << "no recording: " << describe(*record_result_);
  }

  // Fails within the error timeout: exit 1, one line naming every phrase, no crash.
  void expect_quick_error(const std::vector<std::string>& args, std::initializer_list<std::string> phrases) {
    expect_error(run(args, kErrorTimeoutSeconds), phrases);
  }

  static inline fs::path* shared_ = nullptr;
  static inline RunResult* record_result_ = nullptr;
};

TEST_F(StreamCliTest, RecordWritesTheFramesAskedFor) {
  expect_success(*record_result_);
  EXPECT_NE(record_result_->out.find("recorded " + std::to_string(kRecordedFrames) + " depth frames (640x480 @ 30 Hz)"),
            std::string::npos)
      << record_result_->out;
}

TEST_F(StreamCliTest, ReplayGivesEveryFrameInOrderWithIncreasingTimestamps) {
  ASSERT_NO_FATAL_FAILURE(require_recording());
  const fs::path out = work_ / "out";
  const RunResult r = run({"replay", recording().string(), "-o", out.string(), "--save", "pcd,png", "--quiet"});
  expect_success(r);
  const std::string summary = read_bytes(out / "summary.json");
  EXPECT_EQ(json_number(summary, "frames_completed"), kRecordedFrames) << summary;
  EXPECT_EQ(json_number(summary, "frames_dropped"), 0) << summary;
  EXPECT_EQ(json_number(summary, "frames_failed"), 0) << summary;
  const std::vector<std::string> pngs = frame_files(out, ".png");
  const std::vector<std::string> pcds = frame_files(out, ".pcd");
  ASSERT_EQ(pngs.size(), static_cast<std::size_t>(kRecordedFrames));
  ASSERT_EQ(pcds.size(), static_cast<std::size_t>(kRecordedFrames));
  for (std::size_t i = 0; i < pngs.size(); ++i) {
    const auto [index, timestamp] = index_and_timestamp(pngs[i]);
    EXPECT_EQ(index, i);
    if (i > 0) {
      EXPECT_GT(timestamp, index_and_timestamp(pngs[i - 1]).second);
    }
  }
  const std::string n = std::to_string(kRecordedFrames);
  EXPECT_NE(r.out.find("frames " + n + " received + 0 sensor gaps = " + n + " completed + 0 failed + 0 dropped"),
            std::string::npos)
      << r.out;
}

// The same segments; the replay's ids are stable across frames, segment's are 1..K.
TEST_F(StreamCliTest, ReplaySegmentsEqualSegmentOnTheSameFramesCloud) {
  ASSERT_NO_FATAL_FAILURE(require_recording());
  const fs::path out = work_ / "out";
  expect_success(run({"replay", recording().string(), "-o", out.string(), "--save", "pcd", "--frames", "3", "--quiet"}));
  const std::vector<std::string> pcds = frame_files(out, ".pcd");
  ASSERT_EQ(pcds.size(), 3u);
  for (const std::string& name : pcds) {
    const fs::path segmented = work_ / ("segment_" + name);
    expect_success(run({"segment", (out / name).string(), "-o", segmented.string()}));
    const LabelledCloud replayed = read_cloud(out / name);
    const LabelledCloud single = read_cloud(segmented);
    ASSERT_TRUE(replayed.labels && single.labels);
    EXPECT_TRUE(test::same_partition(*replayed.labels, *single.labels)) << name;
    EXPECT_GT(*std::max_element(replayed.labels->begin(), replayed.labels->end()), 3u) << name;
  }
}

TEST_F(StreamCliTest, LiveOnTheVirtualSensorForFiveSecondsAccountsForAboutOneHundredFiftyFrames) {
  const fs::path out = work_ / "out";
  const RunResult r = run({"live", "--uri", "virtual://synthetic", "--seconds", "5", "-o", out.string(), "--quiet", "--log-level", "warn"});
  expect_success(r);
  const std::string summary = read_bytes(out / "summary.json");
  const double completed = json_number(summary, "frames_completed");
  const double dropped = json_number(summary, "frames_dropped");
  const double received = json_number(summary, "frames_received");
  // 5 s of a 30 Hz sensor: every frame up to the last one taken is either segmented or
  // counted as dropped (frame numbers the sensor skipped included), and there are no
  // more than 5 s of them. How close to 150 that gets depends on how fast the machine
  // renders and takes frames: a sanitizer build takes one every second or so.
  EXPECT_GE(received, 1) << summary;
  expect_counts_add_up(summary, r.out);
  EXPECT_LE(completed + dropped, 152) << summary;
  // The synthetic scene (300k points, 100k voxels a frame) is heavier than mOSD: on
  // busy cores or in a sanitizer build most frames are dropped, and counted. How many
  // get through is a matter of speed; that some do and each is written is not.
  EXPECT_GE(completed, 1) << summary;
  EXPECT_EQ(frame_files(out, ".png").size(), static_cast<std::size_t>(completed));
}

TEST_F(StreamCliTest, LiveDeviceThatDisappearsFlushesItsFramesAndFails) {
  const fs::path out = work_ / "out";
  const RunResult r = run({"live", "--uri", "virtual://synthetic?frames=20", "-o", out.string(), "--quiet", "--log-level", "warn"},
                          kErrorTimeoutSeconds);
  SCOPED_TRACE(describe(r));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("lccp: error: ", 0), 0u);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  const std::string summary = read_bytes(out / "summary.json");
  // The device delivered 20 frames; every frame taken is segmented or counted as
  // dropped, and so is every frame number the sensor skipped while it was slow (a
  // loaded machine, a sanitizer build), so the sum is 20 or more. A frame the
  // reader was too slow to take before the device vanished is not received: the
  // error line says how many were, as the summary does (20 on an idle machine).
  const double received = json_number(summary, "frames_received");
  EXPECT_GE(received, 1) << summary;
  EXPECT_LE(received, 20) << summary;
  EXPECT_NE(r.err.find("disconnected after " + std::to_string(static_cast<int>(received)) + " frames"), std::string::npos);
  EXPECT_GE(json_number(summary, "frames_completed") + json_number(summary, "frames_dropped"), 20) << summary;
  expect_counts_add_up(summary, r.out);
  EXPECT_EQ(frame_files(out, ".png").size(), static_cast<std::size_t>(json_number(summary, "frames_completed")));
}

TEST_F(StreamCliTest, MissingRecording) {
  expect_quick_error({"replay", (work_ / "absent.oni").string()}, {"absent.oni", "no such file"});
}

TEST_F(StreamCliTest, CorruptRecording) {
  ASSERT_NO_FATAL_FAILURE(require_recording());
  std::string bytes = read_bytes(recording());
  for (std::size_t i = 0; i < 4096 && i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 131 + 7);
  write_bytes(work_ / "corrupt.oni", bytes);
  expect_quick_error({"replay", (work_ / "corrupt.oni").string()}, {"corrupt.oni"});
  write_bytes(work_ / "text.oni", "this is not a recording\n");
  expect_quick_error({"replay", (work_ / "text.oni").string()}, {"text.oni"});
}

TEST_F(StreamCliTest, RecordingWithoutDepthStream) {
  ASSERT_NO_FATAL_FAILURE(require_recording());
  // The recording's one stream, declared an IR stream instead: the node type
  // (2 = depth, 5 = IR) follows the node name "Depth\0" in its NodeAdded record.
  std::string bytes = read_bytes(recording());
  const std::size_t name = bytes.find(std::string("Depth\0", 6));
  ASSERT_NE(name, std::string::npos);
  ASSERT_EQ(bytes[name + 6], '\x02');
  bytes[name + 6] = '\x05';
  write_bytes(work_ / "infrared.oni", bytes);
  expect_quick_error({"replay", (work_ / "infrared.oni").string()}, {"infrared.oni", "no depth stream"});
}

TEST_F(StreamCliTest, RandomlyDamagedRecordingsNeverCrashOrHang) {
  ASSERT_NO_FATAL_FAILURE(require_recording());
  const std::string original = read_bytes(recording());
  std::uint64_t state = 12345;
  const auto random = [&] {  // xorshift64: the same damage on every run
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  for (int variant = 0; variant < 4; ++variant) {
    std::string bytes = original;
    for (int i = 0; i < 50; ++i) bytes[random() % bytes.size()] = static_cast<char>(random());
    const fs::path damaged = work_ / ("damaged" + std::to_string(variant) + ".oni");
    write_bytes(damaged, bytes);
    const RunResult r = run({"replay", damaged.string(), "--quiet", "--log-level", "error"}, kErrorTimeoutSeconds);
    SCOPED_TRACE(describe(r));
    EXPECT_EQ(r.signal, 0);
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1);
  }
}

TEST_F(StreamCliTest, TruncatedRecording) {
  ASSERT_NO_FATAL_FAILURE(require_recording());
  const std::string bytes = read_bytes(recording());
  write_bytes(work_ / "truncated.oni", bytes.substr(0, bytes.size() / 2));
  expect_quick_error({"replay", (work_ / "truncated.oni").string()}, {"truncated.oni"});
}

TEST_F(StreamCliTest, UriWithoutDevice) {
  expect_quick_error({"live", "--uri", "virtual://no-such-scene", "--frames", "3"}, {"virtual://no-such-scene"});
  expect_quick_error({"live", "--uri", "usb://0000/0000", "--frames", "3"}, {"usb://0000/0000"});
  expect_quick_error({"record", "--uri", "usb://0000/0000", "-o", (work_ / "x.oni").string(), "--frames", "3"},
                     {"usb://0000/0000"});
  EXPECT_FALSE(fs::exists(work_ / "x.oni"));
}

}  // namespace
}  // namespace lccp
