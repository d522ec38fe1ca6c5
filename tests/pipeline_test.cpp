// The streaming pipeline: labels equal a serial run of the same frames (each
// segmented alone, ids matched frame to frame) for any number of frames in
// flight and threads, and partition each cloud as LccpSegmenter::segment does; frames reach the sink in order, depth frames are
// back-projected, drop_oldest drops and counts, errors stay with their frame or
// end run() after the frames in flight (returned, not thrown), the counts add
// up, and a stop request ends an endless stream.
#include <atomic>
#include <condition_variable>
#include <stop_token>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "lccp/frame_source.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/objects/scene.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/pipeline/pipeline.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

const std::vector<std::string> kScenes = {"mosd_test2", "mosd_test34", "mosd_test43", "mosd_test60"};

const SceneSegmenter& segmenter() {
  static const SceneSegmenter instance{SceneConfig{}};
  return instance;
}

// The mOSD scenes, each read once.
const PointCloud& scene(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<PointCloud>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<PointCloud>(
        read_cloud(std::filesystem::path(LCCP_TEST_DATA_DIR) / (name + ".pcd")).cloud);
  }
  return *slot;
}

// The labels a stream of these clouds must get: every stage of kStages run on
// one frame after the other, ids matched by one tracker.
std::vector<Labels> serial_stream_labels(const std::vector<const PointCloud*>& clouds) {
  SegmentTracker tracker = segmenter().new_tracker();
  std::vector<Labels> labels;
  for (const PointCloud* cloud : clouds) {
    SceneWork work(*cloud);
    for (const StageInfo& stage : kStages) {
      if (stage.stage != Stage::ids) segmenter().run_stage(stage.stage, work);
    }
    segmenter().assign_ids(work, &tracker);
    labels.push_back(work.take_result().labels);
  }
  return labels;
}

// LccpSegmenter::segment of each scene, computed once.
const Labels& reference_labels(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, Labels> cache;
  std::lock_guard lock(mutex);
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, LccpSegmenter(LccpConfig{}).segment(scene(name)).labels).first;
  return it->second;
}

// A small organized cloud (a box on a table, 320 x 240 camera) for the tests
// that need many frames, and its segment() labels.
const PointCloud& small_cloud() {
  static const PointCloud cloud =
      test::render(test::box_on_table().rects, test::PinholeCamera{262.5, 159.5, 119.5, 320, 240}).cloud;
  return cloud;
}
const Labels& small_reference() {
  static const Labels labels = segmenter().segment(small_cloud()).labels;
  return labels;
}

Frame cloud_frame(std::uint64_t index, const PointCloud& cloud, std::string name = {}) {
  Frame frame;
  frame.index = index;
  frame.cloud = cloud;
  frame.name = std::move(name);
  return frame;
}

// A depth image as the sensor would have delivered the organized 640 x 480
// cloud: z in millimetres, 0 where there is no point.
DepthImage depth_of(const PointCloud& cloud) {
  DepthImage depth;
  depth.width = cloud.width;
  depth.height = cloud.height;
  depth.horizontal_fov_rad = 2.0f * std::atan(320.0f / 525.0f);
  depth.vertical_fov_rad = 2.0f * std::atan(240.0f / 525.0f);
  depth.depth_mm.reserve(cloud.size());
  for (const Eigen::Vector3f& p : cloud.points) {
    const bool valid = p.allFinite() && p.z() > 0;
    depth.depth_mm.push_back(valid ? static_cast<std::uint16_t>(std::lround(p.z() * 1000.0f)) : 0);
  }
  return depth;
}

// Frames from memory, in order. Optionally throws lccp::Error("device lost")
// when asked for frame `throw_at`.
class VectorSource : public FrameSource {
 public:
  explicit VectorSource(std::vector<Frame> frames, bool live = false, std::optional<std::size_t> throw_at = {})
      : frames_(std::move(frames)), live_(live), throw_at_(throw_at) {}

  std::optional<Frame> next(std::stop_token stop) override {
    if (stop.stop_requested()) return std::nullopt;
    if (throw_at_ && next_ == *throw_at_) throw Error("device lost");
    if (next_ == frames_.size()) return std::nullopt;
    Frame frame = frames_[next_++];
    frame.captured = Clock::now();
    return frame;
  }
  std::optional<std::uint64_t> frame_count() const override { return frames_.size(); }
  bool is_live() const override { return live_; }

 private:
  std::vector<Frame> frames_;
  bool live_;
  std::optional<std::size_t> throw_at_;
  std::size_t next_ = 0;
};

// An endless stream of the small cloud, frame indices 0, 1, 2, ... After
// `block_after` frames (if given), next() blocks until a stop is requested.
class EndlessSource : public FrameSource {
 public:
  explicit EndlessSource(bool live, std::optional<std::uint64_t> block_after = {})
      : live_(live), block_after_(block_after) {}

  std::optional<Frame> next(std::stop_token stop) override {
    if (block_after_ && index_ == *block_after_) {
      std::mutex mutex;
      std::condition_variable_any never_notified;
      std::unique_lock lock(mutex);
      never_notified.wait(lock, stop, [] { return false; });
    }
    if (stop.stop_requested()) return std::nullopt;
    Frame frame = cloud_frame(index_++, small_cloud());
    frame.captured = Clock::now();
    return frame;
  }
  std::optional<std::uint64_t> frame_count() const override { return std::nullopt; }
  bool is_live() const override { return live_; }

 private:
  bool live_;
  std::optional<std::uint64_t> block_after_;
  std::uint64_t index_ = 0;
};

// What the sink saw, in call order.
struct Delivered {
  std::vector<std::uint64_t> indices;
  std::vector<FrameResult> results;
};

// Runs f with at most n threads: the global limit plus an arena of exactly n slots.
template <class F>
auto with_threads(int n, F&& f) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(n));
  tbb::task_arena arena(n);
  return arena.execute(std::forward<F>(f));
}

bool strictly_increasing(const std::vector<std::uint64_t>& v) {
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (v[i] <= v[i - 1]) return false;
  }
  return true;
}

// --- labels and order ------------------------------------------------------------------

class PipelineMatchesSegment : public ::testing::TestWithParam<std::tuple<unsigned, int>> {};

TEST_P(PipelineMatchesSegment, LabelsEqualSegmentAndFramesArriveInOrder) {
  const auto [frames_in_flight, threads] = GetParam();
  const std::size_t frame_count = 2 * kScenes.size();  // every scene twice
  std::vector<Frame> frames;
  for (std::size_t i = 0; i < frame_count; ++i) {
    const std::string& name = kScenes[i % kScenes.size()];
    frames.push_back(cloud_frame(i, scene(name), name));
  }
  std::vector<const PointCloud*> clouds;
  for (std::size_t i = 0; i < frame_count; ++i) clouds.push_back(&scene(kScenes[i % kScenes.size()]));
  static const std::vector<Labels> serial = serial_stream_labels(clouds);
  VectorSource source(std::move(frames));
  Pipeline pipeline(segmenter(), PipelineConfig{frames_in_flight});

  Delivered seen;
  const PipelineStats stats = with_threads(threads, [&] {
    return pipeline.run(source, [&](FrameResult& result) {
      seen.indices.push_back(result.frame.index);
      seen.results.push_back(std::move(result));
    }).stats;
  });

  EXPECT_EQ(stats.frames_received, frame_count);
  EXPECT_EQ(stats.frames_completed, frame_count);
  EXPECT_EQ(stats.frames_dropped, 0u);
  EXPECT_GT(stats.wall_seconds, 0.0);
  ASSERT_EQ(seen.results.size(), frame_count);
  for (std::size_t i = 0; i < frame_count; ++i) {
    const FrameResult& r = seen.results[i];
    const std::string& name = kScenes[i % kScenes.size()];
    EXPECT_EQ(r.frame.index, i);
    EXPECT_EQ(r.frame.name, name);
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.frame.cloud.size(), scene(name).size());
    EXPECT_TRUE(r.segmentation.labels == serial[i]) << name;
    EXPECT_TRUE(test::same_partition(r.segmentation.labels, reference_labels(name))) << name;
    EXPECT_GT(r.segmentation.segment_count, 1u);
    EXPECT_GT(r.segmentation.times[Stage::voxelize], 0.0);
    EXPECT_GT(r.segmentation.times[Stage::growth], 0.0);
    EXPECT_GT(r.segmentation.times[Stage::filter], 0.0);
    EXPECT_EQ(r.back_projection_ms, 0.0);  // a cloud frame is not back-projected
    EXPECT_GE(r.end_to_end_ms(), r.segmentation.times.total_ms() * 0.999);
  }
}

INSTANTIATE_TEST_SUITE_P(Pipeline, PipelineMatchesSegment,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u), ::testing::Values(1, 2)),
                         [](const ::testing::TestParamInfo<std::tuple<unsigned, int>>& info) {
                           return "K" + std::to_string(std::get<0>(info.param)) + "_threads" +
                                  std::to_string(std::get<1>(info.param));
                         });

// The flood growth (the default) through the stream: one real frame, 2K + 1
// times, with K frames in flight on 2 threads. A tracker's first frame gives
// object k id k and an identical frame keeps them (SegmentTracker), so every
// copy's ids are byte for byte the labels LccpSegmenter::segment gives the frame.
class PipelineFloodMatchesSegment : public ::testing::TestWithParam<unsigned> {};

TEST_P(PipelineFloodMatchesSegment, RepeatedFrameLabelsEqualSegmentByteForByte) {
  const unsigned frames_in_flight = GetParam();
  SceneConfig config;
  config.objects.supervoxels.growth = Growth::flood;
  const SceneSegmenter flood(config);
  const PointCloud& cloud = scene("mosd_test43");
  const SegmentationResult alone = LccpSegmenter(config.objects).segment(cloud);
  ASSERT_GT(alone.segment_count, 1u);
  const std::size_t frame_count = 2 * frames_in_flight + 1;
  std::vector<Frame> frames;
  for (std::size_t i = 0; i < frame_count; ++i) frames.push_back(cloud_frame(i, cloud));
  VectorSource source(std::move(frames));
  std::vector<FrameResult> seen;
  const PipelineStats stats = with_threads(2, [&] {
    return Pipeline(flood, PipelineConfig{frames_in_flight}).run(source, [&](FrameResult& r) { seen.push_back(std::move(r)); }).stats;
  });
  EXPECT_EQ(stats.frames_completed, frame_count);
  ASSERT_EQ(seen.size(), frame_count);
  for (const FrameResult& r : seen) {
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_TRUE(r.segmentation.labels == alone.labels) << "frame " << r.frame.index;
    EXPECT_EQ(r.segmentation.voxel_count, alone.voxel_count);
    EXPECT_EQ(r.segmentation.supervoxel_count, alone.supervoxel_count);
    EXPECT_EQ(r.segmentation.segment_count, alone.segment_count);
  }
}

INSTANTIATE_TEST_SUITE_P(Pipeline, PipelineFloodMatchesSegment, ::testing::Values(1u, 2u, 3u),
                         [](const ::testing::TestParamInfo<unsigned>& info) { return "K" + std::to_string(info.param); });

TEST(PipelineDepth, DepthFramesAreBackProjectedThenSegmented) {
  const std::vector<std::string> names = {"mosd_test2", "mosd_test60"};
  std::vector<Frame> frames;
  for (std::size_t i = 0; i < names.size(); ++i) {
    ASSERT_EQ(scene(names[i]).width, 640u);
    ASSERT_EQ(scene(names[i]).height, 480u);
    Frame frame;
    frame.index = i;
    frame.depth = depth_of(scene(names[i]));
    frames.push_back(std::move(frame));
  }
  std::vector<PointCloud> clouds;
  for (const Frame& frame : frames) clouds.push_back(back_project(*frame.depth));
  const std::vector<Labels> expected = serial_stream_labels({&clouds[0], &clouds[1]});

  VectorSource source(std::move(frames));
  Pipeline pipeline(segmenter(), PipelineConfig{2});
  std::vector<FrameResult> seen;
  const PipelineStats stats = pipeline.run(source, [&](FrameResult& r) { seen.push_back(std::move(r)); }).stats;

  EXPECT_EQ(stats.frames_completed, names.size());
  ASSERT_EQ(seen.size(), names.size());
  for (std::size_t i = 0; i < seen.size(); ++i) {
    const FrameResult& r = seen[i];
    EXPECT_EQ(r.frame.index, i);
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_FALSE(r.frame.depth.has_value());
    EXPECT_EQ(r.frame.cloud.width, 640u);
    EXPECT_EQ(r.frame.cloud.height, 480u);
    EXPECT_EQ(r.frame.cloud.size(), 640u * 480u);
    EXPECT_GT(r.back_projection_ms, 0.0);
    EXPECT_TRUE(r.segmentation.labels == expected[i]) << names[i];
  }
}

// --- drop policy -------------------------------------------------------------------------

// A live source far faster than a slow sink. Accounting: every frame taken
// from the source is completed or dropped by the policy, and frames_dropped
// also holds the gaps in the source's index.
TEST(PipelineDropOldest, DropsAreCountedAndFramesStayInOrder) {
  constexpr std::uint64_t kFrames = 40;
  std::vector<Frame> frames;
  std::uint64_t index = 0;
  std::uint64_t gaps = 0;
  for (std::uint64_t i = 0; i < kFrames; ++i) {
    if (i > 0 && i % 10 == 0) {  // the sensor lost two frames here
      index += 2;
      gaps += 2;
    }
    frames.push_back(cloud_frame(index++, small_cloud()));
  }
  VectorSource source(std::move(frames), /*live=*/true);
  Pipeline pipeline(segmenter(), PipelineConfig{2});

  Delivered seen;
  const PipelineStats stats = pipeline.run(source, [&](FrameResult& r) {
    seen.indices.push_back(r.frame.index);
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_TRUE(r.segmentation.labels == small_reference());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // a slow consumer, not synchronization
  }).stats;

  EXPECT_EQ(stats.frames_received, kFrames);
  EXPECT_EQ(stats.frames_completed, seen.indices.size());
  EXPECT_GE(stats.frames_completed, 1u);
  EXPECT_LT(stats.frames_completed, kFrames);
  EXPECT_EQ(stats.sensor_gaps, gaps);
  EXPECT_EQ(stats.frames_failed, 0u);
  EXPECT_EQ(stats.frames_received - stats.frames_completed + gaps, stats.frames_dropped);
  EXPECT_TRUE(stats.adds_up());
  EXPECT_TRUE(strictly_increasing(seen.indices));
  // The newest frame always gets through: the last one is never dropped.
  EXPECT_EQ(seen.indices.back(), kFrames - 1 + gaps);
}

// A live source gets K synthetic frames through the graph before its own
// (PipelineConfig::warm_up): none of them reaches the sink, the counts or the
// stream's ids, so frame 0 gets the ids a fresh tracker gives it.
TEST(PipelineWarmUp, SyntheticFramesNeverReachTheSinkCountsOrIds) {
  constexpr std::uint64_t kFrames = 6;
  const auto frames = [&] {
    std::vector<Frame> list;
    for (std::uint64_t i = 0; i < kFrames; ++i) list.push_back(cloud_frame(i, small_cloud()));
    return list;
  };
  Labels first_without_warm_up;
  VectorSource recording(frames());
  Pipeline(segmenter(), PipelineConfig{2}).run(recording, [&](FrameResult& r) {
    if (r.frame.index == 0) first_without_warm_up = r.segmentation.labels;
  });
  ASSERT_FALSE(first_without_warm_up.empty());

  for (const unsigned frames_in_flight : {1u, 2u, 3u}) {
    VectorSource live(frames(), /*live=*/true);
    Delivered seen;
    const PipelineStats stats = Pipeline(segmenter(), PipelineConfig{frames_in_flight}).run(live, [&](FrameResult& r) {
      EXPECT_TRUE(r.error.empty()) << r.error;
      EXPECT_EQ(r.frame.cloud.size(), small_cloud().size());
      seen.indices.push_back(r.frame.index);
      seen.results.push_back(std::move(r));
    }).stats;
    EXPECT_EQ(stats.frames_received, kFrames);
    EXPECT_EQ(stats.frames_completed, seen.indices.size());
    EXPECT_EQ(stats.frames_failed, 0u);
    EXPECT_TRUE(stats.adds_up());
    ASSERT_FALSE(seen.indices.empty());
    EXPECT_EQ(seen.indices.front(), 0u);
    EXPECT_EQ(seen.indices.back(), kFrames - 1);
    EXPECT_TRUE(seen.results.front().segmentation.labels == first_without_warm_up) << "K = " << frames_in_flight;
  }
}

TEST(PipelineBlock, IndexGapsAreCountedAsDrops) {
  std::vector<Frame> frames;
  for (std::uint64_t index : {5, 6, 9, 10, 14}) frames.push_back(cloud_frame(index, small_cloud()));
  VectorSource source(std::move(frames));
  Pipeline pipeline(segmenter(), PipelineConfig{2});
  std::vector<std::uint64_t> seen;
  const PipelineStats stats = pipeline.run(source, [&](FrameResult& r) { seen.push_back(r.frame.index); }).stats;
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{5, 6, 9, 10, 14}));
  EXPECT_EQ(stats.sensor_gaps, 5u);
  EXPECT_TRUE(stats.adds_up());
  EXPECT_EQ(stats.frames_received, 5u);
  EXPECT_EQ(stats.frames_completed, 5u);
  EXPECT_EQ(stats.frames_dropped, 2u + 3u);  // 7-8 and 11-13 never arrived; nothing before the first frame
}

// --- errors ------------------------------------------------------------------------------

TEST(PipelineSourceError, FramesInFlightReachTheSinkThenRunReturnsTheError) {
  for (const DropPolicy policy : {DropPolicy::block, DropPolicy::drop_oldest}) {
    std::vector<Frame> frames;
    for (std::uint64_t i = 0; i < 6; ++i) frames.push_back(cloud_frame(i, small_cloud()));
    VectorSource source(std::move(frames), policy == DropPolicy::drop_oldest, /*throw_at=*/3);
    Pipeline pipeline(segmenter(), PipelineConfig{2});
    std::vector<std::uint64_t> seen;
    const PipelineOutcome outcome = pipeline.run(source, [&](FrameResult& r) {
      EXPECT_TRUE(r.segmentation.labels == small_reference());
      seen.push_back(r.frame.index);
    });
    EXPECT_EQ(outcome.error, "device lost");
    EXPECT_EQ(outcome.stats.frames_received, 3u);
    EXPECT_EQ(outcome.stats.frames_completed, seen.size());
    EXPECT_TRUE(outcome.stats.adds_up());
    if (policy == DropPolicy::block) {
      EXPECT_EQ(seen, (std::vector<std::uint64_t>{0, 1, 2}));
    } else {  // frames may have been dropped, but the last one before the error got through
      EXPECT_TRUE(strictly_increasing(seen));
      ASSERT_FALSE(seen.empty());
      EXPECT_EQ(seen.back(), 2u);
    }
  }
}

TEST(PipelineStageError, FailedFrameReachesTheSinkAndTheStreamGoesOn) {
  PointCloud no_finite_points;
  no_finite_points.width = 10;
  no_finite_points.height = 10;
  no_finite_points.points.assign(100, Eigen::Vector3f::Constant(test::kNaN));
  Frame bad_depth;
  bad_depth.index = 3;
  bad_depth.depth = DepthImage{4, 4, 1.0f, 1.0f, std::vector<std::uint16_t>(3, 1000)};  // 3 pixels for 4 x 4

  std::vector<Frame> frames;
  frames.push_back(cloud_frame(0, small_cloud()));
  frames.push_back(cloud_frame(1, no_finite_points));
  frames.push_back(cloud_frame(2, small_cloud()));
  frames.push_back(std::move(bad_depth));
  frames.push_back(cloud_frame(4, small_cloud()));
  VectorSource source(std::move(frames));
  Pipeline pipeline(segmenter(), PipelineConfig{3});
  std::vector<FrameResult> seen;
  const PipelineStats stats = pipeline.run(source, [&](FrameResult& r) { seen.push_back(std::move(r)); }).stats;

  EXPECT_EQ(stats.frames_completed, 3u);
  EXPECT_EQ(stats.frames_failed, 2u);
  EXPECT_TRUE(stats.adds_up());
  ASSERT_EQ(seen.size(), 5u);
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i].frame.index, i);
  for (std::size_t i : {0, 2, 4}) {
    EXPECT_TRUE(seen[i].error.empty()) << seen[i].error;
    EXPECT_TRUE(seen[i].segmentation.labels == small_reference());
  }
  EXPECT_NE(seen[1].error.find("no finite points"), std::string::npos) << seen[1].error;
  EXPECT_EQ(seen[1].segmentation.labels, Labels(100, 0));
  EXPECT_EQ(seen[1].segmentation.segment_count, 0u);
  EXPECT_NE(seen[3].error.find("depth image"), std::string::npos) << seen[3].error;
  EXPECT_TRUE(seen[3].segmentation.labels.empty());  // no cloud: no points to label
}

TEST(PipelineSinkError, NoMoreFramesAreTakenAndRunReturnsTheError) {
  EndlessSource source(/*live=*/false);
  Pipeline pipeline(segmenter(), PipelineConfig{2});
  int calls = 0;
  const PipelineOutcome outcome = pipeline.run(source, [&](FrameResult&) {
    if (++calls == 2) throw Error("disk full");
  });
  EXPECT_EQ(outcome.error, "disk full");
  EXPECT_EQ(calls, 2);  // not called again after it threw
  EXPECT_EQ(outcome.stats.frames_completed, 1u);
  EXPECT_EQ(outcome.stats.frames_failed, 1u);  // the frame the sink threw on
  EXPECT_TRUE(outcome.stats.adds_up());
}

// --- stop --------------------------------------------------------------------------------

// Requests a stop on token() once the sink has seen `frames` frames.
class StopAfter {
 public:
  explicit StopAfter(std::size_t frames)
      : frames_(frames), thread_([this] {
          std::unique_lock lock(mutex_);
          seen_changed_.wait(lock, [&] { return seen_ >= frames_ || abandoned_; });
          stop_called_ = Clock::now();
          lock.unlock();
          stop_.request_stop();
        }) {}
  ~StopAfter() {  // also when run() returned before the sink saw enough frames
    {
      std::lock_guard lock(mutex_);
      abandoned_ = true;
    }
    seen_changed_.notify_one();
    thread_.join();
  }

  void saw_frame() {
    {
      std::lock_guard lock(mutex_);
      ++seen_;
    }
    seen_changed_.notify_one();
  }
  std::stop_token token() const { return stop_.get_token(); }
  Clock::time_point stop_called() {
    std::lock_guard lock(mutex_);
    return stop_called_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable seen_changed_;
  std::size_t seen_ = 0;
  std::size_t frames_;
  bool abandoned_ = false;
  Clock::time_point stop_called_{};
  std::stop_source stop_;
  std::thread thread_;
};

TEST(PipelineStop, EndsAnEndlessStreamWithEveryTakenFrameCompleted) {
  for (const DropPolicy policy : {DropPolicy::block, DropPolicy::drop_oldest}) {
    EndlessSource source(/*live=*/policy == DropPolicy::drop_oldest);
    Pipeline pipeline(segmenter(), PipelineConfig{2});
    std::vector<std::uint64_t> seen;
    PipelineStats stats;
    Clock::time_point returned;
    {
      StopAfter stopper(3);
      const PipelineOutcome outcome = pipeline.run(
          source,
          [&](FrameResult& r) {
            EXPECT_TRUE(r.segmentation.labels == small_reference());
            seen.push_back(r.frame.index);
            stopper.saw_frame();
          },
          stopper.token());
      EXPECT_EQ(outcome.error, "");
      stats = outcome.stats;
      returned = Clock::now();
      const double stop_to_return_s = std::chrono::duration<double>(returned - stopper.stop_called()).count();
      EXPECT_LT(stop_to_return_s, 5.0);
    }
    EXPECT_GE(seen.size(), 3u);
    EXPECT_EQ(stats.frames_completed, seen.size());
    EXPECT_TRUE(strictly_increasing(seen));
    EXPECT_TRUE(stats.adds_up());
    // Lossless until the stop: frames 0, 1, 2, ... reached the sink, and the
    // frame the source handed over while the stop came is not received, so a
    // lossless source drops nothing.
    if (policy == DropPolicy::block) {
      EXPECT_EQ(seen.back(), seen.size() - 1);
      EXPECT_EQ(stats.frames_received, seen.size());
    }
    EXPECT_LE(stats.frames_dropped, policy == DropPolicy::block ? 0u : stats.frames_received);
  }
}

TEST(PipelineStop, UnblocksASourceWaitingForItsNextFrame) {
  EndlessSource source(/*live=*/false, /*block_after=*/2);
  Pipeline pipeline(segmenter(), PipelineConfig{2});
  std::vector<std::uint64_t> seen;
  PipelineStats stats;
  {
    StopAfter stopper(2);
    stats = pipeline.run(
                    source,
                    [&](FrameResult& r) {
                      seen.push_back(r.frame.index);
                      stopper.saw_frame();
                    },
                    stopper.token())
                .stats;
  }
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{0, 1}));
  EXPECT_EQ(stats.frames_received, 2u);
  EXPECT_EQ(stats.frames_completed, 2u);
}

TEST(PipelineConstruction, ZeroFramesInFlightIsRejected) {
  EXPECT_THROW(Pipeline(segmenter(), PipelineConfig{0}), Error);
  EXPECT_NO_THROW(Pipeline(segmenter(), PipelineConfig{1}));
}

TEST(PipelineStop, AStopBeforeRunTakesNoFrame) {
  EndlessSource source(/*live=*/false);
  std::stop_source stop;
  stop.request_stop();
  int calls = 0;
  const PipelineOutcome outcome = Pipeline(segmenter(), PipelineConfig{2}).run(source, [&](FrameResult&) { ++calls; },
                                                                                stop.get_token());
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(outcome.stats.frames_received, 0u);
  EXPECT_TRUE(outcome.stats.adds_up());
}

}  // namespace
}  // namespace lccp
