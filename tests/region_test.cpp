// The region of interest (RegionConfig): points outside the box are left out
// before anything else, exactly as if they had no depth; the support plane is
// sought among the rest; the keys parse, validate and show.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "lccp/config.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/io/config_file.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

std::string config_error(const std::string& setting) {
  SceneConfig config;
  try {
    apply_setting(config, setting);
    validate(config);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(RegionOfInterest, KeysParseValidateAndShow) {
  EXPECT_FALSE(LccpConfig{}.region.bounded());
  const SceneConfig config = parse_config("region_min_z_m: 0.5\nregion_max_z_m: 1.5\nregion_min_x_m: -inf\n", "test");
  EXPECT_EQ(config.objects.region.min_z_m, 0.5f);
  EXPECT_EQ(config.objects.region.max_z_m, 1.5f);
  EXPECT_EQ(config.objects.region.min_x_m, -kInf);
  EXPECT_EQ(config.objects.region.max_y_m, kInf);
  EXPECT_TRUE(config.objects.region.bounded());
  EXPECT_NE(describe_config(config).find("region_max_z_m: 1.5"), std::string::npos) << describe_config(config);

  EXPECT_EQ(config_error("region_max_x_m=inf"), "");
  EXPECT_EQ(parse_config("region_min_y_m: -.inf\nregion_max_y_m: .inf\n", "yaml").objects.region.min_y_m, -kInf);
  EXPECT_EQ(parse_config("region_max_y_m: .Inf\n", "yaml").objects.region.max_y_m, kInf);
  EXPECT_NE(config_error("region_min_z_m=inf").find("'region_min_z_m' must be below its max key"), std::string::npos)
      << config_error("region_min_z_m=inf");
  EXPECT_NE(config_error("region_max_y_m=-inf").find("'region_min_y_m'"), std::string::npos);
  EXPECT_NE(config_error("region_max_x_m=nan").find("'region_min_x_m'"), std::string::npos);
  EXPECT_NE(config_error("region_max_z_m=far").find("is not a number"), std::string::npos);
}

// mOSD test scene 2 (depths 0.5-1.2 m, median 0.73 m) cut at 0.75 m: the far
// half is left out, and the near half is labelled exactly as when the far half's
// points have no depth at all.
TEST(RegionOfInterest, PointsOutsideAreLabelledAsIfTheyHadNoDepth) {
  const PointCloud cloud = read_cloud(std::filesystem::path(LCCP_TEST_DATA_DIR) / "mosd_test2.pcd").cloud;
  LccpConfig config;
  config.region.min_z_m = 0.0f;
  config.region.max_z_m = 0.75f;
  PointCloud cut = cloud;
  std::size_t outside = 0, inside = 0;
  for (Eigen::Vector3f& p : cut.points) {
    if (!is_finite(p)) continue;
    const bool in = p.z() <= config.region.max_z_m;
    (in ? inside : outside) += 1;
    if (!in) p = Eigen::Vector3f::Constant(kNaN);
  }
  ASSERT_GT(outside, 20000u);
  ASSERT_GT(inside, 20000u);

  const Labels with_region = LccpSegmenter(config).segment(cloud).labels;
  const Labels without_depth = LccpSegmenter(LccpConfig{}).segment(cut).labels;
  EXPECT_EQ(with_region, without_depth);
  std::size_t labelled = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cloud.points[i].z() > config.region.max_z_m) {
      EXPECT_EQ(with_region[i], 0u) << "point " << i;
    }
    labelled += with_region[i] != 0;
  }
  EXPECT_EQ(labelled, inside);
}

// Nothing inside the region is a result (no segment, every point 0), as a
// robot needs when it looks away from its work space; a cloud without any
// finite point is still an error, region or not.
TEST(RegionOfInterest, ARegionHoldingNoPointGivesAnEmptyResult) {
  const PointCloud cloud = read_cloud(std::filesystem::path(LCCP_TEST_DATA_DIR) / "mosd_test2.pcd").cloud;
  LccpConfig config;
  config.region.max_z_m = 0.1f;  // the scene's depths are 0.5-1.2 m
  const SegmentationResult result = LccpSegmenter(config).segment(cloud);
  EXPECT_EQ(result.segment_count, 0u);
  EXPECT_EQ(result.supervoxel_count, 0u);
  EXPECT_EQ(result.voxel_count, 0u);
  ASSERT_EQ(result.labels.size(), cloud.size());
  EXPECT_EQ(std::count(result.labels.begin(), result.labels.end(), 0u), static_cast<std::ptrdiff_t>(cloud.size()));

  PointCloud no_depth = cloud;
  for (Eigen::Vector3f& p : no_depth.points) p = Eigen::Vector3f::Constant(kNaN);
  for (const LccpConfig& c : {config, LccpConfig{}}) {
    try {
      LccpSegmenter(c).segment(no_depth);
      ADD_FAILURE() << "a cloud without finite points was segmented";
    } catch (const Error& e) {
      EXPECT_STREQ(e.what(), "the cloud has no finite points");
    }
  }
}

// A 0.8 x 0.8 m table 0.3 m below the sensor with a 10 cm cube on it and,
// 2.5 m away, a wall with four times its points. Without a region the wall is
// the biggest plane and becomes the support; with the depth range cut at 2 m
// the table does, and the wall's points are left out.
TEST(RegionOfInterest, TheSupportPlaneIsSoughtInsideTheRegion) {
  PointCloud cloud;
  for (int a = 0; a <= 160; ++a) {
    for (int b = 0; b <= 160; ++b) cloud.points.emplace_back(-0.4f + 0.005f * a, 0.3f, 0.6f + 0.005f * b);
  }
  const std::size_t table_points = cloud.points.size();
  for (int a = 0; a <= 20; ++a) {
    for (int b = 0; b <= 20; ++b) {
      cloud.points.emplace_back(-0.05f + 0.005f * a, 0.2f, 0.95f + 0.005f * b);   // top
      cloud.points.emplace_back(-0.05f + 0.005f * a, 0.2f + 0.005f * b, 0.95f);  // front
    }
  }
  const std::size_t wall_begin = cloud.points.size();
  for (int a = 0; a <= 400; ++a) {
    for (int b = 0; b <= 260; ++b) cloud.points.emplace_back(-1.0f + 0.005f * a, -1.0f + 0.005f * b, 2.5f);
  }
  cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  ASSERT_GT(cloud.points.size() - wall_begin, 4 * table_points);

  LccpConfig config;
  config.support.enabled = true;
  const SegmentationWork everything = LccpSegmenter(config).run(cloud);
  ASSERT_TRUE(everything.support.has_value());
  EXPECT_LT(test::angle_deg(everything.support->plane.normal, Eigen::Vector3d(0, 0, -1)), 1.0);

  config.region.max_z_m = 2.0f;
  const SegmentationWork near = LccpSegmenter(config).run(cloud);
  ASSERT_TRUE(near.support.has_value());
  EXPECT_LT(test::angle_deg(near.support->plane.normal, Eigen::Vector3d(0, -1, 0)), 1.0);
  EXPECT_NEAR(near.support->plane.d, 0.3f, 1e-3f);
  EXPECT_EQ(near.support->inliers, table_points + 3 * 21);  // and the cube's rows within distance_m (1 cm)
  for (std::size_t i = wall_begin; i < cloud.size(); ++i) {
    ASSERT_EQ(near.support->on_plane[i], 0u) << "wall point " << i;
    ASSERT_EQ(near.result.labels[i], 0u) << "wall point " << i;
  }
}

}  // namespace
}  // namespace lccp
