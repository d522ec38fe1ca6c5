#pragma once
// One frame of a stream: a depth image from a sensor or recording (back-projected
// by the pipeline), or a point cloud read from a file.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lccp/cloud.hpp"

namespace lccp {

using Clock = std::chrono::steady_clock;

// A depth image as OpenNI2 delivers it: row-major millimetres, 0 = no return.
// The stream's fields of view are the whole camera model (an .oni stores
// nothing else): fx = width / (2 tan(hfov / 2)), cx = width / 2, as OpenNI2's
// CoordinateConverter::convertDepthToWorld computes it.
struct DepthImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  float horizontal_fov_rad = 0;
  float vertical_fov_rad = 0;
  std::vector<std::uint16_t> depth_mm;
};

struct Frame {
  std::uint64_t index = 0;         // position in the source's sequence; a gap means lost frames
  std::uint64_t timestamp_us = 0;  // the source's clock (sensor or recording); 0 if none
  Clock::time_point captured{};    // host time the frame arrived: where latency starts
  std::optional<DepthImage> depth; // set by depth sources; cleared once back-projected
  PointCloud cloud;                // set by cloud sources, or by back-projection
  std::string name;                // source name for outputs (e.g. the PCD file's stem)
  std::string file;                // the file it was read from (cloud files), for messages; else empty
};

}  // namespace lccp
