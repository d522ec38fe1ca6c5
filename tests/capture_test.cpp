// Frame sources: depth-mode choice, back-projection against OpenNI2's own
// CoordinateConverter, .oni recordings made from the virtual sensor, device
// loss, and cloud files.
#include <gtest/gtest.h>

#include <OpenNI.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stop_token>
#include <thread>
#include <vector>

#include "lccp/capture/cloud_files.hpp"
#include "lccp/capture/open_source.hpp"
#include "lccp/capture/openni_session.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/error.hpp"
#include "lccp/synthetic/tabletop_scene.hpp"
#include "expect_error.hpp"
#include "codec_tail.hpp"
#include "test_files.hpp"
#include "virtual_uri.hpp"  // the virtual sensor's URI parser (lccp_virtual_uri)

namespace lccp {
namespace {

SourceLimits frames_limit(std::uint64_t frames) {
  SourceLimits limits;
  limits.max_frames = frames;
  return limits;
}

SourceLimits seconds_limit(double seconds) {
  SourceLimits limits;
  limits.max_seconds = seconds;
  return limits;
}


namespace fs = std::filesystem;

const fs::path kData = LCCP_TEST_DATA_DIR;

using test::expect_lccp_error;

// --- depth modes --------------------------------------------------------------------

TEST(DepthModes, ExactModeIsChosen) {
  const std::vector<DepthMode> offered{{320, 240, 30}, {640, 480, 60}, {640, 480, 30}};
  EXPECT_EQ(nearest_depth_mode(offered, {640, 480, 30}), 2u);
}

TEST(DepthModes, NearestSizeFirstThenRate) {
  const std::vector<DepthMode> offered{{320, 240, 30}, {640, 480, 60}, {1280, 1024, 30}, {640, 480, 25}};
  EXPECT_EQ(nearest_depth_mode(offered, {640, 480, 30}), 3u);  // same size; 25 Hz is nearer 30 than 60
  EXPECT_EQ(nearest_depth_mode({{320, 240, 30}, {1280, 1024, 30}}, {640, 480, 30}), 0u);
}

TEST(DepthModes, NoModeIsAnError) {
  expect_lccp_error([] { nearest_depth_mode({}, {}); }, {"no video mode"});
}

// --- back-projection ----------------------------------------------------------------

TEST(BackProjection, MatchesOpenNICoordinateConverterWithinHalfAMillimetre) {
  initialize_openni();
  openni::Device device;
  ASSERT_EQ(device.open("virtual://synthetic"), openni::STATUS_OK) << openni_error();
  openni::VideoStream stream;
  ASSERT_EQ(stream.create(device, openni::SENSOR_DEPTH), openni::STATUS_OK) << openni_error();
  ASSERT_EQ(stream.start(), openni::STATUS_OK);
  openni::VideoStream* streams[] = {&stream};
  int ready = -1;
  ASSERT_EQ(openni::OpenNI::waitForAnyStream(streams, 1, &ready, 3000), openni::STATUS_OK);
  openni::VideoFrameRef frame;
  ASSERT_EQ(stream.readFrame(&frame), openni::STATUS_OK);

  DepthImage image;
  image.width = static_cast<std::uint32_t>(frame.getWidth());
  image.height = static_cast<std::uint32_t>(frame.getHeight());
  image.horizontal_fov_rad = stream.getHorizontalFieldOfView();
  image.vertical_fov_rad = stream.getVerticalFieldOfView();
  image.depth_mm.resize(std::size_t{image.width} * image.height);
  for (std::uint32_t row = 0; row < image.height; ++row) {
    std::memcpy(&image.depth_mm[row * image.width],
                static_cast<const char*>(frame.getData()) + row * frame.getStrideInBytes(), image.width * 2);
  }
  const PointCloud cloud = back_project(image);
  ASSERT_EQ(cloud.width, 640u);
  ASSERT_EQ(cloud.height, 480u);

  double worst_mm = 0;
  std::size_t compared = 0;
  for (std::uint32_t v = 0; v < image.height; ++v) {
    for (std::uint32_t u = 0; u < image.width; ++u) {
      const std::uint16_t mm = image.depth_mm[v * image.width + u];
      const Eigen::Vector3f& p = cloud.points[v * image.width + u];
      if (mm == 0) {
        EXPECT_FALSE(is_finite(p));
        continue;
      }
      float x = 0, y = 0, z = 0;
      openni::CoordinateConverter::convertDepthToWorld(stream, static_cast<int>(u), static_cast<int>(v), mm, &x, &y, &z);
      // OpenNI2's world y points up; ours (the optical frame) points down.
      const Eigen::Vector3f openni_m(x / 1000.0f, -y / 1000.0f, z / 1000.0f);
      worst_mm = std::max(worst_mm, 1000.0 * double((openni_m - p).cwiseAbs().maxCoeff()));
      ++compared;
    }
  }
  stream.stop();
  stream.destroy();
  device.close();
  EXPECT_GT(compared, 100000u);
  EXPECT_LT(worst_mm, 0.5);
}

TEST(BackProjection, RejectsAnImageWithoutFieldOfViewOrWithTheWrongSize) {
  DepthImage image{4, 3, 1.0f, 0.8f, std::vector<std::uint16_t>(12, 1000)};
  EXPECT_EQ(back_project(image).size(), 12u);
  image.depth_mm.pop_back();
  expect_lccp_error([&] { back_project(image); }, {"4x3", "11 pixels"});
  image.depth_mm.push_back(1000);
  image.horizontal_fov_rad = 0;
  expect_lccp_error([&] { back_project(image); }, {"field of view"});
}

// --- recordings of the virtual sensor -----------------------------------------------

class RecordingTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    directory_ = new fs::path(test::scratch_root() / "lccp_capture");
    fs::create_directories(*directory_);
    LiveOptions options;
    options.uri = "virtual://synthetic";
    stats_ = record_device(options, recording(), kRecordedFrames);
  }
  static void TearDownTestSuite() {
    delete directory_;
  }
  static fs::path recording() { return *directory_ / "synthetic.oni"; }

  static constexpr std::uint64_t kRecordedFrames = 12;
  static inline fs::path* directory_ = nullptr;
  static inline RecordStats stats_;
};

TEST_F(RecordingTest, RecordHoldsTheFramesAskedFor) {
  EXPECT_EQ(stats_.frames, kRecordedFrames);
  EXPECT_EQ(stats_.mode, (DepthMode{640, 480, 30}));
  EXPECT_TRUE(fs::exists(recording()));
  for (const auto& entry : fs::directory_iterator(*directory_)) {
    EXPECT_EQ(entry.path(), recording()) << "left behind: " << entry.path();  // no temporary, whatever its name
  }
}

TEST_F(RecordingTest, ReplayDeliversEveryFrameInOrderWithTheSensorsDepth) {
  const auto source = open_recording(recording());
  ASSERT_EQ(source->frame_count(), kRecordedFrames);
  EXPECT_FALSE(source->is_live());
  const synthetic::TabletopScene scene;
  std::uint64_t frames = 0;
  std::uint64_t previous_timestamp = 0;
  while (std::optional<Frame> frame = source->next({})) {
    EXPECT_EQ(frame->index, frames);
    if (frames > 0) {
      EXPECT_GT(frame->timestamp_us, previous_timestamp);
    }
    previous_timestamp = frame->timestamp_us;
    ASSERT_TRUE(frame->depth.has_value());
    const DepthImage& depth = *frame->depth;
    EXPECT_EQ(depth.width, 640u);
    EXPECT_EQ(depth.height, 480u);
    EXPECT_NEAR(depth.horizontal_fov_rad, scene.camera().horizontal_fov_rad, 1e-5);
    // The stored timestamps name the synthetic frame: its depth comes back exactly,
    // but for the pixels the 16zT codec may change at a frame's end (codec_tail.hpp).
    const DepthImage rendered = scene.render(synthetic::frame_of_timestamp_us(frame->timestamp_us)).depth;
    EXPECT_EQ(test::differing_pixels_but_codec_tail(depth.depth_mm, rendered.depth_mm), 0u) << "frame " << frames;
    ++frames;
  }
  EXPECT_EQ(frames, kRecordedFrames);
  EXPECT_FALSE(source->next({}).has_value()) << "a frame after the end";
}

TEST_F(RecordingTest, FrameLimitAndStopEndTheReplay) {
  const auto limited = limit_source(open_recording(recording()), frames_limit(4));
  EXPECT_EQ(limited->frame_count(), 4u);
  int frames = 0;
  while (limited->next({})) ++frames;
  EXPECT_EQ(frames, 4);

  const auto stopped = open_recording(recording());
  std::stop_source stop;
  ASSERT_TRUE(stopped->next(stop.get_token()).has_value());
  stop.request_stop();
  EXPECT_FALSE(stopped->next(stop.get_token()).has_value());
}

TEST_F(RecordingTest, LimitsOfZeroAreRefused) {
  expect_lccp_error([&] { limit_source(open_recording(recording()), frames_limit(0)); }, {"at least 1"});
  expect_lccp_error([&] { limit_source(open_recording(recording()), seconds_limit(0.0)); }, {"more than 0"});
}

TEST_F(RecordingTest, StopWakesARealtimeReplayWaitingForItsNextFrame) {
  // Paced by its timestamps, the replay waits 33 ms between frames; the stop
  // comes from another thread while it waits and ends next() at once.
  ReplayOptions options;
  options.realtime = true;
  const auto source = open_recording(recording(), options);
  std::stop_source stop;
  std::uint64_t frames = 0;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    stop.request_stop();
  });
  while (source->next(stop.get_token())) ++frames;
  stopper.join();
  EXPECT_LT(frames, kRecordedFrames);  // ended by the stop, not by the end of the file
}

TEST_F(RecordingTest, RealtimeReplayKeepsTheRecordingsPace) {
  ReplayOptions options;
  options.realtime = true;
  const auto source = limit_source(open_recording(recording(), options), frames_limit(7));
  EXPECT_TRUE(source->is_live());
  const auto start = std::chrono::steady_clock::now();
  while (source->next({})) {
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(seconds, 6 / 30.0 - 0.01);  // 6 frame periods after the first frame
  EXPECT_LT(seconds, 60.0);  // a hang, not speed: a loaded machine or a sanitizer build is slow
}

TEST_F(RecordingTest, TruncatedRecordingIsRefusedNamingTheFile) {
  const fs::path truncated = *directory_ / "truncated.oni";
  const std::string bytes = test::read_bytes(recording());
  test::write_bytes(truncated, bytes.substr(0, bytes.size() / 2));
  const auto start = std::chrono::steady_clock::now();
  try {
    const auto source = open_recording(truncated);
    while (source->next({})) {
    }
    ADD_FAILURE() << "a truncated recording replayed to the end";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated.oni"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

// A replay is read on the caller's thread: opening, reading and closing one start
// no thread (OpenNI2's file player ran one, whose stream walk raced a close).
TEST_F(RecordingTest, AReplayStartsNoThread) {
  const auto threads = [] {
    return std::distance(fs::directory_iterator("/proc/self/task"), fs::directory_iterator{});
  };
  const auto before = threads();
  {
    const auto source = open_recording(recording());
    ASSERT_TRUE(source->next({}).has_value());
    EXPECT_EQ(threads(), before);
  }
  EXPECT_EQ(threads(), before);
}

// The file is checked when it is opened and read frame by frame after: a file cut
// while it is replayed ends the replay with one line naming it and the frame.
TEST_F(RecordingTest, RecordingCutWhileReplayingFailsNamingTheFrame) {
  const fs::path cut = *directory_ / "cut.oni";
  const std::string bytes = test::read_bytes(recording());
  test::write_bytes(cut, bytes);
  const auto source = open_recording(cut);
  ASSERT_TRUE(source->next({}).has_value());
  fs::resize_file(cut, bytes.size() / 2);
  std::uint64_t frames = 1;
  try {
    while (source->next({})) ++frames;
    ADD_FAILURE() << "a recording cut in half replayed to the end";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cut.oni: frame " + std::to_string(frames) + ": "), std::string::npos) << message;
  }
  EXPECT_GT(frames, 1u);
  EXPECT_LT(frames, kRecordedFrames);
}

TEST(Recording, MissingOrWrongFilesAreNamed) {
  expect_lccp_error([] { open_recording("/nonexistent/x.oni"); }, {"/nonexistent/x.oni", "no such file"});
  expect_lccp_error([] { open_recording(kData); }, {"not a file"});
  expect_lccp_error([] { open_recording(kData / "mosd_test2.pcd"); }, {"mosd_test2.pcd", "not an .oni recording"});
}

// --- live devices -------------------------------------------------------------------

TEST(LiveDevice, VirtualSensorStreamsAtThirtyHertz) {
  LiveOptions options;
  options.uri = "virtual://synthetic";
  const auto source = limit_source(open_device(options), frames_limit(10));
  EXPECT_TRUE(source->is_live());
  const auto start = std::chrono::steady_clock::now();
  int frames = 0;
  while (std::optional<Frame> frame = source->next({})) {
    ASSERT_TRUE(frame->depth.has_value());
    EXPECT_EQ(frame->depth->width, 640u);
    ++frames;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(frames, 10);
  EXPECT_GT(seconds, 0.2);  // 9 periods of 33 ms at least, give or take the first frame
  EXPECT_LT(seconds, 60.0);  // a hang, not speed: a loaded machine or a sanitizer build is slow
}

TEST(LiveDevice, DisappearingDeviceIsAnErrorNamingIt) {
  LiveOptions options;
  options.uri = "virtual://synthetic?frames=5";
  const auto source = open_device(options);
  int frames = 0;
  const auto start = std::chrono::steady_clock::now();
  expect_lccp_error(
      [&] {
        while (source->next({})) ++frames;
      },
      {"virtual://synthetic", "disconnected", "after 5 frames"});
  EXPECT_EQ(frames, 5);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(LiveDevice, UriWithoutDeviceIsAnError) {
  LiveOptions options;
  options.uri = "virtual://no-such-scene";
  expect_lccp_error([&] { open_device(options); }, {"cannot open device", "virtual://no-such-scene"});
  options.uri = "usb://0000/0000";
  expect_lccp_error([&] { open_device(options); }, {"cannot open device", "usb://0000/0000"});
}

// --- virtual sensor URIs -------------------------------------------------------------

using virtual_sensor::parse_virtual_uri;

TEST(VirtualUri, DocumentedFormsParse) {
  EXPECT_EQ(parse_virtual_uri("virtual://synthetic").seed, 1u);
  const auto limited = parse_virtual_uri("virtual://synthetic?frames=18446744073709551615&seed=7");
  EXPECT_EQ(limited.frame_limit, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(limited.seed, 7u);
  const auto clouds = parse_virtual_uri("virtual://clouds?path=/data/a b.pcd");
  EXPECT_EQ(clouds.kind, virtual_sensor::SourceKind::clouds);
  EXPECT_EQ(clouds.path, fs::path("/data/a b.pcd"));
}

// Any string parses or throws one printable line of bounded length.
void expect_uri_refused(const std::string& uri, std::initializer_list<std::string> parts) {
  SCOPED_TRACE(::testing::PrintToString(uri));
  try {
    parse_virtual_uri(uri);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_LT(message.size(), 400u);
    EXPECT_TRUE(std::all_of(message.begin(), message.end(), [](char c) { return c >= 0x20 && c < 0x7f; })) << message;
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(VirtualUri, BadNumbersOptionsAndBytesAreOneLineErrors) {
  expect_uri_refused("virtual://synthetic?frames=18446744073709551616", {"out of range"});
  expect_uri_refused("virtual://synthetic?frames=-1", {"not a non-negative integer"});
  expect_uri_refused("virtual://synthetic?frames=+1", {"not a non-negative integer"});
  expect_uri_refused("virtual://synthetic?frames=0", {"at least 1"});
  expect_uri_refused("virtual://synthetic?seed=1e3", {"seed=1e3"});
  expect_uri_refused("virtual://synthetic?seed=1&seed=2", {"given twice"});
  expect_uri_refused("virtual://synthetic?&", {"not key=value"});
  expect_uri_refused("virtual://synthetic?=1", {"unknown option"});
  expect_uri_refused("virtual://", {"unknown source"});
  expect_uri_refused("virtual://clouds", {"needs ?path=P"});
  expect_uri_refused("virtual://clouds?path=", {"path is empty"});
  expect_uri_refused(std::string("virtual://clouds?path=/tmp/a\0b.pcd", 34), {"control character at byte 28", "\\x00"});
  expect_uri_refused("virtual://synthetic?seed=1\n", {"control character", "\\x0a"});
  expect_uri_refused("virtual://synthetic?seed=\xff", {"\\xff"});
  expect_uri_refused("virtual://synthetic?seed=" + std::string(5000, '9'), {"longer than 4096 bytes", "..."});
  expect_uri_refused("usb://x", {"does not start with virtual://"});
}

TEST(VirtualUri, RandomStringsParseOrFailCleanly) {
  const std::vector<std::string> pieces = {"virtual://", "synthetic", "clouds", "?", "&", "=", "seed", "frames", "path",
                                           "0", "1", "99999999999999999999", "-", "/tmp", std::string(1, '\0'), "\n", "%",
                                           "\xff", "x"};
  std::uint64_t state = 99;
  for (int i = 0; i < 5000; ++i) {
    std::string uri = i % 2 == 0 ? "virtual://" : "";
    for (int n = 0; n < 8; ++n) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      uri += pieces[(state >> 33) % pieces.size()];
    }
    try {
      parse_virtual_uri(uri);
    } catch (const Error& e) {
      const std::string message = e.what();
      ASSERT_EQ(message.find('\n'), std::string::npos) << message;
      ASSERT_EQ(message.find('\0'), std::string::npos) << message;
    }
  }
}

TEST(VirtualUri, OutOfRangeFrameLimitCannotOpenADevice) {
  LiveOptions options;
  options.uri = "virtual://synthetic?frames=99999999999999999999999";
  expect_lccp_error([&] { open_device(options); }, {"cannot open device"});
}

// --- cloud files --------------------------------------------------------------------

TEST(CloudFiles, DirectoryGivesItsCloudsSortedByName) {
  const auto source = open_cloud_files({kData});
  ASSERT_EQ(source->frame_count(), 4u);
  std::vector<std::string> names;
  while (std::optional<Frame> frame = source->next({})) {
    EXPECT_EQ(frame->index, names.size());
    EXPECT_FALSE(frame->depth.has_value());
    EXPECT_GT(frame->cloud.size(), 100000u);
    names.push_back(frame->name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"mosd_test2", "mosd_test34", "mosd_test43", "mosd_test60"}));
}

TEST(CloudFiles, MissingPathOrEmptyDirectoryIsAnError) {
  expect_lccp_error([] { open_cloud_files({"/nonexistent/clouds"}); }, {"/nonexistent/clouds", "no such file"});
  const fs::path empty = test::scratch_dir("lccp_capture");
  expect_lccp_error([&] { open_cloud_files({empty}); }, {"holds no .pcd or .ply file"});
}

}  // namespace
}  // namespace lccp
