// Per-segment geometry (describe_segments) on scenes of known geometry: boxes on a
// plane (box_scene.hpp) segmented with the paper's P1 parameters, and point sets
// built by hand.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "box_scene.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/objects/geometry.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

// A segmentation that owns its cloud (the work points into it).
struct Segmented {
  std::unique_ptr<PointCloud> cloud;
  SegmentationWork work;
};

Segmented segment_p1(PointCloud cloud) {
  auto owned = std::make_unique<PointCloud>(std::move(cloud));
  SegmentationWork work = LccpSegmenter(LccpConfig{}).run(*owned);  // defaults: P1
  return {std::move(owned), std::move(work)};
}

// The scene's points of the given truth labels, as an unorganized cloud (truth kept alongside).
PointCloud points_of(const test::BoxScene& scene, int min_truth, std::vector<int>& truth) {
  std::vector<Eigen::Vector3f> points;
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    if (scene.truth[i] >= min_truth) points.push_back(scene.cloud.points[i]), truth.push_back(scene.truth[i]);
  }
  return test::unorganized(std::move(points));
}

// The segment (label) holding the most points of truth `t`.
std::uint32_t best_segment(const Labels& labels, const std::vector<int>& truth, int t, std::uint32_t K) {
  std::vector<std::size_t> votes(K + 1, 0);
  for (std::size_t i = 0; i < labels.size(); ++i) votes[labels[i]] += truth[i] == t;
  return static_cast<std::uint32_t>(std::max_element(votes.begin() + 1, votes.end()) - votes.begin());
}

Eigen::Vector3d mean_of(const PointCloud& cloud, const std::vector<int>& truth, int t) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double n = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] == t) sum += cloud.points[i].cast<double>(), n += 1;
  }
  return sum / n;
}

// Angle between two lines (directions up to sign), degrees.
double line_angle_deg(const Eigen::Vector3f& a, const Eigen::Vector3d& b) {
  return std::min(test::angle_deg(a, b), test::angle_deg(a, Eigen::Vector3d(-b)));
}

bool has_neighbour(const SegmentGeometry& g, std::uint32_t id, Boundary boundary) {
  return std::find(g.adjacent.begin(), g.adjacent.end(), Neighbour{id, boundary}) != g.adjacent.end();
}

// Compares the box found with the true one: the first OBB axis along the longer
// footprint side, the third along the box's vertical; full extents.
void expect_box_matches(const OrientedBox& obb, const test::BoxTruth& box, double extent_m, double angle_deg) {
  const int longer = box.extents.x() >= box.extents.y() ? 0 : 1;
  const Eigen::Vector3d expected(box.extents[longer], box.extents[1 - longer], box.extents.z());
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(obb.extents[a], expected[a], extent_m) << "extent " << a;
  EXPECT_LT(line_angle_deg(obb.axes.col(0), box.axes.col(longer)), angle_deg);
  EXPECT_LT(line_angle_deg(obb.axes.col(1), box.axes.col(1 - longer)), angle_deg);
  EXPECT_LT(line_angle_deg(obb.axes.col(2), box.axes.col(2)), angle_deg);
  EXPECT_NEAR(obb.axes.determinant(), 1.0f, 1e-4f);
}

// The true partition (scene truth as labels on LCCP's work): every figure is
// the box's, up to the sampling (edges are sampled, so full extents are exact).
TEST(SegmentGeometry, TrueBoxSegmentsGiveTheBoxPoses) {
  const test::BoxScene scene = test::two_touching_boxes();
  std::vector<int> truth;
  Segmented s = segment_p1(points_of(scene, 1, truth));  // the plane's points removed
  s.work.result.labels.assign(truth.begin(), truth.end());
  s.work.result.segment_count = 2;
  const std::vector<SegmentGeometry> geometry = describe_segments(s.work, scene.plane);
  ASSERT_EQ(geometry.size(), 2u);
  for (int b = 1; b <= 2; ++b) {
    SCOPED_TRACE("box " + std::to_string(b));
    const SegmentGeometry& g = geometry[b - 1];
    EXPECT_EQ(g.id, static_cast<std::uint32_t>(b));
    EXPECT_EQ(g.points, static_cast<std::uint64_t>(std::count(truth.begin(), truth.end(), b)));
    EXPECT_LT((g.centroid.cast<double>() - mean_of(*s.cloud, truth, b)).norm(), 1e-4);
    expect_box_matches(g.obb, scene.boxes[b - 1], 0.001, 0.5);
    EXPECT_LT(test::angle_deg(g.mean_normal, Eigen::Vector3d(-g.centroid.cast<double>())), 90.0);  // faces the sensor
  }
}

// Spread of the segment's points along the true box axes, ordered as
// expect_box_matches orders the box's extents (longer footprint side first).
Eigen::Vector3d spread_along(const Segmented& s, std::uint32_t id, const test::BoxTruth& box) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (std::size_t i = 0; i < s.cloud->size(); ++i) {
    if (s.work.result.labels[i] != id) continue;
    const Eigen::Vector3d q = box.axes.transpose() * s.cloud->points[i].cast<double>();
    lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  }
  const Eigen::Vector3d spread = hi - lo;
  const int longer = box.extents.x() >= box.extents.y() ? 0 : 1;
  return {spread[longer], spread[1 - longer], spread.z()};
}

// LCCP with P1 on the two boxes (plane removed): two segments, adjacent along a
// concave boundary, each with its box's axes; its OBB spans its own points. The
// segments are the boxes only up to LCCP's boundary: at the concave crease it is
// jagged by up to a supervoxel (measured: points of B's top up to 18 mm from A's
// face join A's segment, 5 % of B's points), so the OBB extents and centroids
// are compared with the truth more loosely than in TrueBoxSegmentsGiveTheBoxPoses.
TEST(SegmentGeometry, TwoTouchingBoxesLccpP1SegmentsAndConcaveBoundary) {
  const test::BoxScene scene = test::two_touching_boxes();
  std::vector<int> truth;
  const Segmented s = segment_p1(points_of(scene, 1, truth));  // the plane's points removed
  ASSERT_EQ(s.work.result.segment_count, 2u);
  const std::vector<SegmentGeometry> geometry = describe_segments(s.work, scene.plane);
  ASSERT_EQ(geometry.size(), 2u);
  std::vector<std::uint32_t> id_of_box;
  for (int b = 1; b <= 2; ++b) {
    SCOPED_TRACE("box " + std::to_string(b));
    const std::uint32_t id = best_segment(s.work.result.labels, truth, b, 2);
    id_of_box.push_back(id);
    const SegmentGeometry& g = geometry[id - 1];
    EXPECT_EQ(g.id, id);
    EXPECT_LT((g.centroid.cast<double>() - mean_of(*s.cloud, truth, b)).norm(), 0.006);
    expect_box_matches(g.obb, scene.boxes[b - 1], 0.020, 2.0);
    const Eigen::Vector3d own = spread_along(s, id, scene.boxes[b - 1]);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(g.obb.extents[a], own[a], 0.002) << "extent " << a;
    EXPECT_NEAR(g.principal_axes.determinant(), 1.0f, 1e-4f);
  }
  ASSERT_NE(id_of_box[0], id_of_box[1]);
  EXPECT_TRUE(has_neighbour(geometry[id_of_box[0] - 1], id_of_box[1], Boundary::concave));
  EXPECT_TRUE(has_neighbour(geometry[id_of_box[1] - 1], id_of_box[0], Boundary::concave));
}

// Paper Sec. III.C: an upright handle is grasped from the side, a lying one from the top.
TEST(SegmentGeometry, GraspHintUprightBoxSideLyingBoxTop) {
  const std::vector<test::BoxSpec> specs = {{-0.12, 0, 10, {0.04, 0.04, 0.20}}, {0.10, 0.02, 25, {0.20, 0.04, 0.04}}};
  for (const double elevation : {45.0, 15.0}) {
    test::SensorSpec sensor;
    sensor.elevation_deg = elevation;
    const test::BoxScene scene = test::box_scene(specs, sensor);
    std::vector<int> truth;
    const Segmented s = segment_p1(points_of(scene, 1, truth));
    ASSERT_EQ(s.work.result.segment_count, 2u);
    const std::uint32_t upright = best_segment(s.work.result.labels, truth, 1, 2);
    const std::uint32_t lying = best_segment(s.work.result.labels, truth, 2, 2);
    // With the plane; and (seen from 15 deg) without it, "up" being the sensor's -y.
    for (const std::optional<Plane>& plane : {std::optional<Plane>(scene.plane), std::optional<Plane>()}) {
      if (!plane && elevation > 30) continue;  // -y is 45 deg off the vertical: no clear up
      const std::vector<SegmentGeometry> geometry = describe_segments(s.work, plane);
      EXPECT_EQ(geometry[upright - 1].grasp, Grasp::side) << "elevation " << elevation;
      EXPECT_EQ(geometry[lying - 1].grasp, Grasp::top) << "elevation " << elevation;
      EXPECT_LT(line_angle_deg(geometry[lying - 1].principal_axes.col(0), scene.boxes[1].axes.col(0)), 2.0);
    }
  }
}

void expect_same(const SegmentGeometry& a, const SegmentGeometry& b) {
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.centroid, b.centroid);
  EXPECT_EQ(a.obb.center, b.obb.center);
  EXPECT_EQ(a.obb.axes, b.obb.axes);
  EXPECT_EQ(a.obb.extents, b.obb.extents);
  EXPECT_EQ(a.principal_axes, b.principal_axes);
  EXPECT_EQ(a.principal_extents, b.principal_extents);
  EXPECT_EQ(a.mean_normal, b.mean_normal);
  EXPECT_EQ(a.grasp, b.grasp);
  EXPECT_EQ(a.adjacent, b.adjacent);
}

std::vector<SegmentGeometry> with_threads(int n, const SegmentationWork& work, const std::optional<Plane>& plane) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(n));
  tbb::task_arena arena(n);
  return arena.execute([&] { return describe_segments(work, plane); });
}

// The whole scene, plane included (~80k points: several blocks of the per-segment sums).
TEST(SegmentGeometry, SameResultsWithOneAndTwoThreads) {
  const test::BoxScene scene = test::two_touching_boxes();
  std::vector<int> truth;
  const Segmented s = segment_p1(points_of(scene, 0, truth));
  ASSERT_GE(s.work.result.segment_count, 3u);
  for (const std::optional<Plane>& plane : {std::optional<Plane>(scene.plane), std::optional<Plane>()}) {
    const std::vector<SegmentGeometry> one = with_threads(1, s.work, plane);
    const std::vector<SegmentGeometry> two = with_threads(2, s.work, plane);
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t k = 0; k < one.size(); ++k) expect_same(one[k], two[k]);
  }
}

// The plane's segment: its mean normal is the plane's, it touches both boxes along concave edges.
TEST(SegmentGeometry, SupportSegmentNormalAndConcaveBoundaries) {
  const test::BoxScene scene = test::two_touching_boxes();
  std::vector<int> truth;
  const Segmented s = segment_p1(points_of(scene, 0, truth));
  const std::uint32_t K = s.work.result.segment_count;
  const std::vector<SegmentGeometry> geometry = describe_segments(s.work, scene.plane);
  const SegmentGeometry& support = geometry[best_segment(s.work.result.labels, truth, 0, K) - 1];
  EXPECT_LT(test::angle_deg(support.mean_normal, scene.plane.normal.cast<double>()), 1.0);
  EXPECT_NEAR(support.obb.extents.x(), 0.5f, 1e-3f);  // the sampled square of the plane
  EXPECT_NEAR(support.obb.extents.y(), 0.5f, 1e-3f);
  for (int b = 1; b <= 2; ++b) {
    EXPECT_TRUE(has_neighbour(support, best_segment(s.work.result.labels, truth, b, K), Boundary::concave)) << b;
  }
}

// The organized variant (ray cast 640 x 480, NaN where nothing is hit, camera
// binning): NaN points carry label 0 and count in no segment.
TEST(SegmentGeometry, OrganizedSceneCountsEveryLabelledPointOnce) {
  const test::BoxScene scene = test::two_touching_boxes();
  const test::RenderedScene rendered = test::render(scene.rects);
  ASSERT_GT(rendered.cloud.height, 1u);
  ASSERT_LT(test::finite_count(rendered.cloud), rendered.cloud.size());
  const Segmented s = segment_p1(rendered.cloud);
  const std::vector<SegmentGeometry> geometry = describe_segments(s.work, scene.plane);
  std::uint64_t total = 0;
  for (const SegmentGeometry& g : geometry) total += g.points;
  EXPECT_EQ(total, test::finite_count(rendered.cloud));
  std::vector<int> truth;
  for (const int r : rendered.rect_of_point) truth.push_back(r < 0 ? -1 : scene.rect_truth[r]);
  const SegmentGeometry& support =
      geometry[best_segment(s.work.result.labels, truth, 0, s.work.result.segment_count) - 1];
  EXPECT_LT(test::angle_deg(support.mean_normal, scene.plane.normal.cast<double>()), 1.0);
}

// A hand-made segmentation: one segment of the given points, one voxel.
Segmented single_segment(std::vector<Eigen::Vector3f> points) {
  auto cloud = std::make_unique<PointCloud>(test::unorganized(std::move(points)));
  const auto n = static_cast<std::uint32_t>(cloud->size());
  SegmentationWork work(*cloud);
  work.grid.centroids = {Eigen::Vector3f::Zero()};
  work.grid.voxel_of_point.assign(n, 0);
  work.grid.points.offsets = {0, n};
  work.grid.points.items.resize(n);
  std::iota(work.grid.points.items.begin(), work.grid.points.items.end(), 0u);
  work.normals = {{Eigen::Vector3f(0, 0, -1)}, {1}};
  work.result.labels.assign(n, 1);
  work.result.segment_count = 1;
  return {std::move(cloud), std::move(work)};
}

// A solid grid of points 30 x 6 x 2 cm (edges included) in a tilted pose, 1 m in front of the sensor.
TEST(SegmentGeometry, PrincipalAxesFollowAnElongatedSet) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const Eigen::Vector3d size(0.30, 0.06, 0.02), origin(0.1, -0.05, 1.0);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i <= 150; ++i) {
    for (int j = 0; j <= 30; ++j) {
      for (int k = 0; k <= 10; ++k) {
        const Eigen::Vector3d local = Eigen::Vector3d(i / 150.0, j / 30.0, k / 10.0).cwiseProduct(size) - size / 2;
        points.push_back((origin + R * local).cast<float>());
      }
    }
  }
  const Segmented s = single_segment(std::move(points));
  // Plane normal along the set's thinnest axis: the box is the set's own, found by the calipers.
  const Plane plane{(R.col(2)).cast<float>(), 0.0f};
  for (const std::optional<Plane>& support : {std::optional<Plane>(), std::optional<Plane>(plane)}) {
    const SegmentGeometry g = describe_segments(s.work, support).at(0);
    EXPECT_EQ(g.points, 151u * 31u * 11u);
    EXPECT_LT((g.centroid.cast<double>() - origin).norm(), 1e-5);
    for (int a = 0; a < 3; ++a) {
      EXPECT_LT(line_angle_deg(g.principal_axes.col(a), R.col(a)), 0.01) << a;
      EXPECT_NEAR(g.principal_extents[a], size[a], 1e-5) << a;
      EXPECT_LT(line_angle_deg(g.obb.axes.col(a), R.col(a)), 0.01) << a;
      EXPECT_NEAR(g.obb.extents[a], size[a], 1e-5) << a;
    }
    EXPECT_NEAR(g.principal_axes.determinant(), 1.0f, 1e-5f);
    EXPECT_NEAR(g.obb.axes.determinant(), 1.0f, 1e-5f);
    EXPECT_LT((g.obb.center.cast<double>() - origin).norm(), 1e-5);
    EXPECT_TRUE(g.adjacent.empty());
  }
}

}  // namespace
}  // namespace lccp
