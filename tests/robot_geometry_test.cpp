// The hand-checked scene of the robot issue, through the whole robot preset
// (config/robot.yaml: RANSAC support plane, objects, parts, geometry): two boxes
// of known size and pose touching on a plane (tests/box_scene.hpp), noise-free.
// Asserted: the support plane's normal within 0.5 deg, the two boxes as two
// parts, each part's box axes within 2 deg of its box's, the boxes' shared
// boundary concave. Printed, not asserted: centroids and box extents. The robot
// issue asks for 2 mm and 5 mm; not reached yet (perf/RESULTS.md): the 1 cm
// support band takes the boxes' lowest centimetre, and at the concave crease P1's
// boundary is jagged by up to a supervoxel (up to 18 mm of B's top join A).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "box_scene.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/objects/scene.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

// The part holding most points of box b (truth b + 1), and the object it belongs to.
struct Match {
  const SegmentGeometry* part = nullptr;
  std::uint32_t object = 0;
};

Match best_part(const SceneSegmentation& scene, const test::BoxScene& boxes, int truth) {
  std::map<std::uint32_t, std::size_t> votes;
  for (std::size_t i = 0; i < boxes.truth.size(); ++i) {
    if (boxes.truth[i] == truth && scene.labels[i] != 0 && scene.labels[i] != scene.support_id) ++votes[scene.labels[i]];
  }
  const auto best = std::max_element(votes.begin(), votes.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
  Match match;
  for (const ObjectSegments& o : scene.segments) {
    for (const SegmentGeometry& part : o.parts) {
      if (best != votes.end() && part.id == best->first) match = {&part, o.object.id};
    }
  }
  return match;
}

Eigen::Vector3d visible_centroid(const test::BoxScene& boxes, int truth) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double n = 0;
  for (std::size_t i = 0; i < boxes.truth.size(); ++i) {
    if (boxes.truth[i] == truth) sum += boxes.cloud.points[i].cast<double>(), n += 1;
  }
  return sum / n;
}

double line_angle_deg(const Eigen::Vector3f& a, const Eigen::Vector3d& b) {
  return std::min(test::angle_deg(a, b), test::angle_deg(a, Eigen::Vector3d(-b)));
}

// The OBB's axes and extents against the box's: first axis the longer footprint side.
void expect_box(const OrientedBox& obb, const test::BoxTruth& box) {
  const int longer = box.extents.x() >= box.extents.y() ? 0 : 1;
  const Eigen::Vector3d extents(box.extents[longer], box.extents[1 - longer], box.extents.z());
  const int axes[3] = {longer, 1 - longer, 2};
  for (int a = 0; a < 3; ++a) {
    std::printf("  axis %d: extent %.1f mm (true %.1f), angle %.2f deg\n", a, 1000 * obb.extents[a],
                1000 * extents[a], line_angle_deg(obb.axes.col(a), box.axes.col(axes[a])));
    EXPECT_LT(line_angle_deg(obb.axes.col(a), box.axes.col(axes[a])), 2.0) << "axis " << a;
  }
}

TEST(RobotGeometry, TwoTouchingBoxesOnAPlaneMeasuredThroughTheRobotPreset) {
  const test::BoxScene boxes = test::two_touching_boxes();
  const SceneSegmenter segmenter(load_config(fs::path(LCCP_CONFIG_DIR) / "robot.yaml"));
  const SceneSegmentation scene = segmenter.segment(boxes.cloud);
  ASSERT_TRUE(scene.support_plane.has_value());
  const double plane_angle = test::angle_deg(scene.support_plane->normal, boxes.plane.normal.cast<double>());
  std::printf("support normal off by %.3f deg\n", plane_angle);
  EXPECT_LT(plane_angle, 0.5);
  const Match a = best_part(scene, boxes, 1), b = best_part(scene, boxes, 2);
  ASSERT_NE(a.part, nullptr);
  ASSERT_NE(b.part, nullptr);
  ASSERT_NE(a.part->id, b.part->id);
  for (int box = 0; box < 2; ++box) {
    const SegmentGeometry& part = *(box == 0 ? a : b).part;
    const double error = (part.centroid.cast<double>() - visible_centroid(boxes, box + 1)).norm();
    std::printf("box %d: part %u of object %u, centroid off by %.2f mm\n", box + 1, part.id,
                (box == 0 ? a : b).object, 1000 * error);
    expect_box(part.obb, boxes.boxes[box]);
  }
  const auto concave = [](const SegmentGeometry& g, std::uint32_t id) {
    return std::find(g.adjacent.begin(), g.adjacent.end(), Neighbour{id, Boundary::concave}) != g.adjacent.end();
  };
  // Two objects or two parts of one: either way they are neighbours across a concave boundary.
  if (a.object == b.object) {
    EXPECT_TRUE(concave(*a.part, b.part->id));
  } else {
    for (const ObjectSegments& o : scene.segments) {
      if (o.object.id == a.object) {
        EXPECT_TRUE(concave(o.object, b.object));
      }
    }
  }
}

// A robot that has cleared its table sees the plane alone: the frame is the
// support and no object, not an error.
TEST(RobotGeometry, AnEmptyTableIsTheSupportAndNoObject) {
  const test::BoxScene table = test::box_scene({}, test::SensorSpec{});
  ASSERT_GT(table.cloud.size(), 10000u);
  const SceneSegmenter segmenter(load_config(fs::path(LCCP_CONFIG_DIR) / "robot.yaml"));
  const SceneSegmentation scene = segmenter.segment(table.cloud);
  ASSERT_TRUE(scene.support_plane.has_value());
  EXPECT_LT(test::angle_deg(scene.support_plane->normal, table.plane.normal.cast<double>()), 0.5);
  ASSERT_NE(scene.support_id, 0u);
  EXPECT_TRUE(scene.segments.empty());
  EXPECT_EQ(scene.object_count, 0u);
  EXPECT_EQ(scene.segment_count, 0u);
  ASSERT_EQ(scene.labels.size(), table.cloud.size());
  for (std::size_t i = 0; i < scene.labels.size(); ++i) {
    ASSERT_EQ(scene.labels[i], scene.support_id) << "point " << i;
    ASSERT_EQ(scene.objects[i], scene.support_id) << "point " << i;
  }
}

}  // namespace
}  // namespace lccp
