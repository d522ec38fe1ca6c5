// Objects resting on a plane (contact_scenes.hpp), segmented at P1: where an object
// meets its support the crease is concave, so LCCP must keep the object apart from
// the plane (issue 15). perf/contact_battery runs the same scenes through PCL.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <string>

#include "contact_scenes.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/metrics/scores.hpp"

namespace lccp {
namespace {

std::size_t count_label(const Labels& truth, std::uint32_t label) {
  return static_cast<std::size_t>(std::count(truth.begin(), truth.end(), label));
}

TEST(ContactScenes, OrganizedAndUnorganizedHoldTheSameSurfaces) {
  const test::ContactObject dome = test::contact_cap(0.05, 0.05, "dome");
  test::ContactView view;
  const test::ContactScene organized = test::contact_scene(dome, view);
  view.organized = false;
  const test::ContactScene unorganized = test::contact_scene(dome, view);
  ASSERT_EQ(organized.cloud.width, 640u);
  ASSERT_EQ(organized.cloud.height, 480u);
  EXPECT_EQ(unorganized.cloud.height, 1u);
  for (const std::uint32_t label : {test::kContactPlaneLabel, test::kContactObjectLabel}) {
    EXPECT_GT(count_label(organized.truth, label), 2000u);
    EXPECT_EQ(count_label(organized.truth, label), count_label(unorganized.truth, label));
  }
  // Back in the world frame: plane points on z = 0, dome points on the sphere of
  // radius 5 cm about the origin, above the plane.
  const test::Pose& pose = organized.camera_from_world;
  for (std::size_t i = 0; i < organized.truth.size(); ++i) {
    if (organized.truth[i] == 0) continue;
    const Eigen::Vector3d p = pose.R.transpose() * (organized.cloud.points[i].cast<double>() - pose.t);
    if (organized.truth[i] == test::kContactPlaneLabel) {
      ASSERT_NEAR(p.z(), 0.0, 1e-5) << i;
    } else {
      ASSERT_NEAR(p.norm(), 0.05, 1e-5) << i;
      ASSERT_GE(p.z(), -1e-5) << i;
    }
  }
}

TEST(ContactScenes, KinectNoiseStaysWithinItsModel) {
  const test::ContactObject box = test::contact_box(0.10, 0.10, 0.10, 35);
  test::ContactView view;
  const test::ContactScene clean = test::contact_scene(box, view);
  view.noisy = true;
  const test::ContactScene noisy = test::contact_scene(box, view);
  std::size_t compared = 0, missing = 0;
  for (std::size_t i = 0; i < clean.truth.size(); ++i) {
    if (clean.truth[i] == 0) continue;
    if (noisy.truth[i] == 0) {
      ++missing;
      continue;
    }
    const double z = clean.cloud.points[i].z(), dz = std::abs(noisy.cloud.points[i].z() - z);
    // 6 sigma of the axial noise plus half a disparity step.
    EXPECT_LT(dz, 6 * synthetic::detail::axial_noise_sigma_m(z) + synthetic::detail::quantization_step_m(z));
    ++compared;
  }
  EXPECT_GT(compared, 10000u);
  EXPECT_GT(missing, 0u);                  // dropouts
  EXPECT_LT(missing, compared / 20);       // but few: the 0.5 % random ones and grazing views
}

// Both elevations, organized and unorganized, noise-free and Kinect-noisy: the
// object is not lost into the plane and its best segment is mostly the object.
void expect_apart_from_the_plane(const test::ContactObject& object, const LccpConfig& config) {
  const LccpSegmenter segmenter(config);
  for (const double elevation : {45.0, 30.0}) {
    for (const bool organized : {true, false}) {
      for (const bool noisy : {false, true}) {
        test::ContactView view;
        view.elevation_deg = elevation, view.organized = organized, view.noisy = noisy;
        SCOPED_TRACE(testing::Message() << "elevation " << elevation << (organized ? " organized" : " unorganized")
                                        << (noisy ? " kinect noise" : " noise-free"));
        const test::ContactScene scene = test::contact_scene(object, view);
        const SegmentationScores s =
            score_objects(segmenter.segment(scene.cloud).labels, scene.truth, scene.cloud.points, LabelRange{0, 9});
        EXPECT_EQ(s.objects_lost, 0u);
        EXPECT_GE(s.weighted_overlap, 0.8);
      }
    }
  }
}

class ObjectOnPlane : public testing::TestWithParam<test::ContactObject> {};

TEST_P(ObjectOnPlane, StandsApartFromThePlaneAtP1) { expect_apart_from_the_plane(GetParam(), LccpConfig{}); }

// Beyond the paper: with crease-preserving normals the bowls' rims do not blend
// into the plane's normals, and every object of the battery stands apart.
TEST_P(ObjectOnPlane, StandsApartFromThePlaneAtP1WithCreasePreservingNormals) {
  LccpConfig config;
  config.normals.crease_preserving = true;
  expect_apart_from_the_plane(GetParam(), config);
}

std::string case_name(const testing::TestParamInfo<test::ContactObject>& info) {
  std::string name;
  for (const char c : info.param.name) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

bool is_bowl(const test::ContactObject& o) {
  return o.shape == test::ContactObject::Shape::cap && o.cap_height_m < o.sphere_radius_m;
}

// Boxes from 5 cm wide to 3x taller than wide, and domes.
std::vector<test::ContactObject> boxes_and_domes() {
  std::vector<test::ContactObject> objects;
  for (const test::ContactObject& o : test::contact_objects()) {
    if (!is_bowl(o)) objects.push_back(o);
  }
  return objects;
}

INSTANTIATE_TEST_SUITE_P(BoxesAndDomes, ObjectOnPlane, testing::ValuesIn(boxes_and_domes()), case_name);

// Upside-down bowls whose rim meets the plane at 60 and 45 deg. At P1 as the paper
// has it, some of their views merge into the plane (perf/RESULTS.md, issue 15): the
// rim's normals blend with the plane's, so only the crease-preserving test is run.
class BowlOnPlane : public testing::TestWithParam<test::ContactObject> {};

TEST_P(BowlOnPlane, StandsApartFromThePlaneAtP1WithCreasePreservingNormals) {
  LccpConfig config;
  config.normals.crease_preserving = true;
  expect_apart_from_the_plane(GetParam(), config);
}

std::vector<test::ContactObject> bowls() {
  std::vector<test::ContactObject> objects;
  for (const test::ContactObject& o : test::contact_objects()) {
    if (is_bowl(o)) objects.push_back(o);
  }
  return objects;
}

INSTANTIATE_TEST_SUITE_P(Bowls, BowlOnPlane, testing::ValuesIn(bowls()), case_name);

}  // namespace
}  // namespace lccp
