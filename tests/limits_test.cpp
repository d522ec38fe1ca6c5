// The limits of LimitsConfig: every cloud or config beyond them is refused with
// one lccp::Error naming the limit, never a crash, a hang or a silent collapse.
#include <gtest/gtest.h>

#include <climits>
#include <string>
#include <vector>

#include "../src/core/cell_keys.hpp"
#include "lccp/config.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/error.hpp"
#include "lccp/io/config_file.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

// A 20 x 20 cm patch of a plane at 1 m, sampled every 4 mm, as an organized cloud.
PointCloud small_plane(const Eigen::Vector3f& shift = Eigen::Vector3f::Zero()) {
  PointCloud cloud;
  cloud.width = 50;
  cloud.height = 50;
  for (int r = 0; r < 50; ++r) {
    for (int c = 0; c < 50; ++c) cloud.points.push_back(Eigen::Vector3f(0.004f * c - 0.1f, 0.004f * r - 0.1f, 1.0f) + shift);
  }
  return cloud;
}

// Runs the segmenter and returns the error message ("" if it succeeded).
std::string segment_error(const LccpConfig& config, const PointCloud& cloud) {
  try {
    LccpSegmenter(config).segment(cloud);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string validate_error(const LccpConfig& config) {
  try {
    validate(config);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Limits, FarPointInASmallOrganizedCloudIsRefused) {
  // Fuzzing found this crash: 2 x 2 points, one at z = 1e12.
  PointCloud cloud;
  cloud.width = 2;
  cloud.height = 2;
  cloud.points = {{0.0f, 0.0f, 1.0f}, {0.01f, 0.0f, 1.0f}, {0.0f, 0.01f, 1.0f}, {0.0f, 0.0f, 1e12f}};
  const std::string error = segment_error(LccpConfig{}, cloud);
  EXPECT_NE(error.find("max_coordinate_m"), std::string::npos) << error;
  EXPECT_NE(error.find("1e+12"), std::string::npos) << error;
}

TEST(Limits, SceneShiftedFarFromTheOriginIsRefusedNotCollapsed) {
  // At 1e6 m a float's spacing is 6 cm: the plane would become one voxel.
  const std::string error = segment_error(LccpConfig{}, small_plane(Eigen::Vector3f(1e6f, 0.0f, 0.0f)));
  EXPECT_NE(error.find("max_coordinate_m (500)"), std::string::npos) << error;
  // Within the limit the same plane segments into one segment.
  const SegmentationResult ok = LccpSegmenter(LccpConfig{}).segment(small_plane(Eigen::Vector3f(100.0f, 0.0f, 0.0f)));
  EXPECT_EQ(ok.segment_count, 1u);
}

TEST(Limits, HugeSeedSizesAreRefusedByValidation) {
  for (const float seed : {1e30f, 1000.0f, 0.3f}) {
    LccpConfig config;
    config.supervoxels.seed_size_m = seed;
    const std::string error = validate_error(config);
    EXPECT_NE(error.find("seed_size_m"), std::string::npos) << seed << ": " << error;
    EXPECT_NE(error.find("max_growth_passes (100)"), std::string::npos) << seed << ": " << error;
  }
  LccpConfig p2;  // the paper's P2 needs 13 passes
  p2.voxels.voxel_size_m = 0.0075f;
  p2.supervoxels.seed_size_m = 0.06f;
  EXPECT_EQ(validate_error(p2), "");
  EXPECT_EQ(growth_passes(0.06f, 0.0075f), 13);
  EXPECT_EQ(growth_passes(0.02f, 0.005f), 6);
  EXPECT_EQ(growth_passes(1e30f, 1e-30f), 1'000'000'000);
}

TEST(Limits, CoordinateLimitMustKeepFloatSpacingBelowASixteenthOfAVoxel) {
  LccpConfig config;
  config.limits.max_coordinate_m = 5000.0f;  // 5 mm voxels: at most 2621 m
  EXPECT_NE(validate_error(config).find("max_coordinate_m"), std::string::npos);
  config.limits.max_coordinate_m = 2000.0f;
  EXPECT_EQ(validate_error(config), "");
}

TEST(Limits, PointAndVoxelCountsAreBounded) {
  LccpConfig config;
  config.limits.max_points = 2499;
  EXPECT_NE(segment_error(config, small_plane()).find("2500 points, more than max_points (2499)"), std::string::npos);
  config.limits.max_points = 2500;
  config.limits.max_voxels = 10;
  EXPECT_NE(segment_error(config, small_plane()).find("more than max_voxels (10)"), std::string::npos);
}

TEST(Limits, LimitsAreConfigKeys) {
  SceneConfig config;
  apply_setting(config, "max_points=100");
  apply_setting(config, "max_voxels=50");
  apply_setting(config, "max_growth_passes=7");
  apply_setting(config, "max_coordinate_m=20");
  EXPECT_EQ(config.objects.limits.max_points, 100u);
  EXPECT_EQ(config.objects.limits.max_voxels, 50u);
  EXPECT_EQ(config.objects.limits.max_growth_passes, 7u);
  EXPECT_EQ(config.objects.limits.max_coordinate_m, 20.0f);
  EXPECT_THROW(apply_setting(config, "max_points=-1"), Error);
}

TEST(Limits, CellKeysRefuseBoxesWhoseSidesDoNotFitAnInt) {
  using detail::Cell;
  EXPECT_FALSE(detail::CellKeys(Cell(INT_MIN, 0, 0), Cell(INT_MAX, 0, 0)).fits());
  EXPECT_FALSE(detail::CellKeys(Cell(-(1 << 30), 0, 0), Cell(1 << 30, 0, 0)).fits());
  EXPECT_FALSE(detail::CellKeys(Cell(0, 0, 0), Cell(1 << 30, 1 << 30, 1 << 30)).fits());
  const detail::CellKeys small(Cell(-5, -5, -5), Cell(5, 5, 5));
  ASSERT_TRUE(small.fits());
  EXPECT_EQ(small.extent(0), 13u);
  EXPECT_EQ(small.key(Cell(-5, -5, -5)) + small.offset(1, 1, 1), small.key(Cell(-4, -4, -4)));
}

}  // namespace
}  // namespace lccp
