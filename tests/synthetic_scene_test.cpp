// The synthetic table-top scene: frames are pure functions of (camera, seed,
// frame index); the ground truth matches the depth; table points back-project
// onto the table plane with Kinect-sized noise on the disparity grid; objects
// move and the motion repeats; and LCCP with the paper's P1 segments it.
#include "lccp/synthetic/tabletop_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "lccp/config.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/error.hpp"
#include "lccp/metrics/scores.hpp"
// Internal: the scene's constants and the sensor model, to check against.
#include "../src/synthetic/kinect_model.hpp"
#include "../src/synthetic/scene_layout.hpp"

namespace lccp::synthetic {
namespace {

// Every label an object pixel may carry: one per object, the mug's handle its own.
const std::vector<std::uint32_t> kObjectLabels = {object_label(1), object_label(2), object_label(3), object_label(4),
                                                  object_label(kMugObject, kBodyPart),
                                                  object_label(kMugObject, kHandlePart)};
constexpr std::uint32_t kHandleLabel = object_label(kMugObject, kHandlePart);

bool is_object_label(std::uint32_t label) {
  return std::find(kObjectLabels.begin(), kObjectLabels.end(), label) != kObjectLabels.end();
}

std::map<std::uint32_t, std::size_t> label_counts(const Labels& labels) {
  std::map<std::uint32_t, std::size_t> counts;
  for (const std::uint32_t label : labels) ++counts[label];
  return counts;
}

// Pixels per object id (label / 10, the parts together), objects only.
std::map<std::uint32_t, std::size_t> object_counts(const Labels& labels) {
  std::map<std::uint32_t, std::size_t> counts;
  for (const std::uint32_t label : labels) {
    if (label >= kFirstObjectLabel) ++counts[object_of_label(label)];
  }
  return counts;
}

// Pixels whose labels differ although both have a return.
std::size_t label_conflicts(const SyntheticFrame& a, const SyntheticFrame& b) {
  std::size_t conflicts = 0;
  for (std::size_t i = 0; i < a.labels.size(); ++i) {
    conflicts += a.depth.depth_mm[i] != 0 && b.depth.depth_mm[i] != 0 && a.labels[i] != b.labels[i];
  }
  return conflicts;
}

std::size_t label_differences(const SyntheticFrame& a, const SyntheticFrame& b) {
  std::size_t differences = 0;
  for (std::size_t i = 0; i < a.labels.size(); ++i) differences += a.labels[i] != b.labels[i];
  return differences;
}

// Mean pixel position of each object (by object id, label / 10).
std::map<std::uint32_t, Eigen::Vector2d> object_centroids(const SyntheticFrame& frame) {
  std::map<std::uint32_t, Eigen::Vector2d> sums;
  std::map<std::uint32_t, double> counts;
  for (std::size_t i = 0; i < frame.labels.size(); ++i) {
    if (frame.labels[i] < kFirstObjectLabel) continue;
    const std::uint32_t label = object_of_label(frame.labels[i]);
    const double row = static_cast<double>(i / frame.depth.width);
    const double col = static_cast<double>(i % frame.depth.width);
    sums.try_emplace(label, Eigen::Vector2d::Zero()).first->second += Eigen::Vector2d(col, row);
    counts[label] += 1;
  }
  for (auto& [label, sum] : sums) sum /= counts[label];
  return sums;
}

TEST(SyntheticScene, RenderIsAPureFunctionOfTheFrameIndex) {
  const TabletopScene scene;
  const TabletopScene other;
  for (const std::uint64_t index : {0ull, 37ull, 123456ull}) {
    const SyntheticFrame first = scene.render(index);
    const SyntheticFrame again = scene.render(index);
    const SyntheticFrame elsewhere = other.render(index);
    EXPECT_EQ(first.depth.depth_mm, again.depth.depth_mm) << index;
    EXPECT_EQ(first.labels, again.labels) << index;
    EXPECT_EQ(first.depth.depth_mm, elsewhere.depth.depth_mm) << index;
    EXPECT_EQ(first.labels, elsewhere.labels) << index;
  }
  // A copy shares the precomputed state and renders the same.
  const TabletopScene copy = scene;
  EXPECT_EQ(copy.render(5).depth.depth_mm, scene.render(5).depth.depth_mm);
}

TEST(SyntheticScene, ConsecutiveFramesDiffer) {
  const TabletopScene scene;
  const SyntheticFrame a = scene.render(10);
  const SyntheticFrame b = scene.render(11);
  EXPECT_NE(a.depth.depth_mm, b.depth.depth_mm);
  // 1/30 s of motion moves some object boundaries.
  EXPECT_GT(label_conflicts(a, b), 20u);
}

TEST(SyntheticScene, NoiseSeedChangesDepthButHardlyLabels) {
  const SyntheticFrame a = TabletopScene(Camera{}, 1).render(0);
  const SyntheticFrame b = TabletopScene(Camera{}, 2).render(0);
  std::size_t both = 0, different = 0;
  for (std::size_t i = 0; i < a.labels.size(); ++i) {
    if (a.depth.depth_mm[i] == 0 || b.depth.depth_mm[i] == 0) continue;
    ++both;
    different += a.depth.depth_mm[i] != b.depth.depth_mm[i];
  }
  // Noise of 0.6-0.9 disparity steps: most pixels land on another step.
  EXPECT_GT(different, both / 3);
  // Same geometry: labels differ only where one seed dropped the return (about 1 %).
  EXPECT_EQ(label_conflicts(a, b), 0u);
  EXPECT_LT(label_differences(a, b), a.labels.size() / 50);
  EXPECT_GT(label_differences(a, b), 0u);
}

TEST(SyntheticScene, ImageMatchesTheCamera) {
  for (const Camera& camera : {Camera{}, Camera{320, 240}}) {
    const TabletopScene scene(camera);
    EXPECT_EQ(scene.camera().width, camera.width);
    const SyntheticFrame frame = scene.render(0);
    const std::size_t pixels = std::size_t{camera.width} * camera.height;
    EXPECT_EQ(frame.depth.width, camera.width);
    EXPECT_EQ(frame.depth.height, camera.height);
    EXPECT_EQ(frame.depth.horizontal_fov_rad, camera.horizontal_fov_rad);
    EXPECT_EQ(frame.depth.vertical_fov_rad, camera.vertical_fov_rad);
    ASSERT_EQ(frame.depth.depth_mm.size(), pixels);
    ASSERT_EQ(frame.labels.size(), pixels);
    // The same scene at any resolution: every object in view, in proportion.
    const auto counts = object_counts(frame.labels);
    for (std::uint32_t object = 1; object <= kObjectCount; ++object) {
      EXPECT_GT(counts.count(object) ? counts.at(object) : 0, pixels / 400) << camera.width << " object " << object;
    }
  }
}

TEST(SyntheticScene, RejectsACameraWithoutPixelsOrFieldOfView) {
  Camera empty;
  empty.width = 0;
  EXPECT_THROW(TabletopScene{empty}, Error);
  Camera flat;
  flat.vertical_fov_rad = 0;
  EXPECT_THROW(TabletopScene{flat}, Error);
  Camera half_sphere;
  half_sphere.horizontal_fov_rad = 3.2f;
  EXPECT_THROW(TabletopScene{half_sphere}, Error);
}

TEST(SyntheticScene, LabelIsZeroExactlyWhereDepthIsZero) {
  const TabletopScene scene;
  for (const std::uint64_t index : {0ull, 45ull, 150ull, 299ull}) {
    const SyntheticFrame frame = scene.render(index);
    std::size_t missing = 0;
    for (std::size_t i = 0; i < frame.labels.size(); ++i) {
      ASSERT_EQ(frame.depth.depth_mm[i] == 0, frame.labels[i] == kNoReturnLabel) << "frame " << index << " pixel " << i;
      missing += frame.depth.depth_mm[i] == 0;
    }
    // Dropout (0.5 %), projector shadows and grazing surfaces: a few per cent.
    EXPECT_GT(missing, frame.labels.size() / 200) << index;
    EXPECT_LT(missing, frame.labels.size() / 20) << index;
  }
}

TEST(SyntheticScene, FirstFrameShowsTheTableAndEveryObject) {
  const SyntheticFrame frame = TabletopScene().render(0);
  const std::size_t pixels = frame.labels.size();
  const auto counts = label_counts(frame.labels);
  for (const auto& [label, count] : counts) {
    const bool known = label == kNoReturnLabel || label == kTableLabel || label == kBackgroundLabel ||
                       is_object_label(label);
    EXPECT_TRUE(known) << label;
  }
  EXPECT_GT(counts.at(kTableLabel), pixels * 2 / 5);
  EXPECT_GT(counts.at(kBackgroundLabel), pixels / 10);
  // Objects of 6-20 cm at about 1.1 m: 0.3 % to 5 % of the image each.
  const auto objects = object_counts(frame.labels);
  EXPECT_EQ(objects.size(), std::size_t{kObjectCount});
  for (std::uint32_t object = 1; object <= kObjectCount; ++object) {
    ASSERT_TRUE(objects.count(object)) << object;
    EXPECT_TRUE(counts.count(object_label(object))) << "object " << object << " has no body";
    EXPECT_GT(objects.at(object), pixels * 3 / 1000) << object;
    EXPECT_LT(objects.at(object), pixels / 20) << object;
  }
}

// Table points of frame 0 with the depth the table plane gives their pixel's ray.
struct TablePoint {
  double measured_m = 0;
  double true_m = 0;
};

std::vector<TablePoint> table_points(const SyntheticFrame& frame) {
  const PointCloud cloud = back_project(frame.depth);
  const detail::Plane plane = detail::table_plane_in_camera();
  std::vector<TablePoint> points;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (frame.labels[i] != kTableLabel) continue;
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    // p = z * ray with ray = (x/z, y/z, 1); the plane meets that ray at -offset / (n . ray).
    const Eigen::Vector3d ray = p / p.z();
    points.push_back({p.z(), -plane.offset / plane.normal.dot(ray)});
  }
  return points;
}

TEST(SyntheticScene, TablePointsLieOnTheTablePlane) {
  const std::vector<TablePoint> points = table_points(TabletopScene().render(0));
  ASSERT_GT(points.size(), 100000u);
  std::size_t within_3_sigma = 0;
  for (const TablePoint& p : points) {
    const double error = std::abs(p.measured_m - p.true_m);
    // Quantization moves a depth by at most half a disparity step, mm rounding by 0.5 mm.
    const double rounding = 0.55 * detail::quantization_step_m(p.true_m) + 0.0005;
    // The normal deviates are bounded (8.3 sigma): a hard bound.
    ASSERT_LT(error, 8.3 * detail::axial_noise_sigma_m(p.true_m) + rounding) << p.true_m;
    within_3_sigma += error < 3 * detail::axial_noise_sigma_m(p.true_m) + rounding;
  }
  EXPECT_GT(within_3_sigma, points.size() * 99 / 100);
}

TEST(SyntheticScene, NoiseAtOneMetreIsKinectLike) {
  // Axial error of table points 0.95-1.05 m away: Gaussian sigma 1.7-2.0 mm
  // (Nguyen et al.) on top of disparity steps of 2.9 mm (uniform error, 0.8 mm
  // std) and mm rounding: about 2.1 mm in all.
  const std::vector<TablePoint> points = table_points(TabletopScene().render(0));
  double sum = 0, squares = 0, expected_variance = 0;
  std::size_t n = 0, beyond_1m = 0, on_grid = 0;
  for (const TablePoint& p : points) {
    if (p.true_m < 0.95 || p.true_m > 1.05) continue;
    const double error = p.measured_m - p.true_m;
    sum += error;
    squares += error * error;
    const double step = detail::quantization_step_m(p.true_m);
    expected_variance += std::pow(detail::axial_noise_sigma_m(p.true_m), 2) + step * step / 12 + 1e-6 / 12;
    ++n;
    // Measured depths sit on the disparity grid: beyond 1 m, f b / z is within
    // mm rounding (0.18 steps) of a whole 1/8 px.
    if (p.measured_m >= 1.0) {
      ++beyond_1m;
      const double steps = detail::kDisparityStepsTimesDepth / p.measured_m;
      on_grid += std::abs(steps - std::round(steps)) < 0.18;
    }
  }
  ASSERT_GT(n, 10000u);
  const double mean = sum / n;
  const double std_dev = std::sqrt(squares / n - mean * mean);
  const double expected_std = std::sqrt(expected_variance / n);
  EXPECT_LT(std::abs(mean), 0.0003);
  EXPECT_GT(std_dev, 0.0015);
  EXPECT_LT(std_dev, 0.0027);
  EXPECT_NEAR(std_dev, expected_std, 0.1 * expected_std);
  EXPECT_GT(beyond_1m, n / 4);
  EXPECT_EQ(on_grid, beyond_1m);
}

TEST(SyntheticScene, BottlePointsLieOnItsCylinder) {
  // The bottle (object 3) in the world frame: points on its side at its radius
  // from the axis, or on its top at its height.
  const SyntheticFrame frame = TabletopScene().render(0);
  const PointCloud cloud = back_project(frame.depth);
  const detail::CameraPose pose = detail::camera_pose();
  const detail::Part bottle = detail::object_parts_at(0.0)[3];
  ASSERT_EQ(bottle.shape, detail::Shape::cylinder);
  const double radius = bottle.size.x();
  const double height = bottle.size.z();
  std::vector<double> residuals;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (frame.labels[i] != bottle.label) continue;
    const Eigen::Vector3d world = pose.axes * cloud.points[i].cast<double>() + pose.position - bottle.position;
    const double side = std::abs(world.head<2>().norm() - radius);
    const double top = std::abs(world.z() - height) + std::max(0.0, world.head<2>().norm() - radius);
    residuals.push_back(std::min(side, top));
  }
  ASSERT_GT(residuals.size(), 1000u);
  std::sort(residuals.begin(), residuals.end());
  EXPECT_LT(residuals[residuals.size() / 2], 0.002);
  EXPECT_LT(residuals[residuals.size() * 99 / 100], 0.006);
}

TEST(SyntheticScene, ObjectsMoveOverTwoSeconds) {
  const TabletopScene scene;
  const SyntheticFrame a = scene.render(0);
  const SyntheticFrame b = scene.render(60);
  std::size_t object_pixels_changed = 0;
  for (std::size_t i = 0; i < a.labels.size(); ++i) {
    const bool object_a = a.labels[i] >= kFirstObjectLabel, object_b = b.labels[i] >= kFirstObjectLabel;
    object_pixels_changed += (object_a || object_b) && a.labels[i] != b.labels[i] && a.labels[i] && b.labels[i];
  }
  EXPECT_GT(object_pixels_changed, 2000u);
  // The bottle swings across, the can slides; the boxes and the mug turn.
  const auto before = object_centroids(a), after = object_centroids(b);
  std::size_t moved = 0;
  for (const auto& [label, centroid] : before) moved += (after.at(label) - centroid).norm() > 2.0;
  EXPECT_GE(moved, 2u);
  EXPECT_GT((after.at(4) - before.at(4)).norm(), 40.0);  // the bottle, object 4
}

TEST(SyntheticScene, MotionRepeatsEveryTenSeconds) {
  const TabletopScene scene;
  static_assert(detail::kPeriodFrames == 300);
  for (const std::uint64_t index : {0ull, 77ull, 299ull}) {
    const SyntheticFrame a = scene.render(index);
    const SyntheticFrame b = scene.render(index + detail::kPeriodFrames);
    // Same geometry; the noise (and so the dropout) is drawn anew.
    EXPECT_EQ(label_conflicts(a, b), 0u) << index;
    EXPECT_LT(label_differences(a, b), a.labels.size() / 50) << index;
    EXPECT_NE(a.depth.depth_mm, b.depth.depth_mm) << index;
  }
}

TEST(SyntheticScene, TimestampsRoundTrip) {
  std::uint64_t previous = 0;
  for (std::uint64_t frame = 0; frame <= 100000; ++frame) {
    const std::uint64_t timestamp = timestamp_us_of_frame(frame);
    ASSERT_EQ(frame_of_timestamp_us(timestamp), frame);
    if (frame > 0) {
      ASSERT_GE(timestamp - previous, 33333u) << frame;
      ASSERT_LE(timestamp - previous, 33334u) << frame;
    }
    previous = timestamp;
  }
  EXPECT_EQ(timestamp_us_of_frame(30), 1000000u);
}

TEST(SyntheticNoise, NormalDeviatesAreStandardNormal) {
  const detail::NormalDeviates normal;
  // Quantiles against the error function.
  for (const double p : {1e-9, 1e-4, 0.01, 0.2, 0.5, 0.8, 0.99, 1 - 1e-6}) {
    const double x = detail::standard_normal_quantile(p);
    EXPECT_NEAR(0.5 * std::erfc(-x / std::sqrt(2.0)), p, 1e-7 * std::min(p, 1 - p)) << p;
  }
  // Moments and tail mass of a million pixels' deviates.
  const std::uint64_t key = detail::frame_key(1, 0);
  constexpr std::size_t kDraws = 1000000;
  double sum = 0, squares = 0;
  std::size_t beyond_2 = 0, beyond_3 = 0, dropouts = 0;
  for (std::size_t pixel = 0; pixel < kDraws; ++pixel) {
    const detail::PixelNoise noise = detail::pixel_noise(key, pixel, normal);
    sum += noise.gaussian;
    squares += noise.gaussian * noise.gaussian;
    beyond_2 += std::abs(noise.gaussian) > 2;
    beyond_3 += std::abs(noise.gaussian) > 3;
    dropouts += noise.dropout;
  }
  EXPECT_NEAR(sum / kDraws, 0.0, 0.005);
  EXPECT_NEAR(squares / kDraws, 1.0, 0.005);
  EXPECT_NEAR(static_cast<double>(beyond_2) / kDraws, 0.0455, 0.001);
  EXPECT_NEAR(static_cast<double>(beyond_3) / kDraws, 0.0027, 0.0002);
  EXPECT_NEAR(static_cast<double>(dropouts) / kDraws, detail::kDropoutProbability, 0.0005);
}

TEST(SyntheticNoise, KinectModelValues) {
  // Nguyen et al.: 1.2 mm at 0.4 m, 1.88 mm at 1 m, 5.3 mm at 1.87 m.
  EXPECT_DOUBLE_EQ(detail::axial_noise_sigma_m(0.4), 0.0012);
  EXPECT_NEAR(detail::axial_noise_sigma_m(1.0), 0.001884, 1e-6);
  // 1/8 px of disparity at f = 580 px, b = 7.5 cm: 2.87 mm at 1 m, 11.5 mm at 2 m.
  EXPECT_NEAR(detail::quantization_step_m(1.0), 0.002874, 1e-6);
  EXPECT_NEAR(detail::quantization_step_m(2.0), 0.011494, 1e-6);
  EXPECT_NEAR(detail::quantize_depth_m(1.0), 1.0, 0.5 * detail::quantization_step_m(1.0));
  const double q = detail::quantize_depth_m(1.2345);
  EXPECT_DOUBLE_EQ(detail::quantize_depth_m(q), q);  // idempotent
}

// A world point in the local frame of `part` (yawed about z, then moved).
Eigen::Vector3d in_part_frame(const detail::Part& part, const Eigen::Vector3d& world) {
  const double c = std::cos(part.yaw_rad), s = std::sin(part.yaw_rad);
  const Eigen::Vector3d d = world - part.position;
  return Eigen::Vector3d(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
}

// The world points of a frame's pixels (NaN where there is no return).
std::vector<Eigen::Vector3d> world_points(const SyntheticFrame& frame) {
  const PointCloud cloud = back_project(frame.depth);
  const detail::CameraPose pose = detail::camera_pose();
  std::vector<Eigen::Vector3d> points(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) points[i] = pose.axes * cloud.points[i].cast<double>() + pose.position;
  return points;
}

// Distance of a point in the cup's frame from the handle's centre line.
double from_handle_centre_line(const Eigen::Vector3d& p) {
  const auto line = detail::handle_centre_line();
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Eigen::Vector3d ab = line[k + 1] - line[k];
    const double t = std::clamp((p - line[k]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (line[k] + t * ab - p).norm());
  }
  return nearest;
}

double percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1))];
}

// The handle is a part of its own (mOSD: object n's parts n * 10 + k): its
// pixels lie on the handle's tube, the body's stay within the cup's radius.
// The mug turns once per period, so the handle is seen side-on in some frames.
TEST(SyntheticScene, TheMugsHandleCarriesItsOwnPartLabel) {
  const TabletopScene scene;
  std::size_t frames_showing_the_handle = 0;
  for (std::uint64_t index = 0; index < detail::kPeriodFrames; index += 15) {
    const SyntheticFrame frame = scene.render(index);
    const std::vector<Eigen::Vector3d> world = world_points(frame);
    const detail::Part cup = detail::object_parts_at(static_cast<double>(index) / kFrameRateHz)[4];
    std::vector<double> handle_off_tube, body_from_axis;
    for (std::size_t i = 0; i < frame.labels.size(); ++i) {
      if (object_of_label(frame.labels[i]) != kMugObject) continue;
      const Eigen::Vector3d local = in_part_frame(cup, world[i]);
      if (frame.labels[i] == kHandleLabel) {
        handle_off_tube.push_back(std::abs(from_handle_centre_line(local) - detail::kHandleTubeRadiusM));
      } else {
        ASSERT_EQ(frame.labels[i], object_label(kMugObject, kBodyPart)) << index;
        body_from_axis.push_back(local.head<2>().norm());
      }
    }
    ASSERT_GT(body_from_axis.size(), 1000u) << index;
    EXPECT_LT(percentile(body_from_axis, 0.99), detail::kMugOuterRadiusM + 0.006) << index;
    if (handle_off_tube.size() < 200) continue;
    ++frames_showing_the_handle;
    EXPECT_LT(percentile(handle_off_tube, 0.5), 0.002) << index;
    EXPECT_LT(percentile(handle_off_tube, 0.95), 0.006) << index;
  }
  EXPECT_GE(frames_showing_the_handle, 3u);
}

// label / 10 names the same physical object in every frame: object n's pixels
// lie on the n-th solid of the scene's motion (box A, box B, the can, the
// bottle, the mug), wherever it has moved, throughout the period.
TEST(SyntheticScene, LabelOverTenIsTheSameObjectInEveryFrame) {
  const TabletopScene scene;
  for (std::uint64_t index = 0; index < detail::kPeriodFrames; index += 20) {
    const SyntheticFrame frame = scene.render(index);
    const std::vector<Eigen::Vector3d> world = world_points(frame);
    const auto parts = detail::object_parts_at(static_cast<double>(index) / kFrameRateHz);
    std::map<std::uint32_t, std::size_t> on_their_object, pixels;
    for (std::size_t i = 0; i < frame.labels.size(); ++i) {
      const std::uint32_t label = frame.labels[i];
      if (label < kFirstObjectLabel) continue;
      ASSERT_TRUE(is_object_label(label)) << label;
      const std::uint32_t object = object_of_label(label);
      const detail::Part& solid = parts[label == kHandleLabel ? 5 : object - 1];
      const Eigen::Vector3d local = in_part_frame(solid, world[i]);
      const Eigen::Vector3d margin = Eigen::Vector3d::Constant(0.01);
      on_their_object[object] += (local.array() >= (solid.local_min - margin).array()).all() &&
                                 (local.array() <= (solid.local_max + margin).array()).all();
      ++pixels[object];
    }
    EXPECT_EQ(pixels.size(), std::size_t{kObjectCount}) << index;
    for (const auto& [object, count] : pixels) {
      EXPECT_GE(on_their_object[object], count * 99 / 100) << "frame " << index << " object " << object;
    }
  }
}

// LCCP with the paper's P1 defaults separates the objects, scored as objects
// (the mug's handle merged into it; measured WOv: frame 0 0.927, frame 150,
// the can touching box A, 0.922).
TEST(SyntheticScene, SegmentableWithP1Defaults) {
  const TabletopScene scene;
  const LccpSegmenter segmenter{LccpConfig{}};
  for (const std::uint64_t index : {0ull, 150ull}) {
    const SyntheticFrame frame = scene.render(index);
    const PointCloud cloud = back_project(frame.depth);
    const SegmentationResult result = segmenter.segment(cloud);
    const LabelRange ignored{kNoReturnLabel, kFirstObjectLabel - 1};  // 0-9: no return, table, background
    const SegmentationScores scores = score_objects(result.labels, frame.labels, cloud.points, ignored);
    EXPECT_EQ(scores.ground_truth_regions, kObjectCount) << index;
    EXPECT_EQ(scores.objects_lost, 0u) << index;
    EXPECT_GT(scores.weighted_overlap, 0.90) << index;
    EXPECT_LT(scores.under_segmentation, 0.05) << index;
  }
}

}  // namespace
}  // namespace lccp::synthetic
