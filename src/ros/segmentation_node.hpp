#pragma once
// The ROS-free half of the lccp_ros node (C++20 inside, this header C++17 too):
// frames pushed by the subscriber callbacks go into the library's PushSource and
// through its BackgroundStream; every result comes back as plain data for the
// ROS half (ros_node.cpp) to publish. A ROS 2 adapter would use this class unchanged.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ros_frames.hpp"

namespace lccp::ros_node {

struct NodeSettings {
  std::string config = "p1";               // preset name or YAML path (load_preset_or_file)
  std::vector<std::string> settings;       // "key=value" overrides, "parts.key=value" for the second level
  unsigned frames_in_flight = 2;           // K
  unsigned threads = 0;                    // threads of the node's task arena; 0: all cores
};

// An oriented box (the segment's obb) for the markers.
struct SegmentBox {
  std::uint32_t id = 0;
  bool is_part = false;
  std::array<float, 3> center{};
  std::array<float, 9> axes{};  // row-major 3x3, columns the box's unit axes
  std::array<float, 3> extents{};
  std::array<std::uint8_t, 3> color{};  // the segment's colour in the label image
};

struct FrameOutput {
  std::uint64_t stamp_ns = 0;  // the input's header
  std::string frame_id;
  std::uint32_t width = 0;     // the cloud's layout: organized when height > 1
  std::uint32_t height = 1;
  std::vector<float> xyz;                 // 3 per point, the back-projected or received points
  std::vector<std::uint32_t> labels;      // per point: part (finest level) id, 0 = no data
  std::vector<std::uint32_t> objects;     // per point: object id (equal to labels with one level)
  std::vector<std::uint8_t> label_rgb;    // 3 per point: the library's label colours
  std::string segments_json;              // encode_segments_json, one document
  std::vector<SegmentBox> boxes;          // objects, then their parts
  std::string error;                      // a stage's error: labels all 0
};

struct StageLatency {
  std::string name;  // kStages names, "back_projection", "end_to_end"
  double p50_ms = 0;
};

// The stream's PipelineStats as they stand (see lccp/pipeline/pipeline.hpp;
// this header stays C++17, so the counts are copied out) and the latencies.
struct NodeDiagnostics {
  std::uint64_t received = 0;   // frames the pipeline took
  std::uint64_t gaps = 0;       // frames pushed out before it took them (a newer message came first)
  std::uint64_t completed = 0;  // published with labels
  std::uint64_t failed = 0;     // published with a stage error
  std::uint64_t dropped = 0;    // never published: the gaps and the frames the pipeline had no room for
  std::uint64_t window_frames = 0;    // frames the latencies are taken over (the last second)
  std::vector<StageLatency> latency;  // p50 over the window
};

// The private parameter names the config accepts: its keys (describe_config),
// the second level's as "parts/KEY" (ROS names have no dots). Throws lccp::Error
// for an unknown preset or a bad file.
std::vector<std::string> config_parameter_names(const std::string& config);

class SegmentationNode {
 public:
  using Publish = std::function<void(FrameOutput&&)>;
  // Starts the stream. Throws lccp::Error (one line) for a bad config,
  // setting or frame count. `publish` is called in frame order, one call at a time.
  SegmentationNode(const NodeSettings& settings, Publish publish);
  ~SegmentationNode();  // stops: the frames in flight are finished and published
  SegmentationNode(const SegmentationNode&) = delete;
  SegmentationNode& operator=(const SegmentationNode&) = delete;

  void push(ros_bridge::DepthMessage&& depth);
  void push(ros_bridge::CloudMessage&& cloud);
  // Counts since the start; latencies over the last second (and forgets them).
  NodeDiagnostics take_diagnostics();
  // Stops the stream; its counts (for the log): "frames R received ...".
  std::string stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lccp::ros_node
