#pragma once
// What the view sends: a frame sampled on the sink thread (sample_frame, a
// copy and nothing more), then encoded on the server's thread (encode_frame).
//
// One binary WebSocket message per frame, little-endian:
//   u32 n, then n bytes of JSON (the header: frame, segments, counts, latency),
//   zero padding to a multiple of 4,
//   u32 r, {u16 label, u16 length}[r]   the sampled image's pixels, row after row, as runs
//                               of one label: segment index + 1 (0: none)
//   u8  shade[width * height]   grey Lambert shading of the surface, light at the camera
//   zero padding to a multiple of 4,
//   {i16 x, y, z (mm); u16 segment index + 1}[points]   the 3D view's points
// An unorganized cloud has no image (width = height = 0), only points.
#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lccp/metrics/statistics.hpp"
#include "lccp/pipeline/pipeline.hpp"

namespace lccp::view {

inline constexpr std::uint32_t kImageWidth = 320;    // the sampled image's size at most
inline constexpr std::uint32_t kImageHeight = 240;
inline constexpr std::size_t kMaxPoints3d = 20000;   // what a browser's canvas draws at 30 Hz

struct SegmentSample {
  std::uint32_t id = 0;      // the stable id (the label)
  std::uint32_t object = 0;  // its object's id (itself with one level)
  std::uint64_t points = 0;
  Eigen::Vector3f size = Eigen::Vector3f::Zero();      // the oriented box's edges, m
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  // m
  bool top_grasp = true;
  bool part = false;  // a part of a two-level object
};

// A frame as the view holds it between the sink and the encoder.
struct FrameSample {
  std::uint64_t index = 0;
  std::uint32_t width = 0, height = 0;   // the sampled image (0 x 0: unorganized)
  std::vector<Eigen::Vector3f> points;   // image pixels row by row, or up to kMaxPoints3d points
  std::vector<std::uint32_t> labels;     // per point: its segment's id, 0 for none
  std::vector<SegmentSample> segments;
  std::uint32_t support_id = 0;          // 0: no support plane
  std::string error;                     // the frame's stage error, if any
};

// One frame's latency figures, kept for the chart's window.
struct FrameTimes {
  double at_s = 0;  // seconds since the server started
  double end_to_end_ms = 0;
  StageTimes stages;
};

// The window's figures (lccp::percentiles, as the profile report), recomputed
// at most once a second: sorting a minute of frames for every message would
// cost more than the rest of it.
struct WindowFigures {
  Percentiles end_to_end;
  std::array<Percentiles, kStageCount> stages{};
  std::size_t frames = 0;
  double frames_per_second = 0;  // over the last two seconds
  double at_s = -1;              // the newest frame's time when computed
};

// The chart's window (the last minute) and the counts, as the header reports them.
struct RunFigures {
  PipelineStats stats;
  std::deque<FrameTimes> window;
  WindowFigures figures;
  bool ended = false;
};

// A decimated copy of the frame (at most kImageWidth x kImageHeight pixels).
FrameSample sample_frame(const FrameResult& result);

// The frame's times, for the window.
FrameTimes frame_times(const FrameResult& result, double at_s);

// Adds frames' times to the window, drops those older than 60 s, and
// recomputes the window's figures if a second has passed or the run ended.
void add_frame_times(RunFigures& run, const std::vector<FrameTimes>& times);

// The message for one frame (format above); without a frame (the run's end),
// the JSON header alone.
std::string encode_frame(const FrameSample* frame, const RunFigures& figures);

}  // namespace lccp::view
