// The ROS-free half of the lccp_ros node (C++20): a live queue source, the
// library's Pipeline on its own thread, results as plain data.
#include "segmentation_node.hpp"

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stop_token>
#include <thread>

#include <tbb/task_arena.h>

#include "frame_conversion.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/io/segments_json.hpp"
#include "lccp/pipeline/pipeline.hpp"

namespace lccp::ros_node {
namespace {

// Frames from the subscriber callbacks, at most kQueueFrames waiting: a newer
// frame replaces the oldest (its index is then missing, and the pipeline counts
// it as dropped). Live, so the pipeline's admission drops the oldest too.
class FrameQueue final : public FrameSource {
 public:
  static constexpr std::size_t kQueueFrames = 1;

  void push(Frame frame) {
    {
      const std::lock_guard lock(mutex_);
      if (queue_.size() >= kQueueFrames) queue_.pop_front();
      queue_.push_back(std::move(frame));
    }
    ready_.notify_one();
  }

  std::optional<Frame> next(std::stop_token stop) override {
    std::unique_lock lock(mutex_);
    ready_.wait(lock, stop, [&] { return !queue_.empty(); });
    if (queue_.empty()) return std::nullopt;
    Frame frame = std::move(queue_.front());
    queue_.pop_front();
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override { return std::nullopt; }
  bool is_live() const override { return true; }

 private:
  std::mutex mutex_;
  std::condition_variable_any ready_;
  std::deque<Frame> queue_;
};

SegmentBox box_of(const SegmentGeometry& segment, bool is_part, std::uint32_t object_id) {
  SegmentBox box;
  box.id = segment.id;
  box.is_part = is_part;
  for (int row = 0; row < 3; ++row) {
    box.center[row] = segment.obb.center[row];
    box.extents[row] = segment.obb.extents[row];
    for (int col = 0; col < 3; ++col) box.axes[3 * row + col] = segment.obb.axes(row, col);
  }
  box.color = is_part ? part_color(object_id, segment.id) : label_color(segment.id);
  return box;
}

void fill_points(const FrameResult& result, FrameOutput& out) {
  const PointCloud& cloud = result.frame.cloud;
  const SceneSegmentation& scene = result.segmentation;
  out.width = cloud.width;
  out.height = cloud.height;
  out.xyz.resize(cloud.size() * 3);
  out.labels = scene.labels;
  out.objects = scene.objects.empty() ? scene.labels : scene.objects;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) out.xyz[3 * i + axis] = cloud.points[i][axis];
  }
  const auto rgb = label_rgb(scene.labels, scene.objects.empty() ? nullptr : &scene.objects);
  static_assert(sizeof(rgb[0]) == 3);
  out.label_rgb.resize(3 * rgb.size());
  std::memcpy(out.label_rgb.data(), rgb.data(), out.label_rgb.size());
}

FrameOutput output_of(const FrameResult& result) {
  FrameOutput out;
  fill_points(result, out);
  out.error = result.error;
  out.segments_json = encode_segments_json(result.frame.index, result.frame.timestamp_us, result.segmentation);
  for (const ObjectSegments& object : result.segmentation.segments) {
    out.boxes.push_back(box_of(object.object, false, object.object.id));
    for (const SegmentGeometry& part : object.parts) out.boxes.push_back(box_of(part, true, object.object.id));
  }
  return out;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

struct LatencySample {
  StageTimes stages;
  double back_projection_ms = 0;
  double end_to_end_ms = 0;
};

std::vector<StageLatency> median_latencies(const std::vector<LatencySample>& samples) {
  std::vector<StageLatency> latency;
  const auto column = [&](const std::string& name, const auto& get) {
    std::vector<double> values;
    for (const LatencySample& sample : samples) values.push_back(get(sample));
    latency.push_back({name, median(std::move(values))});
  };
  column("back_projection", [](const LatencySample& s) { return s.back_projection_ms; });
  for (const StageInfo& info : kStages) {
    column(std::string(info.name), [&](const LatencySample& s) { return s.stages[info.stage]; });
  }
  column("end_to_end", [](const LatencySample& s) { return s.end_to_end_ms; });
  return latency;
}

}  // namespace

std::vector<std::string> config_parameter_names(const std::string& config) {
  std::vector<std::string> names;
  std::istringstream lines(describe_config(load_preset_or_file(config)));
  for (std::string line; std::getline(lines, line);) {
    std::string name = line.substr(0, line.find(':'));
    if (name.starts_with("parts.")) name.replace(0, 6, "parts/");
    names.push_back(name);
  }
  return names;
}

struct SegmentationNode::Impl {
  struct Header {
    std::uint64_t stamp_ns = 0;
    std::string frame_id;
  };

  Impl(const NodeSettings& settings, Publish publish_to)
      : arena(settings.threads > 0 ? static_cast<int>(settings.threads) : tbb::task_arena::automatic),
        segmenter(resolve_config(settings.config, settings.settings)),
        pipeline(segmenter, PipelineConfig{settings.frames_in_flight}),
        publish(std::move(publish_to)) {}

  void push(Frame frame, Header header) {
    {
      const std::lock_guard lock(mutex);
      frame.index = received++;
      headers.emplace(frame.index, std::move(header));
    }
    queue.push(std::move(frame));
  }

  void deliver(FrameResult& result) {
    FrameOutput out = output_of(result);
    {
      const std::lock_guard lock(mutex);
      // Frames before this one that never came: dropped by the queue or the pipeline.
      dropped += result.frame.index - next_expected;
      next_expected = result.frame.index + 1;
      auto header = headers.find(result.frame.index);
      if (header != headers.end()) {
        out.stamp_ns = header->second.stamp_ns;
        out.frame_id = std::move(header->second.frame_id);
      }
      headers.erase(headers.begin(), headers.upper_bound(result.frame.index));
      (result.error.empty() ? completed : failed) += 1;
      window.push_back({result.segmentation.times, result.back_projection_ms, result.end_to_end_ms()});
    }
    publish(std::move(out));
  }

  tbb::task_arena arena;  // the pipeline's threads: a nodelet shares its process, so no global setting
  SceneSegmenter segmenter;
  Pipeline pipeline;
  Publish publish;
  FrameQueue queue;
  std::stop_source stop;
  PipelineOutcome outcome;
  std::thread thread;

  std::mutex mutex;  // guards what follows
  std::map<std::uint64_t, Header> headers;
  std::uint64_t received = 0, completed = 0, failed = 0, dropped = 0, next_expected = 0;
  std::vector<LatencySample> window;
};

SegmentationNode::SegmentationNode(const NodeSettings& settings, Publish publish)
    : impl_(std::make_unique<Impl>(settings, std::move(publish))) {
  Impl& impl = *impl_;
  impl.thread = std::thread([&impl] {
    impl.arena.execute([&impl] {
      impl.outcome = impl.pipeline.run(impl.queue, [&impl](FrameResult& result) { impl.deliver(result); },
                                       impl.stop.get_token());
    });
  });
}

SegmentationNode::~SegmentationNode() { stop(); }

void SegmentationNode::push(ros_bridge::DepthMessage&& depth) {
  Impl::Header header{depth.stamp_ns, depth.frame_id};
  impl_->push(ros_bridge::to_frame(std::move(depth), 0), std::move(header));
}

void SegmentationNode::push(ros_bridge::CloudMessage&& cloud) {
  Impl::Header header{cloud.stamp_ns, cloud.frame_id};
  impl_->push(ros_bridge::to_frame(std::move(cloud), 0), std::move(header));
}

NodeDiagnostics SegmentationNode::take_diagnostics() {
  std::vector<LatencySample> window;
  NodeDiagnostics diagnostics;
  {
    const std::lock_guard lock(impl_->mutex);
    window.swap(impl_->window);
    diagnostics = {impl_->received, impl_->completed, impl_->failed, impl_->dropped, window.size(), {}};
  }
  diagnostics.latency = median_latencies(window);
  return diagnostics;
}

std::string SegmentationNode::stop() {
  if (!impl_->thread.joinable()) return {};
  impl_->stop.request_stop();
  impl_->thread.join();
  const PipelineStats& stats = impl_->outcome.stats;
  std::ostringstream line;
  line << "frames " << stats.frames_received << " received + " << stats.sensor_gaps << " gaps = "
       << stats.frames_completed << " completed + " << stats.frames_failed << " failed + " << stats.frames_dropped
       << " dropped";
  if (!impl_->outcome.error.empty()) line << "; error: " << impl_->outcome.error;
  return line.str();
}

}  // namespace lccp::ros_node
