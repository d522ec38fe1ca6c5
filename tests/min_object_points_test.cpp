// min_object_points (config.hpp, FilterConfig): at the object level, an object
// of fewer points is dropped and its points get label 0; the other objects keep
// their points and are numbered as before.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "expect_error.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/objects/scene.hpp"

namespace lccp {
namespace {

using test::expect_lccp_error;

// A table (y = 0.5 m, the camera's y points down) with a 10 cm cube on it, and a
// speck of 9 points within 4 mm floating 20 cm above the table: a flying pixel's kind.
struct TableWithSpeck {
  PointCloud cloud;
  std::size_t speck_begin = 0, speck_end = 0;

  TableWithSpeck() {
    constexpr float kStep = 0.004f;
    for (float x = -0.4f; x <= 0.4f; x += kStep)
      for (float z = 0.8f; z <= 1.6f; z += kStep) add({x, 0.5f, z});
    for (float a = 0.0f; a <= 0.1f; a += kStep / 2)  // the cube's top and the two faces towards the camera
      for (float b = 0.0f; b <= 0.1f; b += kStep / 2) {
        add({-0.05f + a, 0.4f, 1.0f + b});
        add({-0.05f + a, 0.4f + b, 1.0f});
        add({-0.05f, 0.4f + b, 1.0f + a});
      }
    speck_begin = cloud.points.size();
    for (int k = 0; k < 9; ++k) add({0.3f + 0.001f * (k % 3), 0.3f + 0.001f * (k / 3), 1.2f});
    speck_end = cloud.points.size();
  }
  void add(const Eigen::Vector3f& p) {
    cloud.points.push_back(p);
    cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  }
};

SceneSegmentation segment_with(const std::string& preset, const std::vector<std::string>& settings,
                               const PointCloud& cloud) {
  return SceneSegmenter(resolve_config(preset, settings)).segment(cloud);
}

TEST(MinObjectPoints, ASpeckBelowTheSizeIsNoObjectAndItsPointsAreUnassigned) {
  const TableWithSpeck scene;
  for (const std::string preset : {"objects", "robot"}) {
    SCOPED_TRACE(preset);
    const SceneSegmentation kept = segment_with(preset, {"min_object_points=0"}, scene.cloud);
    const SceneSegmentation dropped = segment_with(preset, {}, scene.cloud);  // the preset's 25 points
    const Labels& kept_objects = preset == "robot" ? kept.objects : kept.labels;
    const Labels& dropped_objects = preset == "robot" ? dropped.objects : dropped.labels;
    ASSERT_EQ(kept.object_count, 2u);  // the cube and the speck
    EXPECT_EQ(dropped.object_count, 1u);
    EXPECT_EQ(dropped.segments.size(), 1u);
    std::set<std::uint32_t> speck_ids;
    for (std::size_t i = scene.speck_begin; i < scene.speck_end; ++i) {
      speck_ids.insert(kept_objects[i]);
      EXPECT_EQ(dropped_objects[i], 0u) << "speck point " << i;
      EXPECT_EQ(dropped.labels[i], 0u) << "speck point " << i;
    }
    EXPECT_EQ(speck_ids.size(), 1u);
    EXPECT_NE(*speck_ids.begin(), 0u);
    // Every other point keeps its object.
    for (std::size_t i = 0; i < scene.speck_begin; ++i) {
      ASSERT_EQ(dropped_objects[i], kept_objects[i]) << "point " << i;
    }
  }
}

TEST(MinObjectPoints, OnThePartLevelIsRefused) {
  expect_lccp_error([] { SceneSegmenter(resolve_config("paper-robot", {"parts.min_object_points=10"})); },
                    {"parts.min_object_points", "objects"});
}

}  // namespace
}  // namespace lccp
