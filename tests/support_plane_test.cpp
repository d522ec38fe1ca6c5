// find_support_plane: RANSAC for the support plane (stage 0). Synthetic scenes with a
// known table plane: accuracy of the refit, which points it marks, the up constraint,
// the inlier-share floor, NaN handling, organized clouds, and thread-count independence.
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "lccp/core/lccp.hpp"
#include "lccp/core/support_plane.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

using test::angle_deg;
using test::kNaN;

// What every point of a generated scene is.
enum Part : int { kTablePoint = 0, kBoxTop = 1, kBoxSide = 2, kWallPoint = 3, kNoPoint = 4, kPlatePoint = 5 };

// A scene built in a world frame (z up, table z = 0) and seen by a camera at `eye`
// looking at the table's centre. The table's true plane in the camera frame is
// n . p + d = 0 with n toward the sensor.
struct Scene {
  PointCloud cloud;
  std::vector<int> part;
  test::Pose pose;
  Eigen::Vector3d table_normal;  // camera frame, toward the sensor
  double table_d = 0;
  Eigen::Vector3d wall_normal;   // camera frame, toward the sensor
};

class SceneBuilder {
 public:
  explicit SceneBuilder(const Eigen::Vector3d& eye) : rng_(7) {
    scene_.pose = test::look_at(eye, Eigen::Vector3d::Zero());
    scene_.table_normal = scene_.pose.R * Eigen::Vector3d::UnitZ();
    scene_.table_d = -scene_.table_normal.dot(scene_.pose.t);
  }

  // Points on the rect (world frame) every `step_m`, moved along its normal by uniform
  // noise in [-noise_m, noise_m].
  void add(const test::Rect& r, double step_m, double noise_m, Part part) {
    std::uniform_real_distribution<double> noise(-noise_m, noise_m);
    const int nu = static_cast<int>(r.u.norm() / step_m), nv = static_cast<int>(r.v.norm() / step_m);
    for (int a = 0; a <= nu; ++a) {
      for (int b = 0; b <= nv; ++b) {
        const Eigen::Vector3d p = r.corner + r.u * a / nu + r.v * b / nv + r.normal() * noise(rng_);
        scene_.cloud.points.push_back(scene_.pose.apply(p).cast<float>());
        scene_.part.push_back(part);
      }
    }
  }

  // An axis-aligned box of the given size standing on the table at (x, y): top and four sides.
  void add_box(double x, double y, double side_m, double height_m, double step_m) {
    const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
    const double h = side_m / 2;
    add(test::centered_rect({x, y, height_m}, X, side_m, Y, side_m), step_m, 0.002, kBoxTop);
    add(test::centered_rect({x - h, y, height_m / 2}, Y, side_m, Z, height_m), step_m, 0.002, kBoxSide);
    add(test::centered_rect({x + h, y, height_m / 2}, Y, side_m, Z, height_m), step_m, 0.002, kBoxSide);
    add(test::centered_rect({x, y - h, height_m / 2}, X, side_m, Z, height_m), step_m, 0.002, kBoxSide);
    add(test::centered_rect({x, y + h, height_m / 2}, X, side_m, Z, height_m), step_m, 0.002, kBoxSide);
  }

  Scene done() {
    scene_.cloud.width = static_cast<std::uint32_t>(scene_.cloud.points.size());
    scene_.cloud.height = 1;
    return scene_;
  }

  Scene& scene() { return scene_; }

 private:
  std::mt19937 rng_;
  Scene scene_;
};

const Eigen::Vector3d kEye(0.3, -0.8, 0.7);  // the camera 50 deg above the table, off to one side

// A 1 m x 0.8 m table with a 1 cm noise band (+-5 mm) and three boxes on it.
Scene table_with_boxes() {
  SceneBuilder b(kEye);
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY();
  b.add(test::centered_rect({0, 0, 0}, X, 1.0, Y, 0.8), 0.01, 0.005, kTablePoint);
  b.add_box(-0.2, 0.1, 0.15, 0.12, 0.005);
  b.add_box(0.25, -0.1, 0.10, 0.08, 0.005);
  b.add_box(0.1, 0.25, 0.2, 0.05, 0.005);
  return b.done();
}

// The table above and, behind it, a wall (the plane y = 0.4) with more points than the table.
Scene table_and_wall() {
  SceneBuilder b(kEye);
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  b.add(test::centered_rect({0, 0, 0}, X, 1.0, Y, 0.8), 0.01, 0.003, kTablePoint);
  b.add(test::centered_rect({0, 0.4, 0.75}, X, 1.6, Z, 1.5), 0.01, 0.003, kWallPoint);
  b.add_box(0.0, 0.0, 0.15, 0.12, 0.005);
  b.scene().wall_normal = b.scene().pose.R * -Y;  // the wall faces the camera (at y < 0)
  return b.done();
}

SupportPlaneConfig table_config() {
  SupportPlaneConfig config;
  config.enabled = true;
  config.distance_m = 0.01f;
  return config;
}

std::size_t count_part(const Scene& s, Part part) {
  return static_cast<std::size_t>(std::count(s.part.begin(), s.part.end(), part));
}

// Points of `part` the result marks as on the plane.
std::size_t marked(const SupportPlane& support, const Scene& s, Part part) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.part.size(); ++i) n += s.part[i] == part && support.on_plane[i];
  return n;
}

std::uint64_t on_plane_count(const SupportPlane& support) {
  return static_cast<std::uint64_t>(std::count(support.on_plane.begin(), support.on_plane.end(), 1));
}

TEST(SupportPlane, NoisyTableWithBoxesIsFoundAccurately) {
  const Scene s = table_with_boxes();
  const auto support = find_support_plane(s.cloud, table_config());
  ASSERT_TRUE(support.has_value());
  EXPECT_LT(angle_deg(support->plane.normal, s.table_normal), 0.5);
  EXPECT_NEAR(support->plane.d, s.table_d, 0.002);
  EXPECT_GT(support->plane.d, 0.0f);  // the sensor is above the table
  EXPECT_NEAR(support->plane.normal.norm(), 1.0f, 1e-5f);
  ASSERT_EQ(support->on_plane.size(), s.cloud.size());
  EXPECT_EQ(marked(*support, s, kTablePoint), count_part(s, kTablePoint));
  EXPECT_EQ(marked(*support, s, kBoxTop), 0u);
  EXPECT_EQ(support->inliers, on_plane_count(*support));
}

TEST(SupportPlane, UpDirectionPicksTheTableOverABiggerWall) {
  const Scene s = table_and_wall();
  ASSERT_GT(count_part(s, kWallPoint), 2 * count_part(s, kTablePoint));
  // up: the table's normal turned by 20 deg about the camera's x axis (within 30 deg).
  const Eigen::Vector3d up = Eigen::AngleAxisd(test::deg2rad(20.0), Eigen::Vector3d::UnitX()) * s.table_normal;
  ASSERT_NEAR(angle_deg(up, s.table_normal), 20.0, 1e-6);
  SupportPlaneConfig config = table_config();
  config.up_x = static_cast<float>(up.x()), config.up_y = static_cast<float>(up.y()), config.up_z = static_cast<float>(up.z());
  config.max_tilt_deg = 30.0f;
  const auto support = find_support_plane(s.cloud, config);
  ASSERT_TRUE(support.has_value());
  EXPECT_LT(angle_deg(support->plane.normal, s.table_normal), 0.5);
  EXPECT_NEAR(support->plane.d, s.table_d, 0.002);
  EXPECT_EQ(marked(*support, s, kTablePoint), count_part(s, kTablePoint));
  EXPECT_EQ(marked(*support, s, kBoxTop), 0u);
}

TEST(SupportPlane, WithoutUpTheBiggestPlaneWins) {
  const Scene s = table_and_wall();
  const auto support = find_support_plane(s.cloud, table_config());
  ASSERT_TRUE(support.has_value());
  EXPECT_LT(angle_deg(support->plane.normal, s.wall_normal), 0.5);
  EXPECT_EQ(marked(*support, s, kWallPoint), count_part(s, kWallPoint));
  EXPECT_LT(marked(*support, s, kTablePoint), count_part(s, kTablePoint) / 10);
}

TEST(SupportPlane, SkippedPointsTakeNoPart) {
  const Scene s = table_and_wall();
  std::vector<std::uint8_t> skip(s.cloud.size(), 0);
  for (std::size_t i = 0; i < skip.size(); ++i) skip[i] = s.part[i] == kWallPoint;
  const auto support = find_support_plane(s.cloud, table_config(), skip);
  ASSERT_TRUE(support.has_value());
  EXPECT_LT(angle_deg(support->plane.normal, s.table_normal), 0.5);
  EXPECT_EQ(marked(*support, s, kWallPoint), 0u);
  EXPECT_EQ(marked(*support, s, kTablePoint), count_part(s, kTablePoint));
  // The inlier share counts the points that take part: the table is most of them.
  SupportPlaneConfig config = table_config();
  config.min_inlier_share = 0.6f;
  EXPECT_TRUE(find_support_plane(s.cloud, config, skip).has_value());
}

TEST(SupportPlane, UpTooFarFromEveryPlaneGivesNothing) {
  const Scene s = table_with_boxes();
  // up perpendicular to the table normal: no plane of the scene is within 30 deg of it
  // (box sides facing that way are too small to pass min_inlier_share).
  const Eigen::Vector3d up = s.pose.R * Eigen::Vector3d(1, 1, 0).normalized();
  SupportPlaneConfig config = table_config();
  config.up_x = static_cast<float>(up.x()), config.up_y = static_cast<float>(up.y()), config.up_z = static_cast<float>(up.z());
  const auto support = find_support_plane(s.cloud, config);
  EXPECT_FALSE(support.has_value());
}

TEST(SupportPlane, TooFewInliersGivesNothing) {
  const Scene s = table_with_boxes();
  const auto found = find_support_plane(s.cloud, table_config());
  ASSERT_TRUE(found.has_value());
  const double share = static_cast<double>(found->inliers) / static_cast<double>(s.cloud.size());
  ASSERT_GT(share, 0.4);
  ASSERT_LT(share, 0.6);
  SupportPlaneConfig config = table_config();
  config.min_inlier_share = static_cast<float>(0.95 * share);
  EXPECT_TRUE(find_support_plane(s.cloud, config).has_value());
  config.min_inlier_share = static_cast<float>(1.05 * share);
  EXPECT_FALSE(find_support_plane(s.cloud, config).has_value());
  config.min_inlier_share = 0.9f;
  EXPECT_FALSE(find_support_plane(s.cloud, config).has_value());
}

TEST(SupportPlane, NoFinitePointsGivesNothing) {
  EXPECT_FALSE(find_support_plane(PointCloud{}, table_config()).has_value());
  const PointCloud nans = test::unorganized(std::vector<Eigen::Vector3f>(1000, Eigen::Vector3f(kNaN, kNaN, kNaN)));
  EXPECT_FALSE(find_support_plane(nans, table_config()).has_value());
  const PointCloud two = test::unorganized({Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0.1f, 0, 1)});
  EXPECT_FALSE(find_support_plane(two, table_config()).has_value());
}

TEST(SupportPlane, NaNPointsStayOffThePlane) {
  Scene s = table_with_boxes();
  // Every third point becomes NaN (no data), one more becomes infinite.
  for (std::size_t i = 0; i < s.cloud.size(); i += 3) s.cloud.points[i] = Eigen::Vector3f(kNaN, kNaN, kNaN), s.part[i] = kNoPoint;
  s.cloud.points[1] = Eigen::Vector3f(std::numeric_limits<float>::infinity(), 0, 1), s.part[1] = kNoPoint;
  const auto support = find_support_plane(s.cloud, table_config());
  ASSERT_TRUE(support.has_value());
  ASSERT_EQ(support->on_plane.size(), s.cloud.size());
  EXPECT_EQ(marked(*support, s, kNoPoint), 0u);
  EXPECT_EQ(marked(*support, s, kTablePoint), count_part(s, kTablePoint));
  EXPECT_LT(angle_deg(support->plane.normal, s.table_normal), 0.5);
  EXPECT_EQ(support->inliers, on_plane_count(*support));
}

TEST(SupportPlane, MostlyNaNCloudStillFindsTheTable) {
  // The scene's points at the end of a cloud that is 90% NaN: few scoring samples,
  // but the least-squares round and the marking still see every point.
  const Scene s = table_with_boxes();
  PointCloud cloud;
  cloud.points.assign(9 * s.cloud.size(), Eigen::Vector3f(kNaN, kNaN, kNaN));
  cloud.points.insert(cloud.points.end(), s.cloud.points.begin(), s.cloud.points.end());
  cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  const auto support = find_support_plane(cloud, table_config());
  ASSERT_TRUE(support.has_value());
  EXPECT_LT(angle_deg(support->plane.normal, s.table_normal), 0.5);
  EXPECT_NEAR(support->plane.d, s.table_d, 0.002);
  const std::size_t offset = cloud.size() - s.cloud.size();
  EXPECT_EQ(std::count(support->on_plane.begin(), support->on_plane.begin() + offset, 1), 0);
  std::size_t table_marked = 0;
  for (std::size_t i = 0; i < s.part.size(); ++i) table_marked += s.part[i] == kTablePoint && support->on_plane[offset + i];
  EXPECT_EQ(table_marked, count_part(s, kTablePoint));
}

TEST(SupportPlane, SameResultForOneAndTwoThreads) {
  const Scene s = table_and_wall();
  SupportPlaneConfig config = table_config();
  std::vector<SupportPlane> results;
  for (const int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    for (const std::uint32_t seed : {1u, 2u}) {
      config.seed = seed;
      const auto support = find_support_plane(s.cloud, config);
      ASSERT_TRUE(support.has_value());
      results.push_back(*support);
    }
  }
  for (std::size_t k = 0; k < 2; ++k) {
    const SupportPlane& one = results[k];
    const SupportPlane& two = results[k + 2];
    EXPECT_EQ(one.plane.normal.x(), two.plane.normal.x());  // bit for bit, not approximately
    EXPECT_EQ(one.plane.normal.y(), two.plane.normal.y());
    EXPECT_EQ(one.plane.normal.z(), two.plane.normal.z());
    EXPECT_EQ(one.plane.d, two.plane.d);
    EXPECT_EQ(one.on_plane, two.on_plane);
    EXPECT_EQ(one.inliers, two.inliers);
  }
}

TEST(SupportPlane, OrganizedCloudOfABoxOnATable) {
  const test::BoxOnTable scene = test::box_on_table(0.10, 0.50);
  const test::RenderedScene rendered = test::render(scene.rects);
  ASSERT_TRUE(rendered.cloud.organized());
  ASSERT_GT(rendered.cloud.size(), test::finite_count(rendered.cloud));  // some pixels see nothing
  const auto support = find_support_plane(rendered.cloud, table_config());
  ASSERT_TRUE(support.has_value());
  const test::Rect& table = scene.rects[test::BoxOnTable::kTable];
  const Eigen::Vector3d normal = test::normal_toward_sensor(table);
  EXPECT_LT(angle_deg(support->plane.normal, normal), 0.05);
  EXPECT_NEAR(support->plane.d, -normal.dot(table.corner), 0.0005);
  std::size_t table_points = 0, table_marked = 0, top_marked = 0, nan_marked = 0;
  for (std::size_t i = 0; i < rendered.cloud.size(); ++i) {
    const int rect = rendered.rect_of_point[i];
    table_points += rect == 0;
    table_marked += rect == 0 && support->on_plane[i];
    top_marked += rect == 1 && support->on_plane[i];
    nan_marked += rect < 0 && support->on_plane[i];
  }
  EXPECT_EQ(table_marked, table_points);
  EXPECT_EQ(top_marked, 0u);
  EXPECT_EQ(nan_marked, 0u);
}

TEST(SupportPlane, PlaneThroughTheSensorIsOrientedAlongUp) {
  // The plane y = 0 contains the sensor: d = 0, the normal follows up.
  std::vector<Eigen::Vector3f> points;
  for (int a = 0; a < 40; ++a) {
    for (int b = 0; b < 40; ++b) points.emplace_back(-0.5f + 0.025f * a, 0.0f, 0.5f + 0.025f * b);
  }
  const PointCloud cloud = test::unorganized(points);
  for (const float sign : {1.0f, -1.0f}) {
    SupportPlaneConfig config = table_config();
    config.up_y = sign;
    const auto support = find_support_plane(cloud, config);
    ASSERT_TRUE(support.has_value());
    EXPECT_EQ(support->plane.d, 0.0f);
    EXPECT_NEAR(support->plane.normal.y(), sign, 1e-6f);
    EXPECT_EQ(support->inliers, cloud.size());
  }
}

}  // namespace
}  // namespace lccp

namespace lccp {
namespace {

// A 1 x 0.8 m table (points every `table_step_m`, uniform noise within
// +-table_noise_m) and a 15 x 15 x 12 cm box standing on it.
Scene box_on_table(double table_step_m, double table_noise_m) {
  SceneBuilder b(kEye);
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY();
  b.add(test::centered_rect({0, 0, 0}, X, 1.0, Y, 0.8), table_step_m, table_noise_m, kTablePoint);
  b.add_box(0.0, 0.0, 0.15, 0.12, 0.005);
  return b.done();
}

// With support_noise_sigmas the band follows the plane's own noise: a table
// with +-1 mm of noise keeps 99 % of its points (the band scales as a
// Kinect's noise does, z^2; this noise does not grow with depth, so the
// nearest points' is wider than their band), and a box standing on it
// keeps its foot (only its lowest row of points, within half a depth step of
// the table, goes to the plane); the 1 cm band takes its lowest centimetre.
TEST(SupportPlane, ANoiseScaledBandLeavesObjectsTheirFoot) {
  const Scene s = box_on_table(0.01, 0.001);
  std::size_t lowest_row = 0;  // box side points less than 2 mm above the table
  for (std::size_t i = 0; i < s.part.size(); ++i) {
    const double height = s.table_normal.dot(s.cloud.points[i].cast<double>()) + s.table_d;
    lowest_row += s.part[i] == kBoxSide && height < 0.002;
  }
  ASSERT_GT(lowest_row, 0u);
  const auto fixed = find_support_plane(s.cloud, table_config());
  SupportPlaneConfig scaled = table_config();
  scaled.noise_sigmas = 3.0f;
  const auto band = find_support_plane(s.cloud, scaled);
  ASSERT_TRUE(fixed.has_value() && band.has_value());
  EXPECT_GE(marked(*band, s, kTablePoint), 0.99 * static_cast<double>(count_part(s, kTablePoint)));
  EXPECT_LE(marked(*band, s, kBoxSide), lowest_row);
  EXPECT_GE(marked(*fixed, s, kBoxSide), 3 * lowest_row);  // 1 cm of each side: rows at 0, 5 and 10 mm
  // Uniform noise in +-1 mm: median distance 0.5 mm, robust sigma 1.4826 * 0.5 mm.
  EXPECT_NEAR(band->noise_m, 0.00074f, 0.00015f);
  EXPECT_NEAR(fixed->noise_m, band->noise_m, 1e-6f);  // the same plane, the same noise
}

}  // namespace
}  // namespace lccp

namespace lccp {
namespace {

// Points of `part` from `low` to `high` over the table (metres), and those of
// them the segmentation labels (not the support's, not left out).
std::pair<std::size_t, std::size_t> labelled_between(const Scene& s, const SegmentationWork& w, Part part, double low,
                                                     double high) {
  std::size_t all = 0, labelled = 0;
  for (std::size_t i = 0; i < s.part.size(); ++i) {
    const double height = s.table_normal.dot(s.cloud.points[i].cast<double>()) + s.table_d;
    if (s.part[i] != part || height < low || height >= high) continue;
    all += 1, labelled += w.result.labels[i] != 0;
  }
  return {all, labelled};
}

// support_by_patches: a box's band points are segmented with it, and the
// patches decide which are the support's. A table with +-3 mm of noise has a
// band some 7 mm wide (3 robust sigmas): it takes each side's row of points
// 5 mm above the table. With the patches deciding, most of that row stays the
// box's (its side's plane fits it better than the table's), the box keeps
// its points higher up, and the table stays the support.
TEST(SupportPlane, PatchesDecideWhichBandPointsAreTheSupports) {
  const Scene s = box_on_table(0.005, 0.003);
  LccpConfig config;
  config.support = table_config();
  config.support.noise_sigmas = 3.0f;
  config.support.decided_by_patches = true;
  const SegmentationWork by_patches = LccpSegmenter(config).run(s.cloud);
  config.support.decided_by_patches = false;
  const SegmentationWork by_band = LccpSegmenter(config).run(s.cloud);
  ASSERT_TRUE(by_patches.support && by_band.support);
  const auto [row, row_kept] = labelled_between(s, by_patches, kBoxSide, 0.004, 0.006);
  ASSERT_GT(row, 0u);
  EXPECT_EQ(labelled_between(s, by_band, kBoxSide, 0.004, 0.006).second, 0u);
  EXPECT_GT(2 * row_kept, row);
  const auto [higher, higher_kept] = labelled_between(s, by_patches, kBoxSide, 0.006, 1.0);
  EXPECT_GE(static_cast<double>(higher_kept), 0.99 * static_cast<double>(higher));
  EXPECT_GE(marked(*by_patches.support, s, kTablePoint), 0.99 * static_cast<double>(count_part(s, kTablePoint)));
}


// The band regions near the objects are compared with the open table around
// them (the band points left out): the table around two boxes stays the
// support; a plate 3 mm above the table inside a tray's walls (a raised floor,
// most of its points within the band of +-1 mm noise) is not the support. (The
// robot battery's pan with Kinect noise at 45 deg is the case the rule before
// it failed: a 5-point patch of its floor fell within its own tolerance.)
TEST(SupportPlane, BandRegionsAreTheSupportWhereTheOpenTableAroundThemIs) {
  SceneBuilder b(kEye);
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  // The table, 1 x 0.8 m, but under the tray (within 0.11 m of (0, -0.2)).
  b.add(test::centered_rect({-0.305, 0, 0}, X, 0.39, Y, 0.8), 0.005, 0.001, kTablePoint);
  b.add(test::centered_rect({0.305, 0, 0}, X, 0.39, Y, 0.8), 0.005, 0.001, kTablePoint);
  b.add(test::centered_rect({0, -0.355, 0}, X, 0.22, Y, 0.09), 0.005, 0.001, kTablePoint);
  b.add(test::centered_rect({0, 0.155, 0}, X, 0.22, Y, 0.49), 0.005, 0.001, kTablePoint);
  b.add_box(-0.25, 0.15, 0.12, 0.10, 0.005);
  b.add_box(0.25, 0.15, 0.12, 0.10, 0.005);
  // The tray: a 20 cm plate 3 mm up inside walls 1 cm thick and 4 cm high
  // (their inner and outer faces: a wall of no thickness lets the band region
  // of the plate's edge reach the table's through its foot).
  b.add(test::centered_rect({0, -0.2, 0.003}, X, 0.2, Y, 0.2), 0.005, 0.001, kPlatePoint);
  for (const double face : {-0.11, -0.1, 0.1, 0.11}) {
    const double length = 2 * std::abs(face);
    b.add(test::centered_rect({face, -0.2, 0.02}, Y, length, Z, 0.04), 0.005, 0.001, kWallPoint);
    b.add(test::centered_rect({0, -0.2 + face, 0.02}, X, length, Z, 0.04), 0.005, 0.001, kWallPoint);
  }
  const Scene s = b.done();
  LccpConfig config;
  config.support = table_config();
  config.support.noise_sigmas = 3.0f;
  config.support.decided_by_patches = true;
  const SegmentationWork w = LccpSegmenter(config).run(s.cloud);
  ASSERT_TRUE(w.support.has_value());
  EXPECT_GE(marked(*w.support, s, kTablePoint), 0.99 * static_cast<double>(count_part(s, kTablePoint)));
  EXPECT_LE(marked(*w.support, s, kPlatePoint), 0.05 * static_cast<double>(count_part(s, kPlatePoint)));
}

}  // namespace
}  // namespace lccp
