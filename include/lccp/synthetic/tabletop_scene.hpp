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

// Ground-truth labels per pixel, in the convention of the Object Segmentation
// Database (OSD, Richtsfeld et al. 2012) and mOSD: 0 no data, 1-9 the support
// (table, floor, wall), and object n's parts n * 10 + k. Here object n (1-5)
// has its body k = 0, and the mug's handle its own part k = 1. label / 10 is
// a persistent object id: an object keeps its n in every frame, at every
// camera and seed. Scored as objects with --ignore 0-9 (and eval's
// --object-level, which merges the parts n * 10 + k into one region).
inline constexpr std::uint32_t kNoReturnLabel = 0;    // no depth measured
inline constexpr std::uint32_t kTableLabel = 1;
inline constexpr std::uint32_t kBackgroundLabel = 2;  // floor and wall
inline constexpr std::uint32_t kLastSupportLabel = 9;  // labels 1-9: table and background

// The objects n = 1..kObjectCount: 1 box A (the larger box), 2 box B, 3 the
// can, 4 the bottle, 5 the mug.
inline constexpr std::uint32_t kObjectCount = 5;
inline constexpr std::uint32_t kMugObject = 5;
// Parts k of an object.
inline constexpr std::uint32_t kBodyPart = 0;
inline constexpr std::uint32_t kHandlePart = 1;  // the mug's handle

// The label of part `part` of object `object` (1..kObjectCount): object * 10 + part.
constexpr std::uint32_t object_label(std::uint32_t object, std::uint32_t part = kBodyPart) {
  return object * 10 + part;
}
inline constexpr std::uint32_t kFirstObjectLabel = object_label(1);  // 10: labels below are no object

// The persistent object id of a label (n for n * 10 + k), 0 for the
// no-return and support labels 0-9.
constexpr std::uint32_t object_of_label(std::uint32_t label) { return label / 10; }
// The part k of an object's label n * 10 + k.
constexpr std::uint32_t part_of_label(std::uint32_t label) { return label % 10; }

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
  Labels labels;     // per pixel, row-major, kNoReturnLabel where depth is 0 (the ground truth)
};

class TabletopScene {
 public:
  // Throws lccp::Error for a camera without pixels or with a field of view
  // outside (0, pi).
  explicit TabletopScene(Camera camera = {}, std::uint64_t noise_seed = 1);

  // The scene at time frame_index / kFrameRateHz seconds (the motion repeats
  // every 10 s; the noise does not). Single-threaded, about 2.5 ms at 640x480;
  // safe to call from several threads at once. Its labels are the frame's
  // ground truth: all an evaluation needs of a frame index (per-object
  // centroids and the like follow from the labelled points).
  SyntheticFrame render(std::uint64_t frame_index) const;

  const Camera& camera() const { return camera_; }

 private:
  Camera camera_;
  std::uint64_t noise_seed_;
  // The noise model's table (16 KB) and the static scene's surface image
  // (tabletop_scene.cpp), computed once, shared by copies.
  struct Fixed;
  std::shared_ptr<const Fixed> fixed_;
};

}  // namespace lccp::synthetic
