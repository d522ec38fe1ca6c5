// The rosbag frame source and bag recording (lccp/capture/rosbag.hpp): a bag made
// from the bundled recording replays with the recording's depth and labels, and
// bags it cannot read fail with one line naming the topic. Built with ROS only.
#ifdef LCCP_HAVE_ROSBAG
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <tuple>
#include <utility>
#include <vector>

#include "expect_error.hpp"
#include "lccp/capture/open_source.hpp"
#include "lccp/capture/rosbag.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/pipeline/pipeline.hpp"
#include "test_files.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

const fs::path kRecording = fs::path(LCCP_TEST_DATA_DIR) / ".." / ".." / "recordings" / "mosd_scenes.oni";
constexpr std::uint64_t kRecordingFrames = 62;
constexpr std::uint64_t kSegmentedFrames = 12;

struct FrameLabels {
  std::uint64_t index = 0;
  std::uint64_t timestamp_us = 0;
  Labels labels;
  Labels objects;
};

// What `lccp replay` computes: the pipeline over the source, stable ids and all.
std::vector<FrameLabels> replay_labels(std::unique_ptr<FrameSource> source, const std::string& config) {
  const SceneSegmenter segmenter(load_preset_or_file(config));
  std::vector<FrameLabels> frames;
  const PipelineOutcome outcome = Pipeline(segmenter, {2}).run(*source, [&](FrameResult& result) {
    EXPECT_EQ(result.error, "");
    frames.push_back({result.frame.index, result.frame.timestamp_us, result.segmentation.labels,
                      result.segmentation.objects});
  });
  EXPECT_EQ(outcome.error, "");
  return frames;
}

fs::path record_recording(const fs::path& dir) {
  const fs::path bag = dir / "mosd_scenes.bag";
  auto oni = open_source({kRecording.string()});
  EXPECT_EQ(record_bag(*oni, bag), kRecordingFrames);
  return bag;
}

TEST(RosbagSource, RecordedBagHoldsEveryDepthFrameBitForBit) {
  const fs::path bag = record_recording(test::scratch_dir("lccp_rosbag"));
  auto oni = open_source({kRecording.string()});
  auto from_bag = open_source({bag.string()});
  EXPECT_EQ(from_bag->frame_count(), kRecordingFrames);
  EXPECT_FALSE(from_bag->is_live());
  std::uint64_t frames = 0;
  std::uint64_t first_oni_us = 0, first_bag_us = 0;
  while (std::optional<Frame> expected = oni->next({})) {
    std::optional<Frame> actual = from_bag->next({});
    ASSERT_TRUE(actual && actual->depth) << "frame " << frames;
    if (frames == 0) std::tie(first_oni_us, first_bag_us) = std::pair(expected->timestamp_us, actual->timestamp_us);
    EXPECT_EQ(actual->index, frames);
    EXPECT_EQ(actual->timestamp_us - first_bag_us, expected->timestamp_us - first_oni_us);  // the same spacing
    EXPECT_EQ(actual->depth->width, expected->depth->width);
    EXPECT_EQ(actual->depth->height, expected->depth->height);
    EXPECT_EQ(actual->depth->horizontal_fov_rad, expected->depth->horizontal_fov_rad);  // bit for bit
    EXPECT_EQ(actual->depth->vertical_fov_rad, expected->depth->vertical_fov_rad);
    EXPECT_TRUE(actual->depth->depth_mm == expected->depth->depth_mm) << "frame " << frames;
    ++frames;
  }
  EXPECT_EQ(frames, kRecordingFrames);
  EXPECT_FALSE(from_bag->next({}));
  fs::remove_all(bag.parent_path());
}

TEST(RosbagSource, ReplayOfTheBagGivesTheRecordingsLabels) {
  const fs::path bag = record_recording(test::scratch_dir("lccp_rosbag"));
  const SourceLimits first{kSegmentedFrames, {}};
  for (const std::string config : {"p1", "robot"}) {
    const std::vector<FrameLabels> expected = replay_labels(open_source({kRecording.string()}, {first}), config);
    const std::vector<FrameLabels> actual = replay_labels(open_source({bag.string()}, {first}), config);
    ASSERT_EQ(actual.size(), kSegmentedFrames);
    ASSERT_EQ(expected.size(), kSegmentedFrames);
    for (std::size_t i = 0; i < actual.size(); ++i) {
      EXPECT_EQ(actual[i].index, expected[i].index);
      EXPECT_EQ(actual[i].timestamp_us - actual[0].timestamp_us, expected[i].timestamp_us - expected[0].timestamp_us);
      EXPECT_TRUE(actual[i].labels == expected[i].labels) << config << ", frame " << i;
      EXPECT_TRUE(actual[i].objects == expected[i].objects) << config << ", frame " << i;
      EXPECT_GT(*std::max_element(actual[i].labels.begin(), actual[i].labels.end()), 1u);
    }
  }
  fs::remove_all(bag.parent_path());
}

std::uint64_t unix_time_us() {
  const auto since_epoch = std::chrono::system_clock::now().time_since_epoch();
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(since_epoch).count());
}

// A bag is stamped like one recorded from a sensor: the time it was written plus
// each frame's offset in the recording, not the .oni's timestamps counted from 0
// (which ROS tools show as 1970).
TEST(RosbagSource, RecordedBagIsStampedFromTheTimeOfRecording) {
  constexpr std::uint64_t kYear2000Us = 946'684'800ull * 1'000'000;  // 2000-01-01T00:00:00Z
  const std::uint64_t before_us = unix_time_us();
  const fs::path bag = record_recording(test::scratch_dir("lccp_rosbag"));
  const std::uint64_t after_us = unix_time_us();
  auto oni = open_source({kRecording.string()});
  auto from_bag = open_source({bag.string()});
  std::vector<std::uint64_t> stamps, oni_stamps;
  while (std::optional<Frame> frame = from_bag->next({})) {
    stamps.push_back(frame->timestamp_us);  // the header stamp, in microseconds
    oni_stamps.push_back(oni->next({})->timestamp_us);
  }
  ASSERT_EQ(stamps.size(), kRecordingFrames);
  EXPECT_GE(stamps.front(), before_us);
  EXPECT_LE(stamps.front(), after_us);
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    EXPECT_GT(stamps[i], kYear2000Us) << "frame " << i;
    if (i > 0) {
      EXPECT_GT(stamps[i], stamps[i - 1]) << "frame " << i;
    }
    EXPECT_EQ(stamps[i] - stamps[0], oni_stamps[i] - oni_stamps[0]) << "frame " << i;
  }
  fs::remove_all(bag.parent_path());
}

TEST(RosbagSource, RecordingIsAtomicAndNeedsDepth) {
  const fs::path dir = test::scratch_dir("lccp_rosbag");
  test::expect_lccp_error([&] { record_bag(*open_source({kRecording.string()}), dir / "out.txt"); }, {"out.txt", ".bag"});
  const fs::path cloud = fs::path(LCCP_TEST_DATA_DIR) / "mosd_test2.pcd";
  test::expect_lccp_error([&] { record_bag(*open_source({cloud.string()}), dir / "clouds.bag"); },
                          {"depth frames", "point clouds"});
  std::stop_source stopped;
  stopped.request_stop();
  test::expect_lccp_error([&] { record_bag(*open_source({kRecording.string()}), dir / "none.bag", stopped.get_token()); },
                          {"no frames", "none.bag"});
  EXPECT_TRUE(fs::is_empty(dir)) << "a failed recording left a file";
  fs::remove_all(dir);
}

// tests/ros/make_test_bag.py (the project's python3, Debian's, with python3-rosbag)
// writes one topic of each kind the source reads or refuses.
class RosbagKinds : public ::testing::Test {
 protected:
  void SetUp() override {
    bag_ = test::scratch_dir("lccp_rosbag") / "kinds.bag";
    const fs::path script = fs::path(LCCP_TEST_DATA_DIR) / ".." / "ros" / "make_test_bag.py";
    const std::string command = std::string(LCCP_PYTHON) + " " + script.string() + " " + bag_.string();
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
  }
  void TearDown() override { fs::remove_all(bag_.parent_path()); }
  fs::path bag_;
};

TEST_F(RosbagKinds, FirstDepthTopicIsTheDefaultAnd32FC1BecomesMillimetres) {
  auto source = open_source({bag_.string()});
  std::optional<Frame> frame = source->next({});
  ASSERT_TRUE(frame && frame->depth);
  EXPECT_EQ(frame->timestamp_us, 5250000u);
  EXPECT_EQ(frame->depth->depth_mm, (std::vector<std::uint16_t>{500, 0, 1250, 0}));
  EXPECT_FLOAT_EQ(frame->depth->horizontal_fov_rad, 2 * std::atan(2.0f / (2 * 2.0f)));  // fx = 2 px, 2 px wide
  EXPECT_FALSE(source->next({}));
}

TEST_F(RosbagKinds, PointCloud2TopicGivesPointsAndColours) {
  auto source = open_rosbag(bag_, "points");  // a topic without its leading slash is found too
  std::optional<Frame> frame = source->next({});
  ASSERT_TRUE(frame && !frame->depth);
  ASSERT_EQ(frame->cloud.size(), 2u);
  EXPECT_EQ(frame->cloud.points[1], Eigen::Vector3f(4, 5, 6));
  EXPECT_EQ(frame->cloud.colors, (std::vector<std::uint32_t>{0xFF0000, 0x00FF00}));
}

TEST_F(RosbagKinds, UnreadableTopicsFailWithOneLineNamingThem) {
  test::expect_lccp_error([&] { open_rosbag(bag_, "/missing"); }, {"kinds.bag", "no topic /missing", "/points"});
  test::expect_lccp_error([&] { open_rosbag(bag_, "/chatter"); }, {"/chatter", "std_msgs/String"});
  test::expect_lccp_error([&] { open_rosbag(bag_, "/cam/depth/camera_info"); }, {"sensor_msgs/CameraInfo"});
  auto bad = open_rosbag(bag_, "/bad/depth/image_raw");
  test::expect_lccp_error([&] { bad->next({}); }, {"/bad/depth/image_raw", "encoding rgb8", "16UC1"});
  test::expect_lccp_error([&] { open_rosbag(bag_.parent_path() / "absent.bag"); }, {"absent.bag", "no such file"});
}

}  // namespace
}  // namespace lccp
#endif  // LCCP_HAVE_ROSBAG
