// SensorConfig::depth_steps: camera cells never shallower than the sensor's
// depth step, and the smoothness check's slack never below half a step.
// Scenes: the test_clouds.hpp renderer, each depth then rounded as a Kinect v1
// rounds it, to the nearest measurable depth z_n = 1 / (n q), q = d / (f b)
// (Khoshelham and Elberink 2012), the point kept on its pixel's ray.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "lccp/core/convexity.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/core/voxel_grid.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

// Every point's depth rounded to the sensor's nearest measurable depth.
PointCloud quantized(PointCloud cloud, const SensorConfig& sensor) {
  const double q = sensor.step_per_m2();
  for (Eigen::Vector3f& p : cloud.points) {
    if (!p.allFinite()) continue;
    const double z = 1.0 / (std::round(1.0 / (q * p.z())) * q);
    p = (p.cast<double>() * (z / p.z())).cast<float>();
  }
  return cloud;
}

// A 2 m square wall 4.5 m away, turned 50 deg about the vertical: its depth
// changes by about 1.1 cm a pixel across, while a step there is 5.8 cm, so it is
// seen as terraces five pixels wide.
PointCloud slanted_wall_at_range(const SensorConfig& sensor) {
  return quantized(test::render({test::tilted_rect(4.5, 2.0, 50.0, 0.0)}).cloud, sensor);
}

// Connected components of the voxel adjacency.
std::size_t voxel_components(const VoxelGrid& grid) {
  std::vector<std::uint32_t> component(grid.size(), kNoVoxel);
  std::size_t count = 0;
  for (std::uint32_t start = 0; start < grid.size(); ++start) {
    if (component[start] != kNoVoxel) continue;
    std::vector<std::uint32_t> stack{start};
    component[start] = static_cast<std::uint32_t>(count);
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      for (const std::uint32_t* u = grid.neighbors.begin(v); u != grid.neighbors.end(v); ++u) {
        if (component[*u] == kNoVoxel) component[*u] = static_cast<std::uint32_t>(count), stack.push_back(*u);
      }
    }
    ++count;
  }
  return count;
}

double largest_segment_share(const std::vector<std::uint32_t>& labels) {
  std::map<std::uint32_t, std::size_t> sizes;
  std::size_t labelled = 0;
  for (const std::uint32_t label : labels) {
    if (label == 0) continue;
    ++sizes[label];
    ++labelled;
  }
  std::size_t largest = 0;
  for (const auto& [label, size] : sizes) largest = std::max(largest, size);
  return labelled ? static_cast<double>(largest) / static_cast<double>(labelled) : 0.0;
}

TEST(SensorDepthSteps, NeighbouringMeasurableDepthsAreAdjacentCells) {
  SensorConfig sensor;
  const PointCloud wall = slanted_wall_at_range(sensor);
  const VoxelConfig cells{0.005f, Binning::camera};
  EXPECT_EQ(voxel_components(voxelize(wall, cells, sensor)), 1u);
  sensor.depth_steps = false;  // cells v z = 2.3 cm deep: each step skips a cell
  EXPECT_GT(voxel_components(voxelize(wall, cells, sensor)), 10u);
}

TEST(SensorDepthSteps, NearerThanTheStepDepthCellsAreUnchanged) {
  // z_q = v / q = 1.74 m for a Kinect v1 and v = 5 mm: a wall at 1.2 m gets
  // the same voxels either way.
  SensorConfig on, off;
  off.depth_steps = false;
  const PointCloud wall = quantized(test::render({test::tilted_rect(1.2, 0.6, 50.0, 0.0)}).cloud, on);
  const VoxelConfig cells{0.005f, Binning::camera};
  EXPECT_EQ(voxelize(wall, cells, on).voxel_of_point, voxelize(wall, cells, off).voxel_of_point);
}

TEST(SensorDepthSteps, ASlantedWallAtRangeIsOneSegment) {
  LccpConfig config;  // P1 defaults
  const PointCloud wall = slanted_wall_at_range(config.sensor);
  EXPECT_GE(largest_segment_share(LccpSegmenter(config).segment(wall).labels), 0.99);
  config.sensor.depth_steps = false;
  EXPECT_LT(largest_segment_share(LccpSegmenter(config).segment(wall).labels), 0.5);
}

TEST(SensorDepthSteps, SmoothnessSlackIsHalfAStepWhereThatIsLarger) {
  const ConvexityConfig config;  // smoothness_threshold 0.1 v
  const SensorConfig sensor;
  const PatchSizes with_steps{0.005f, 0.02f, sensor.step_per_m2()}, without{0.005f, 0.02f};
  const auto parallel = [](float z, float offset) {
    return std::pair{Patch{{0.0f, 0.0f, z}, {0.0f, 0.0f, -1.0f}}, Patch{{0.05f, 0.0f, z + offset}, {0.0f, 0.0f, -1.0f}}};
  };
  // 4.5 m: a step is 5.8 cm; 2 cm is within half of it, 4 cm is not.
  const auto [a, b] = parallel(4.5f, 0.02f);
  EXPECT_TRUE(smoothness_criterion(a, b, config, with_steps));
  EXPECT_FALSE(smoothness_criterion(a, b, config, without));
  const auto [c, d] = parallel(4.5f, 0.04f);
  EXPECT_FALSE(smoothness_criterion(c, d, config, with_steps));
  // 0.9 m: half a step is 1.2 mm, so a 1 cm step between two boxes' faces stays a step.
  const auto [e, f] = parallel(0.9f, 0.01f);
  EXPECT_FALSE(smoothness_criterion(e, f, config, with_steps));
  const auto [g, h] = parallel(0.9f, 0.001f);
  EXPECT_TRUE(smoothness_criterion(g, h, config, with_steps));
  EXPECT_FALSE(smoothness_criterion(g, h, config, without));  // 1 mm > 0.1 v = 0.5 mm
}

}  // namespace
}  // namespace lccp
