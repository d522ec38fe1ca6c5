// Tests of the virtual sensor driver (drivers/virtual_sensor), through OpenNI2 as
// any client sees it: the driver is loaded from build/lib/OpenNI2/Drivers.
// OpenNI2 is initialized once per process and never shut down (tests share it).
#include <gtest/gtest.h>

#include <OpenNI.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "codec_tail.hpp"
#include "test_files.hpp"
#include "lccp/capture/openni_session.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/synthetic/tabletop_scene.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using test::differing_pixels_but_codec_tail;

const fs::path kData = LCCP_TEST_DATA_DIR;
constexpr const char* kSyntheticUri = "virtual://synthetic";

struct CapturedFrame {
  int index = 0;
  std::uint64_t timestamp_us = 0;
  Clock::time_point arrival;
  int width = 0;
  int height = 0;
  int stride = 0;
  std::vector<std::uint16_t> depth_mm;
};

// Waits up to timeout_ms for the next frame; nullopt on timeout.
std::optional<CapturedFrame> next_frame(openni::VideoStream& stream, int timeout_ms) {
  openni::VideoStream* streams[] = {&stream};
  int ready = -1;
  if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, timeout_ms) != openni::STATUS_OK) return std::nullopt;
  openni::VideoFrameRef frame;
  if (stream.readFrame(&frame) != openni::STATUS_OK) return std::nullopt;
  CapturedFrame captured;
  captured.arrival = Clock::now();
  captured.index = frame.getFrameIndex();
  captured.timestamp_us = frame.getTimestamp();
  captured.width = frame.getWidth();
  captured.height = frame.getHeight();
  captured.stride = frame.getStrideInBytes();
  const auto* pixels = static_cast<const std::uint16_t*>(frame.getData());
  captured.depth_mm.assign(pixels, pixels + frame.getDataSize() / sizeof(std::uint16_t));
  return captured;
}

// Waits are limits against hangs, not measures of speed: generous enough for a loaded
// machine or a sanitizer build, where rendering a synthetic frame takes many times longer.
constexpr int kFrameTimeoutMs = 10000;
constexpr auto kEventTimeout = std::chrono::seconds(10);

std::vector<CapturedFrame> read_frames(openni::VideoStream& stream, std::size_t count,
                                       int timeout_ms = kFrameTimeoutMs) {
  std::vector<CapturedFrame> frames;
  while (frames.size() < count) {
    auto frame = next_frame(stream, timeout_ms);
    if (!frame) break;
    frames.push_back(std::move(*frame));
  }
  return frames;
}

std::vector<std::uint16_t> scene_depth(std::uint64_t timestamp_us, std::uint32_t width = 640,
                                       std::uint32_t height = 480, std::uint64_t seed = 1) {
  synthetic::Camera camera;
  camera.width = width;
  camera.height = height;
  return synthetic::TabletopScene(camera, seed).render(synthetic::frame_of_timestamp_us(timestamp_us)).depth.depth_mm;
}

// Pixels that differ.
std::size_t differing_pixels(const std::vector<std::uint16_t>& a, const std::vector<std::uint16_t>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t count = 0;
  for (std::size_t i = 0; i < a.size(); ++i) count += a[i] != b[i];
  return count;
}

// Where two depth images first differ, for failure messages.
std::string first_difference(const std::vector<std::uint16_t>& a, const std::vector<std::uint16_t>& b) {
  if (a.size() != b.size()) return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i]) {
      return "pixel " + std::to_string(i) + " of " + std::to_string(a.size()) + ": " + std::to_string(a[i]) +
             " vs " + std::to_string(b[i]);
    }
  }
  return "none";
}

class VirtualSensor : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { initialize_openni(); }

  // Opens `uri` and starts nothing; fails the test if it does not open.
  void open(openni::Device& device, const std::string& uri) {
    ASSERT_EQ(device.open(uri.c_str()), openni::STATUS_OK) << uri << ": " << openni_error();
  }
  void create_depth(openni::Device& device, openni::VideoStream& stream) {
    ASSERT_EQ(stream.create(device, openni::SENSOR_DEPTH), openni::STATUS_OK) << openni_error();
  }
};

TEST_F(VirtualSensor, SyntheticDeviceIsListedAtStartup) {
  openni::Array<openni::DeviceInfo> devices;
  openni::OpenNI::enumerateDevices(&devices);
  bool found = false;
  for (int i = 0; i < devices.getSize(); ++i) {
    if (std::string(devices[i].getUri()) != kSyntheticUri) continue;
    found = true;
    EXPECT_STREQ(devices[i].getName(), "LCCP Virtual Sensor");
    EXPECT_STREQ(devices[i].getVendor(), "LCCP Stream");
  }
  EXPECT_TRUE(found);
}

TEST_F(VirtualSensor, SyntheticDepthStreamOffersTwoModesAndTheSceneLens) {
  openni::Device device;
  ASSERT_NO_FATAL_FAILURE(open(device, kSyntheticUri));
  EXPECT_STREQ(device.getDeviceInfo().getUri(), kSyntheticUri);
  EXPECT_TRUE(device.hasSensor(openni::SENSOR_DEPTH));
  EXPECT_FALSE(device.hasSensor(openni::SENSOR_COLOR));
  EXPECT_FALSE(device.isFile());

  openni::VideoStream depth;
  ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
  const openni::Array<openni::VideoMode>& modes = depth.getSensorInfo().getSupportedVideoModes();
  ASSERT_EQ(modes.getSize(), 2);
  EXPECT_EQ(modes[0].getResolutionX(), 640);
  EXPECT_EQ(modes[0].getResolutionY(), 480);
  EXPECT_EQ(modes[0].getFps(), 30);
  EXPECT_EQ(modes[0].getPixelFormat(), openni::PIXEL_FORMAT_DEPTH_1_MM);
  EXPECT_EQ(modes[1].getResolutionX(), 320);
  EXPECT_EQ(modes[1].getResolutionY(), 240);
  EXPECT_EQ(modes[1].getFps(), 60);
  EXPECT_EQ(modes[1].getPixelFormat(), openni::PIXEL_FORMAT_DEPTH_1_MM);

  const openni::VideoMode mode = depth.getVideoMode();
  EXPECT_EQ(mode.getResolutionX(), 640);
  EXPECT_EQ(mode.getResolutionY(), 480);
  EXPECT_EQ(mode.getFps(), 30);
  EXPECT_EQ(mode.getPixelFormat(), openni::PIXEL_FORMAT_DEPTH_1_MM);

  const synthetic::Camera lens;
  EXPECT_EQ(depth.getHorizontalFieldOfView(), lens.horizontal_fov_rad);
  EXPECT_EQ(depth.getVerticalFieldOfView(), lens.vertical_fov_rad);
  EXPECT_EQ(depth.getMaxPixelValue(), 10000);
  EXPECT_EQ(depth.getMinPixelValue(), 0);
  EXPECT_FALSE(depth.getMirroringEnabled());
  int stride = 0;
  EXPECT_EQ(depth.getProperty(openni::STREAM_PROPERTY_STRIDE, &stride), openni::STATUS_OK);
  EXPECT_EQ(stride, 1280);

  // Cropping is supported (recordings need it) and reported off.
  EXPECT_TRUE(depth.isCroppingSupported());
  int x = -1, y = -1, width = -1, height = -1;
  EXPECT_FALSE(depth.getCropping(&x, &y, &width, &height));
  EXPECT_EQ(depth.resetCropping(), openni::STATUS_OK);
  EXPECT_NE(depth.setCropping(0, 0, 320, 240), openni::STATUS_OK);
  EXPECT_NE(depth.setMirroringEnabled(true), openni::STATUS_OK);
  EXPECT_EQ(depth.setMirroringEnabled(false), openni::STATUS_OK);

  // Only offered modes are accepted.
  openni::VideoMode unsupported = mode;
  unsupported.setResolution(1280, 1024);
  EXPECT_NE(depth.setVideoMode(unsupported), openni::STATUS_OK);
  EXPECT_EQ(depth.getVideoMode().getResolutionX(), 640);
  EXPECT_EQ(depth.setProperty(openni::STREAM_PROPERTY_AUTO_EXPOSURE, true), openni::STATUS_NOT_SUPPORTED);
  depth.destroy();
  device.close();
}

TEST_F(VirtualSensor, SyntheticStreamFreeRunsAt30HzWithSceneDepth) {
  openni::Device device;
  ASSERT_NO_FATAL_FAILURE(open(device, kSyntheticUri));
  openni::VideoStream depth;
  ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
  ASSERT_EQ(depth.start(), openni::STATUS_OK);
  const std::vector<CapturedFrame> frames = read_frames(depth, 15);
  depth.stop();
  ASSERT_EQ(frames.size(), 15u);

  for (std::size_t i = 0; i < frames.size(); ++i) {
    const CapturedFrame& frame = frames[i];
    EXPECT_EQ(frame.width, 640);
    EXPECT_EQ(frame.height, 480);
    EXPECT_EQ(frame.stride, 1280);
    ASSERT_EQ(frame.depth_mm.size(), 640u * 480u);
    // frameIndex counts frames since the stream started; the timestamp is its time.
    EXPECT_EQ(frame.timestamp_us, synthetic::timestamp_us_of_frame(static_cast<std::uint64_t>(frame.index)));
    if (i == 0) continue;
    const CapturedFrame& previous = frames[i - 1];
    EXPECT_GT(frame.index, previous.index);
    EXPECT_GT(frame.timestamp_us, previous.timestamp_us);
    const std::uint64_t gap = frame.timestamp_us - previous.timestamp_us;
    const std::uint64_t frames_apart = static_cast<std::uint64_t>(frame.index - previous.index);
    EXPECT_NEAR(static_cast<double>(gap), frames_apart * 1e6 / 30, 1.0);
  }
  // Free-running: the sensor's clock is the wall clock. On a loaded machine it skips
  // frame numbers instead of slowing down, so count periods, not frames. How late we
  // read a frame depends on the load (a sanitizer build renders one in about 0.5 s),
  // so the two clocks are compared with a margin for that, not for speed.
  const double wall_s = std::chrono::duration<double>(frames.back().arrival - frames[4].arrival).count();
  const double sensor_s = (frames.back().timestamp_us - frames[4].timestamp_us) * 1e-6;
  const double periods = frames.back().index - frames[4].index;
  constexpr double kReadDelayMarginS = 1.5;
  EXPECT_GE(periods, 10);
  EXPECT_NEAR(wall_s, sensor_s, kReadDelayMarginS) << periods << " frame periods";

  for (const CapturedFrame& frame : {frames.front(), frames[7], frames.back()}) {
    EXPECT_EQ(differing_pixels(frame.depth_mm, scene_depth(frame.timestamp_us)), 0u) << "frame " << frame.index;
  }
  depth.destroy();
  device.close();
}

TEST_F(VirtualSensor, SyntheticLowResolutionModeStreamsAt60Hz) {
  openni::Device device;
  ASSERT_NO_FATAL_FAILURE(open(device, "virtual://synthetic?seed=7"));
  openni::VideoStream depth;
  ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
  openni::VideoMode mode = depth.getVideoMode();
  mode.setResolution(320, 240);
  mode.setFps(60);
  ASSERT_EQ(depth.setVideoMode(mode), openni::STATUS_OK) << openni_error();
  EXPECT_EQ(depth.getVideoMode().getResolutionX(), 320);
  int stride = 0;
  EXPECT_EQ(depth.getProperty(openni::STREAM_PROPERTY_STRIDE, &stride), openni::STATUS_OK);
  EXPECT_EQ(stride, 640);
  // The lens does not change with the resolution.
  EXPECT_EQ(depth.getHorizontalFieldOfView(), synthetic::Camera{}.horizontal_fov_rad);

  ASSERT_EQ(depth.start(), openni::STATUS_OK);
  // The frame size is fixed while streaming.
  openni::VideoMode vga = mode;
  vga.setResolution(640, 480);
  vga.setFps(30);
  EXPECT_NE(depth.setVideoMode(vga), openni::STATUS_OK);
  const std::vector<CapturedFrame> frames = read_frames(depth, 6);
  depth.stop();
  ASSERT_EQ(frames.size(), 6u);
  for (const CapturedFrame& frame : frames) {
    EXPECT_EQ(frame.width, 320);
    EXPECT_EQ(frame.height, 240);
    EXPECT_EQ(frame.stride, 640);
    EXPECT_EQ(frame.timestamp_us, static_cast<std::uint64_t>(std::llround(frame.index * 1e6 / 60)));
  }
  // A frame shows the scene at its timestamp.
  EXPECT_EQ(differing_pixels(frames.back().depth_mm, scene_depth(frames.back().timestamp_us, 320, 240, 7)), 0u);
  depth.destroy();
  device.close();
}

// The depth a clouds device reports for a point at z metres.
std::uint16_t expected_depth_mm(const Eigen::Vector3f& point) {
  if (!is_finite(point) || !(point.z() > 0)) return 0;
  return static_cast<std::uint16_t>(std::lround(static_cast<double>(point.z()) * 1000.0));
}

TEST_F(VirtualSensor, CloudsRebuildDepthAndLensFromPcd) {
  const fs::path path = kData / "mosd_test2.pcd";
  const PointCloud cloud = read_cloud(path).cloud;
  ASSERT_EQ(cloud.width, 640u);
  ASSERT_EQ(cloud.height, 480u);

  openni::Device device;
  ASSERT_NO_FATAL_FAILURE(open(device, "virtual://clouds?path=" + path.string()));
  openni::VideoStream depth;
  ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
  const openni::Array<openni::VideoMode>& modes = depth.getSensorInfo().getSupportedVideoModes();
  ASSERT_EQ(modes.getSize(), 1);
  EXPECT_EQ(modes[0].getResolutionX(), 640);
  EXPECT_EQ(modes[0].getResolutionY(), 480);
  EXPECT_EQ(modes[0].getFps(), 30);
  // mOSD was taken with a Kinect: fx = fy = 525 px.
  EXPECT_NEAR(depth.getHorizontalFieldOfView(), 2 * std::atan(320.0 / 525.0), 0.005 * 2 * std::atan(320.0 / 525.0));
  EXPECT_NEAR(depth.getVerticalFieldOfView(), 2 * std::atan(240.0 / 525.0), 0.005 * 2 * std::atan(240.0 / 525.0));

  ASSERT_EQ(depth.start(), openni::STATUS_OK);
  const std::vector<CapturedFrame> frames = read_frames(depth, 2);
  depth.stop();
  ASSERT_EQ(frames.size(), 2u);
  std::vector<std::uint16_t> expected(cloud.size());
  std::transform(cloud.points.begin(), cloud.points.end(), expected.begin(), expected_depth_mm);
  for (const CapturedFrame& frame : frames) {
    EXPECT_EQ(frame.width, 640);
    EXPECT_EQ(frame.height, 480);
    EXPECT_EQ(differing_pixels(frame.depth_mm, expected), 0u);  // one cloud: every frame shows it
  }
  EXPECT_GT(std::count(expected.begin(), expected.end(), std::uint16_t{0}), 0);
  EXPECT_GT(std::count_if(expected.begin(), expected.end(), [](std::uint16_t mm) { return mm > 0; }), 150000);
  depth.destroy();
  device.close();
}

TEST_F(VirtualSensor, CloudsFolderPlaysItsPcdFilesInNameOrderAndLoops) {
  const fs::path folder = test::scratch_dir("lccp_virtual_sensor");
  fs::create_symlink(kData / "mosd_test60.pcd", folder / "a.pcd");
  fs::create_symlink(kData / "mosd_test2.pcd", folder / "b.pcd");
  test::write_bytes(folder / "notes.txt", "not a cloud");

  openni::Device device;
  ASSERT_NO_FATAL_FAILURE(open(device, "virtual://clouds?path=" + folder.string()));
  openni::VideoStream depth;
  ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
  ASSERT_EQ(depth.start(), openni::STATUS_OK);
  const std::vector<CapturedFrame> frames = read_frames(depth, 3);
  depth.stop();
  depth.destroy();
  device.close();
  ASSERT_EQ(frames.size(), 3u);

  std::vector<std::vector<std::uint16_t>> clouds;
  for (const char* name : {"mosd_test60.pcd", "mosd_test2.pcd"}) {
    const PointCloud cloud = read_cloud(kData / name).cloud;
    std::vector<std::uint16_t>& expected = clouds.emplace_back(cloud.size());
    std::transform(cloud.points.begin(), cloud.points.end(), expected.begin(), expected_depth_mm);
  }
  ASSERT_NE(differing_pixels(clouds[0], clouds[1]), 0u);
  for (const CapturedFrame& frame : frames) {
    EXPECT_EQ(differing_pixels(frame.depth_mm, clouds[static_cast<std::size_t>(frame.index) % 2]), 0u)
        << "frame " << frame.index;
  }
  fs::remove_all(folder);
}

class DisconnectWatcher : public openni::OpenNI::DeviceDisconnectedListener {
 public:
  void onDeviceDisconnected(const openni::DeviceInfo* info) override {
    std::lock_guard lock(mutex_);
    uris_.push_back(info->getUri());
  }
  std::vector<std::string> uris() const {
    std::lock_guard lock(mutex_);
    return uris_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> uris_;
};

// Registers a listener for the scope, so a failed ASSERT leaves none dangling.
class Listening {
 public:
  explicit Listening(openni::OpenNI::DeviceDisconnectedListener& listener) : listener_(listener) {
    EXPECT_EQ(openni::OpenNI::addDeviceDisconnectedListener(&listener_), openni::STATUS_OK);
  }
  ~Listening() { openni::OpenNI::removeDeviceDisconnectedListener(&listener_); }
  Listening(const Listening&) = delete;
  Listening& operator=(const Listening&) = delete;

 private:
  openni::OpenNI::DeviceDisconnectedListener& listener_;
};

TEST_F(VirtualSensor, FramesLimitMakesTheDeviceDisappear) {
  // A lost device stays lost for the process: a fresh URI per run (--gtest_repeat).
  static int run = 0;
  const std::string uri = "virtual://synthetic?frames=5&seed=" + std::to_string(100 + run++);
  DisconnectWatcher watcher;
  const Listening listening(watcher);

  openni::Device device;
  ASSERT_NO_FATAL_FAILURE(open(device, uri));
  openni::VideoStream depth;
  ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
  ASSERT_EQ(depth.start(), openni::STATUS_OK);
  const std::vector<CapturedFrame> frames = read_frames(depth, 5);
  ASSERT_EQ(frames.size(), 5u);  // delivered frames; frame numbers may skip on a loaded machine

  // The disconnection is announced (the driver does it one frame period after the
  // last frame; how soon we see it depends on the machine's load)...
  const auto announced_by = Clock::now() + kEventTimeout;
  while (watcher.uris().empty() && Clock::now() < announced_by) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(watcher.uris(), std::vector<std::string>{uri});
  // ... and no frame comes after the fifth.
  EXPECT_FALSE(next_frame(depth, 300).has_value());
  const auto silent = Clock::now();
  // Gone from the device list, cannot be restarted, and stops and closes without hanging.
  openni::Array<openni::DeviceInfo> devices;
  openni::OpenNI::enumerateDevices(&devices);
  for (int i = 0; i < devices.getSize(); ++i) EXPECT_NE(std::string(devices[i].getUri()), uri);
  depth.stop();
  EXPECT_NE(depth.start(), openni::STATUS_OK);
  depth.destroy();
  device.close();
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - silent).count(), 10.0);

  openni::Device again;
  EXPECT_NE(again.open(uri.c_str()), openni::STATUS_OK);
}

// The listener runs on the driver's frame thread; closing everything from there must
// neither deadlock (the stream's stop cannot join its own thread) nor crash.
class ClosingListener : public openni::OpenNI::DeviceDisconnectedListener {
 public:
  ClosingListener(std::string uri, openni::Device& device, openni::VideoStream& depth)
      : uri_(std::move(uri)), device_(device), depth_(depth) {}
  void onDeviceDisconnected(const openni::DeviceInfo* info) override {
    if (info->getUri() != uri_) return;
    depth_.stop();
    depth_.destroy();
    device_.close();
    closed_.set_value();
  }
  std::future<void> closed() { return closed_.get_future(); }

 private:
  std::string uri_;
  openni::Device& device_;
  openni::VideoStream& depth_;
  std::promise<void> closed_;
};

TEST_F(VirtualSensor, LostDeviceCanBeClosedFromTheDisconnectListener) {
  static int run = 0;
  const std::string uri = "virtual://synthetic?frames=2&seed=" + std::to_string(200 + run++);
  openni::Device device;
  ASSERT_NO_FATAL_FAILURE(open(device, uri));
  openni::VideoStream depth;
  ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
  ClosingListener listener(uri, device, depth);
  std::future<void> closed = listener.closed();
  {
    const Listening listening(listener);
    ASSERT_EQ(depth.start(), openni::STATUS_OK);
    ASSERT_EQ(closed.wait_for(kEventTimeout), std::future_status::ready);
  }
  EXPECT_FALSE(device.isValid());
  EXPECT_FALSE(depth.isValid());
}

TEST_F(VirtualSensor, UnparsableUrisFailToOpen) {
  for (const std::string uri :
       {"virtual://bogus", "virtual://synthetic?seed=abc", "virtual://synthetic?frames=0",
        "virtual://synthetic?colour=red", "virtual://clouds", "virtual://synthetic?seed=1&seed=2"}) {
    openni::Device device;
    EXPECT_NE(device.open(uri.c_str()), openni::STATUS_OK) << uri;
    EXPECT_FALSE(device.isValid()) << uri;
  }
  openni::Device bogus;
  EXPECT_NE(bogus.open("virtual://bogus"), openni::STATUS_OK);
  EXPECT_NE(openni_error().find("unknown source 'bogus'"), std::string::npos) << openni_error();
  // Parses, but the file is missing: open fails and says why.
  openni::Device device;
  EXPECT_NE(device.open("virtual://clouds?path=/nonexistent/scene.pcd"), openni::STATUS_OK);
  EXPECT_NE(openni_error().find("/nonexistent/scene.pcd"), std::string::npos) << openni_error();
  // Not organized: no depth image.
  EXPECT_NE(device.open(("virtual://clouds?path=" + (kData / "mosd_test43.pcd").string()).c_str()), openni::STATUS_OK);
  EXPECT_NE(openni_error().find("not an organized cloud"), std::string::npos) << openni_error();
}

TEST_F(VirtualSensor, RecordingIsReplayedByTheOniFileDriver) {
  const fs::path folder = test::scratch_dir("lccp_virtual_sensor");
  const fs::path oni = folder / "synthetic.oni";

  std::map<std::uint64_t, CapturedFrame> originals;  // by timestamp
  float hfov = 0, vfov = 0;
  {
    openni::Device device;
    ASSERT_NO_FATAL_FAILURE(open(device, kSyntheticUri));
    openni::VideoStream depth;
    ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
    hfov = depth.getHorizontalFieldOfView();
    vfov = depth.getVerticalFieldOfView();
    ASSERT_EQ(depth.start(), openni::STATUS_OK);
    for (CapturedFrame& frame : read_frames(depth, 3)) originals.emplace(frame.timestamp_us, std::move(frame));

    openni::Recorder recorder;
    ASSERT_EQ(recorder.create(oni.c_str()), openni::STATUS_OK) << openni_error();
    ASSERT_EQ(recorder.attach(depth), openni::STATUS_OK) << openni_error();
    ASSERT_EQ(recorder.start(), openni::STATUS_OK) << openni_error();
    for (CapturedFrame& frame : read_frames(depth, 10)) originals.emplace(frame.timestamp_us, std::move(frame));
    recorder.stop();
    recorder.destroy();
    depth.stop();
    depth.destroy();
    device.close();
  }
  ASSERT_GE(originals.size(), 13u);

  std::vector<CapturedFrame> replayed;
  int recorded = 0;
  float replay_hfov = 0, replay_vfov = 0;
  {
    openni::Device device;
    ASSERT_NO_FATAL_FAILURE(open(device, oni.string()));
    ASSERT_TRUE(device.isFile());
    openni::PlaybackControl* playback = device.getPlaybackControl();
    ASSERT_NE(playback, nullptr);
    ASSERT_EQ(playback->setSpeed(-1), openni::STATUS_OK);  // manual: every frame, on request
    openni::VideoStream depth;
    ASSERT_NO_FATAL_FAILURE(create_depth(device, depth));
    recorded = playback->getNumberOfFrames(depth);
    replay_hfov = depth.getHorizontalFieldOfView();
    replay_vfov = depth.getVerticalFieldOfView();
    ASSERT_EQ(depth.start(), openni::STATUS_OK);
    while (replayed.empty() || replayed.back().index < recorded) {
      auto frame = next_frame(depth, 2000);
      if (!frame) break;
      replayed.push_back(std::move(*frame));
    }
    depth.stop();
    depth.destroy();
    device.close();
  }
  fs::remove_all(folder);

  // Every recorded frame comes back, numbered 1..N by the recorder (not the sensor's frameIndex).
  ASSERT_EQ(static_cast<int>(replayed.size()), recorded);
  EXPECT_GE(recorded, 9);  // the 10 frames read while recording, give or take one at either end
  EXPECT_LE(recorded, 13);
  for (std::size_t j = 0; j < replayed.size(); ++j) {
    EXPECT_EQ(replayed[j].index, static_cast<int>(j) + 1);
    EXPECT_EQ(replayed[j].width, 640);
    EXPECT_EQ(replayed[j].height, 480);
    EXPECT_EQ(replayed[j].stride, 1280);
  }

  // Timestamps are rebased: the first recorded frame gets 0, the others keep their
  // distance to it. Which sensor frame came first is found by its depth.
  ASSERT_FALSE(replayed.empty());
  EXPECT_EQ(replayed.front().timestamp_us, 0u);
  const auto first = std::find_if(originals.begin(), originals.end(), [&](const auto& original) {
    return differing_pixels_but_codec_tail(replayed.front().depth_mm, original.second.depth_mm) == 0;
  });
  ASSERT_NE(first, originals.end());
  EXPECT_GE(first->second.index, 3);  // recording started after 3 frames had been read
  const std::uint64_t offset_us = first->first;

  // Depth survives the 16zT codec, but for the pixels it may change at a frame's end.
  std::size_t tail_changed = 0;
  for (const CapturedFrame& frame : replayed) {
    const std::uint64_t sensor_timestamp_us = frame.timestamp_us + offset_us;
    const auto original = originals.find(sensor_timestamp_us);
    const std::vector<std::uint16_t> expected =
        original != originals.end() ? original->second.depth_mm : scene_depth(sensor_timestamp_us);
    EXPECT_EQ(synthetic::timestamp_us_of_frame(synthetic::frame_of_timestamp_us(sensor_timestamp_us)),
              sensor_timestamp_us);
    EXPECT_EQ(differing_pixels_but_codec_tail(frame.depth_mm, expected), 0u)
        << "replayed frame " << frame.index << " (sensor time " << sensor_timestamp_us << " us, "
        << (original != originals.end() ? "as read from the sensor" : "rendered again")
        << "), first difference: " << first_difference(frame.depth_mm, expected);
    tail_changed +=
        differing_pixels(frame.depth_mm, expected) - differing_pixels_but_codec_tail(frame.depth_mm, expected);
  }
  RecordProperty("codec_tail_pixels_changed", static_cast<int>(tail_changed));

  // The fields of view (the whole camera model of an .oni) come back exactly.
  EXPECT_EQ(replay_hfov, hfov);
  EXPECT_EQ(replay_vfov, vfov);
}

}  // namespace
}  // namespace lccp
