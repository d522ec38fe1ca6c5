#pragma once
// An animated synthetic table-top scene seen by a Kinect-class depth sensor:
// boxes, cylinders and a mug with a handle moving on a table and occluding
// each other, with Kinect-like depth noise, disparity quantization and missing
// returns, and per-pixel ground-truth labels. Every frame is a pure function of
// (camera, noise seed, frame index), so ground truth can be regenerated for
// any frame of a recording made from it.
#include <cmath>
#include <cstdint>
#include <memory>

#include "lccp/cloud.hpp"
#include "lccp/frame.hpp"

namespace lccp::synthetic {
namespace detail {
class NormalDeviates;
}  // namespace detail

// Ground-truth labels per pixel. Scored as objects with --ignore 0-9.
inline constexpr std::uint32_t kNoReturnLabel = 0;    // no depth measured
inline constexpr std::uint32_t kTableLabel = 1;
inline constexpr std::uint32_t kBackgroundLabel = 2;  // floor and wall
inline constexpr std::uint32_t kFirstObjectLabel = 10;

inline constexpr double kFrameRateHz = 30.0;

// Sensor timestamps of a free-running 30 Hz stream, and back.
inline std::uint64_t timestamp_us_of_frame(std::uint64_t frame_index) {
  return static_cast<std::uint64_t>(std::llround(static_cast<double>(frame_index) * 1e6 / kFrameRateHz));
}
inline std::uint64_t frame_of_timestamp_us(std::uint64_t timestamp_us) {
  return static_cast<std::uint64_t>(std::llround(static_cast<double>(timestamp_us) * kFrameRateHz / 1e6));
}

struct Camera {
  std::uint32_t width = 640;
  std::uint32_t height = 480;
  float horizontal_fov_rad = 2.0f * std::atan(320.0f / 525.0f);  // Kinect v1, fx = 525 px
  float vertical_fov_rad = 2.0f * std::atan(240.0f / 525.0f);
};

struct SyntheticFrame {
  DepthImage depth;  // millimetres, 0 = no return
  Labels labels;     // per pixel, row-major, kNoReturnLabel where depth is 0
};

class TabletopScene {
 public:
  // Throws lccp::Error for a camera without pixels or with a field of view
  // outside (0, pi).
  explicit TabletopScene(Camera camera = {}, std::uint64_t noise_seed = 1);

  // The scene at time frame_index / kFrameRateHz seconds (the motion repeats
  // every 10 s; the noise does not). Single-threaded, about 5 ms at 640x480;
  // safe to call from several threads at once.
  SyntheticFrame render(std::uint64_t frame_index) const;

  const Camera& camera() const { return camera_; }

 private:
  Camera camera_;
  std::uint64_t noise_seed_;
  // The noise model's table (16 KB), computed once, shared by copies.
  std::shared_ptr<const detail::NormalDeviates> normal_deviates_;
};

}  // namespace lccp::synthetic
