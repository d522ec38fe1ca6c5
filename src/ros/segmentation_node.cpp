// The ROS-free half of the lccp_ros node (C++20): the library's PushSource and
// BackgroundStream, results as plain data.
#include "segmentation_node.hpp"

#include <cstring>
#include <map>
#include <mutex>
#include <sstream>

#include "frame_conversion.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/io/segments_json.hpp"
#include "lccp/metrics/statistics.hpp"
#include "lccp/pipeline/background_stream.hpp"
#include "lccp/pipeline/push_source.hpp"

namespace lccp::ros_node {
namespace {

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
    latency.push_back({name, percentile(std::move(values), 0.5)});
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
  std::vector<std::string> names = config_key_names(load_preset_or_file(config));
  for (std::string& name : names) {
    if (name.starts_with("parts.")) name.replace(0, 6, "parts/");
  }
  return names;
}

struct SegmentationNode::Impl {
  struct Header {
    std::uint64_t stamp_ns = 0;
    std::string frame_id;
  };

  Impl(const NodeSettings& settings, Publish publish_to)
      : publish(std::move(publish_to)),
        stream(resolve_config(settings.config, settings.settings), source,
               StreamConfig{settings.frames_in_flight, static_cast<int>(settings.threads)},
               [this](FrameResult& result) { deliver(result); }) {}

  void push(Frame frame, Header header) {
    const std::lock_guard lock(mutex);  // the index and its header together
    headers.emplace(source.push(std::move(frame)), std::move(header));
  }

  void deliver(FrameResult& result) {
    FrameOutput out = output_of(result);
    {
      const std::lock_guard lock(mutex);
      auto header = headers.find(result.frame.index);
      if (header != headers.end()) {
        out.stamp_ns = header->second.stamp_ns;
        out.frame_id = std::move(header->second.frame_id);
      }
      headers.erase(headers.begin(), headers.upper_bound(result.frame.index));  // these frames are gone
      window.push_back({result.segmentation.times, result.back_projection_ms, result.end_to_end_ms()});
    }
    publish(std::move(out));
  }

  Publish publish;
  PushSource source;         // frames from the subscriber callbacks
  std::mutex mutex;          // guards what follows
  std::map<std::uint64_t, Header> headers;
  std::vector<LatencySample> window;
  BackgroundStream stream;   // last: it starts once everything it uses exists
};

SegmentationNode::SegmentationNode(const NodeSettings& settings, Publish publish)
    : impl_(std::make_unique<Impl>(settings, std::move(publish))) {}

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
  {
    const std::lock_guard lock(impl_->mutex);
    window.swap(impl_->window);
  }
  const PipelineStats stats = impl_->stream.stats();
  return {stats.frames_received, stats.sensor_gaps,    stats.frames_completed,
          stats.frames_failed,   stats.frames_dropped, window.size(),
          median_latencies(window)};
}

std::string SegmentationNode::stop() {
  const PipelineOutcome& outcome = impl_->stream.stop();
  const PipelineStats& stats = outcome.stats;
  std::ostringstream line;
  line << "frames " << stats.frames_received << " received + " << stats.sensor_gaps << " gaps = "
       << stats.frames_completed << " completed + " << stats.frames_failed << " failed + " << stats.frames_dropped
       << " dropped";
  if (!outcome.error.empty()) line << "; error: " << outcome.error;
  return line.str();
}

}  // namespace lccp::ros_node
