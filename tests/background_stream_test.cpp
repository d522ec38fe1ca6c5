// The library's BackgroundStream and PushSource (the Python and ROS faces run
// on them): every frame of a lossless source reaches the consumer in order,
// through the hand-off queue or a sink; a consumer that takes nothing holds the
// run back instead of losing frames; stop() ends any run and the counts add up;
// a source's error comes back after its frames; a PushSource keeps the newest
// frames and the pipeline counts the ones it pushed out.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <stop_token>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lccp/error.hpp"
#include "lccp/pipeline/background_stream.hpp"
#include "lccp/pipeline/push_source.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

using namespace std::chrono_literals;

// A box on a table seen by a 320 x 240 camera.
const PointCloud& small_cloud() {
  static const PointCloud cloud =
      test::render(test::box_on_table().rects, test::PinholeCamera{262.5, 159.5, 119.5, 320, 240}).cloud;
  return cloud;
}

Frame small_frame() {
  Frame frame;
  frame.cloud = small_cloud();
  frame.captured = Clock::now();
  return frame;
}

// `count` frames of the small cloud, indices 0..count-1, lossless; throws
// lccp::Error("device lost") when asked for frame `throw_at`, if given.
class CountingSource : public FrameSource {
 public:
  explicit CountingSource(std::uint64_t count, std::optional<std::uint64_t> throw_at = {})
      : count_(count), throw_at_(throw_at) {}
  std::optional<Frame> next(std::stop_token stop) override {
    if (stop.stop_requested() || taken_ == count_) return std::nullopt;
    if (throw_at_ && taken_ == *throw_at_) throw Error("device lost");
    Frame frame = small_frame();
    frame.index = taken_++;
    return frame;
  }
  std::optional<std::uint64_t> frame_count() const override { return count_; }
  bool is_live() const override { return false; }
  std::uint64_t taken() const { return taken_; }

 private:
  std::uint64_t count_;
  std::optional<std::uint64_t> throw_at_;
  std::uint64_t taken_ = 0;
};

// Takes every result until the stream ends (generous waits: CI may be loaded).
std::vector<std::uint64_t> take_all(BackgroundStream& stream) {
  std::vector<std::uint64_t> indices;
  FrameResult result;
  for (int waits = 0; waits < 600;) {
    const BackgroundStream::Next next = stream.next(result, 100ms);
    if (next == BackgroundStream::Next::ended) return indices;
    if (next == BackgroundStream::Next::frame) {
      EXPECT_TRUE(result.error.empty()) << result.error;
      EXPECT_EQ(result.segmentation.labels.size(), result.frame.cloud.size());
      indices.push_back(result.frame.index);
    } else {
      ++waits;
    }
  }
  ADD_FAILURE() << "the stream did not end within 60 s";
  return indices;
}

std::vector<std::uint64_t> iota(std::uint64_t count) {
  std::vector<std::uint64_t> v;
  for (std::uint64_t i = 0; i < count; ++i) v.push_back(i);
  return v;
}

TEST(BackgroundStream, EveryFrameOfALosslessSourceComesOutInOrderThenItEnds) {
  CountingSource source(12);
  BackgroundStream stream(SceneConfig{}, source, StreamConfig{3, 2, 2});
  EXPECT_EQ(take_all(stream), iota(12));
  const PipelineOutcome& outcome = stream.stop();
  EXPECT_TRUE(outcome.error.empty()) << outcome.error;
  EXPECT_EQ(outcome.stats.frames_completed, 12u);
  EXPECT_EQ(outcome.stats.frames_dropped, 0u);
  EXPECT_TRUE(outcome.stats.adds_up());
}

TEST(BackgroundStream, ASinkGetsEveryFrameInOrderOnTheStreamsThread) {
  CountingSource source(8);
  std::vector<std::uint64_t> seen;  // one call at a time: no lock needed
  const std::thread::id caller = std::this_thread::get_id();
  bool on_caller = false;
  BackgroundStream stream(SceneConfig{}, source, StreamConfig{2, 1, 2}, [&](FrameResult& result) {
    seen.push_back(result.frame.index);
    on_caller = on_caller || std::this_thread::get_id() == caller;
  });
  FrameResult unused;
  while (stream.next(unused, 100ms) != BackgroundStream::Next::ended) {
  }
  const PipelineOutcome& outcome = stream.stop();
  EXPECT_EQ(seen, iota(8));
  EXPECT_FALSE(on_caller);
  EXPECT_EQ(outcome.stats.frames_completed, 8u);
}

TEST(BackgroundStream, AConsumerThatTakesNothingHoldsTheRunBackAndLosesNoFrame) {
  CountingSource source(20);
  BackgroundStream stream(SceneConfig{}, source, StreamConfig{2, 2, 2});
  // Wait (up to 60 s) until the run is stuck behind the full hand-off queue.
  for (int i = 0; i < 600 && stream.stats().frames_received < 4; ++i) std::this_thread::sleep_for(100ms);
  std::this_thread::sleep_for(300ms);
  const PipelineStats held = stream.stats();
  // 2 results wait, K = 2 frames in flight (one at the sink): at most 4 + 1 taken.
  EXPECT_LE(held.frames_received, 5u);
  EXPECT_EQ(held.frames_dropped, 0u);
  EXPECT_EQ(take_all(stream), iota(20));
  EXPECT_TRUE(stream.stop().stats.adds_up());
}

TEST(BackgroundStream, StopEndsARunHeldBackByAFullQueueAndTheCountsAddUp) {
  CountingSource source(1000);
  BackgroundStream stream(SceneConfig{}, source, StreamConfig{2, 2, 1});
  for (int i = 0; i < 600 && stream.stats().frames_received < 2; ++i) std::this_thread::sleep_for(100ms);
  const PipelineOutcome& outcome = stream.stop();
  EXPECT_TRUE(outcome.error.empty()) << outcome.error;
  EXPECT_TRUE(outcome.stats.adds_up());
  EXPECT_LT(outcome.stats.frames_received, 1000u);
  FrameResult result;
  EXPECT_EQ(stream.next(result, 0ms), BackgroundStream::Next::ended);  // results not taken are dropped
}

TEST(BackgroundStream, ASourceErrorComesBackAfterTheFramesBeforeIt) {
  CountingSource source(10, 6);
  BackgroundStream stream(SceneConfig{}, source, StreamConfig{2, 2, 2});
  EXPECT_EQ(take_all(stream), iota(6));
  EXPECT_EQ(stream.stop().error, "device lost");
}

TEST(BackgroundStream, ZeroFramesInFlightIsRejected) {
  CountingSource source(1);
  EXPECT_THROW(BackgroundStream(SceneConfig{}, source, StreamConfig{0, 1, 2}), Error);
}

TEST(PushSource, AFullSourceKeepsTheNewestFramesAndNumbersThemInPushOrder) {
  PushSource source(2);
  std::vector<std::uint64_t> pushed;
  for (int i = 0; i < 5; ++i) pushed.push_back(source.push(small_frame()));
  EXPECT_EQ(pushed, iota(5));
  source.close();
  std::vector<std::uint64_t> taken;
  while (std::optional<Frame> frame = source.next({})) taken.push_back(frame->index);
  EXPECT_EQ(taken, (std::vector<std::uint64_t>{3, 4}));
  EXPECT_THROW(PushSource(0), Error);
}

TEST(PushSource, AStopWakesAWaitingTaker) {
  PushSource source;
  std::stop_source stop;
  std::thread stopper([&] {
    std::this_thread::sleep_for(50ms);
    stop.request_stop();
  });
  EXPECT_FALSE(source.next(stop.get_token()).has_value());
  stopper.join();
}

TEST(PushSource, FramesPushedOutBeforeThePipelineTookThemCountAsDropped) {
  PushSource source(1);
  BackgroundStream stream(SceneConfig{}, source, StreamConfig{1, 1, 2});
  constexpr std::uint64_t kPushed = 30;
  for (std::uint64_t i = 0; i < kPushed; ++i) source.push(small_frame());  // faster than one frame in flight
  source.close();
  const std::vector<std::uint64_t> indices = take_all(stream);
  const PipelineOutcome& outcome = stream.stop();
  ASSERT_FALSE(indices.empty());
  EXPECT_EQ(indices.back(), kPushed - 1);  // the newest frame always gets through
  EXPECT_TRUE(std::is_sorted(indices.begin(), indices.end()));
  EXPECT_EQ(outcome.stats.frames_completed, indices.size());
  EXPECT_EQ(outcome.stats.frames_received + outcome.stats.sensor_gaps, kPushed - indices.front());
  EXPECT_TRUE(outcome.stats.adds_up());
}

}  // namespace
}  // namespace lccp
