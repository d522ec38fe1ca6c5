// The robot battery: objects a robot meets on a table (robot_scenes.hpp: two
// boxes apart, two boxes touching, a box on a box, an upright mug with its
// handle, a pan with a long handle, a can on its side twice), each from the
// eight contact views (elevation 45 and 30 deg, organized and unorganized,
// noise-free and Kinect-noisy), through the robot preset (config/robot.yaml).
// Per case, the acceptance criteria of the robot issue:
//   - the support plane found, its normal within 0.5 deg of the true one;
//   - as many objects as there are, the true objects one-to-one on predicted
//     ones (each true object: the object id holding most of its points);
//   - each matched object's centroid within 2 mm (noise-free) / 10 mm (noise)
//     of the centroid of the true object's points in the cloud;
//   - its box's extents within 5 mm / 10 mm of the true object's: the
//     minimum-area rectangle of its whole solids' footprint (hidden faces too),
//     longer side first, and its own height (from its lowest point: an object
//     resting on another is boxed from its own bottom);
//   - its box's axes within 2 deg: the third the plane normal, the first the
//     footprint rectangle's longer side (as a line);
//   - every reported object's centroid inside its own box (grown by 1 mm).
// Every measured figure is printed ("[robot]" lines) so that it can be quoted.
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "lccp/io/config_file.hpp"
#include "lccp/objects/scene.hpp"
#include "robot_scenes.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

constexpr double kPlaneAngleDeg = 0.5, kAxisAngleDeg = 2.0, kBoxGrowthM = 0.001;
// Every part of every scene shows at least this many points in every view, so
// that a lost object is the segmentation's doing, not the view's.
constexpr std::size_t kMinPartPoints = 100;

struct Tolerances {
  double centroid_m = 0, extent_m = 0;
};

Tolerances tolerances(const test::ContactView& view) {
  return view.noisy ? Tolerances{0.010, 0.010} : Tolerances{0.002, 0.005};
}

const SceneSegmenter& robot_segmenter() {
  static const SceneSegmenter segmenter(load_config(fs::path(LCCP_CONFIG_DIR) / "robot.yaml"));
  return segmenter;
}

// A ground-truth label of the true object `object` (n * 10): any of its parts n * 10 + k.
bool of_object(std::uint32_t label, std::uint32_t object) { return label >= 10 && label / 10 * 10 == object; }

// A world direction in the camera frame (the cloud's).
Eigen::Vector3d in_camera(const test::ContactScene& scene, const Eigen::Vector3d& world) {
  return scene.camera_from_world.R * world;
}

double line_angle_deg(const Eigen::Vector3f& a, const Eigen::Vector3d& b) {
  return std::min(test::angle_deg(a, b), test::angle_deg(a, Eigen::Vector3d(-b)));
}

// The centroid of the true object's points in the cloud, all its parts together.
Eigen::Vector3d visible_centroid(const test::ContactScene& scene, std::uint32_t object) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double n = 0;
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    if (of_object(scene.truth[i], object)) sum += scene.cloud.points[i].cast<double>(), n += 1;
  }
  return sum / n;
}

// Not asserted, printed to tell a hidden extent from a wrong one: the
// minimum-area rectangle (0.25 deg steps) of the true object's visible points
// in the plane, and their top above it.
Eigen::Vector3d visible_extents(const test::ContactScene& scene, std::uint32_t object) {
  std::vector<Eigen::Vector3d> world;
  const test::Pose& pose = scene.camera_from_world;
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    if (of_object(scene.truth[i], object)) {
      world.push_back(pose.R.transpose() * (scene.cloud.points[i].cast<double>() - pose.t));
    }
  }
  Eigen::Vector3d best(0, 0, 0);
  double top = 0;
  for (const Eigen::Vector3d& p : world) top = std::max(top, p.z());
  for (double t_deg = 0; t_deg < 90; t_deg += 0.25) {
    const double t = test::deg2rad(t_deg);
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e9), hi = Eigen::Vector2d::Constant(-1e9);
    for (const Eigen::Vector3d& p : world) {
      const Eigen::Vector2d q(std::cos(t) * p.x() + std::sin(t) * p.y(), -std::sin(t) * p.x() + std::cos(t) * p.y());
      lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    }
    const Eigen::Vector2d sides = hi - lo;
    if (best.x() == 0 || sides.prod() < best.x() * best.y()) best = {sides.maxCoeff(), sides.minCoeff(), top};
  }
  return best;
}

// Every part is in view (else the case tests the view, not the segmentation).
void expect_every_part_seen(const test::RobotCase& c, const test::ContactScene& scene) {
  std::printf("[robot] %s: points", c.name().c_str());
  for (const test::ContactSolid& s : c.layout.solids) {
    const auto n = static_cast<std::size_t>(std::count(scene.truth.begin(), scene.truth.end(), s.label));
    std::printf(" %u: %zu", s.label, n);
    EXPECT_GE(n, kMinPartPoints) << "part " << s.label << " hardly in view";
  }
  std::printf("\n");
}

void expect_support_plane(const SceneSegmentation& seg, const test::ContactScene& scene) {
  ASSERT_TRUE(seg.support_plane.has_value()) << "no support plane";
  const double angle = test::angle_deg(seg.support_plane->normal, in_camera(scene, Eigen::Vector3d::UnitZ()));
  std::printf("[robot]   support normal off by %.3f deg\n", angle);
  EXPECT_LT(angle, kPlaneAngleDeg) << "support plane normal";
}

// The id (of an object, the support, or 0) holding most points of the true
// object (ties: the smaller id).
std::uint32_t id_holding_most(const SceneSegmentation& seg, const test::ContactScene& scene, std::uint32_t object) {
  const Labels& ids = seg.objects.empty() ? seg.labels : seg.objects;  // one level: the segments are the objects
  std::map<std::uint32_t, std::size_t> votes;
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    if (of_object(scene.truth[i], object)) ++votes[ids[i]];
  }
  std::uint32_t best = 0;
  std::size_t most = 0;
  for (const auto& [id, n] : votes) {
    if (n > most) best = id, most = n;
  }
  return best;
}

const ObjectSegments* reported_object(const SceneSegmentation& seg, std::uint32_t id) {
  for (const ObjectSegments& o : seg.segments) {
    if (o.object.id == id) return &o;
  }
  return nullptr;
}

// The object count, and each true object's predicted object (nullptr: mostly
// in the support or in none); the true objects must land on different ones.
std::vector<const ObjectSegments*> match_objects(const SceneSegmentation& seg, const test::ContactScene& scene,
                                                 const std::vector<test::ObjectTruth>& truths) {
  std::printf("[robot]   objects %u (true %zu)\n", seg.object_count, truths.size());
  EXPECT_EQ(seg.object_count, truths.size()) << "object count";
  std::vector<const ObjectSegments*> matched;
  std::map<std::uint32_t, std::uint32_t> truth_of_id;
  for (const test::ObjectTruth& t : truths) {
    const std::uint32_t id = id_holding_most(seg, scene, t.object);
    const ObjectSegments* o = id == seg.support_id ? nullptr : reported_object(seg, id);
    EXPECT_NE(o, nullptr) << "true object " << t.object << " mostly in " << (id == 0 ? "no segment" : "the support");
    const auto [it, fresh] = truth_of_id.emplace(id, t.object);
    EXPECT_TRUE(fresh || o == nullptr) << "true objects " << it->second << " and " << t.object
                                       << " both mostly in object " << id;
    matched.push_back(o);
  }
  return matched;
}

// The box's first axis against the footprint rectangle's longer side: the
// smallest angle to any of the minimum rectangles' (mirror images share it).
double first_axis_angle(const OrientedBox& box, const test::ObjectTruth& t, const test::ContactScene& scene) {
  double angle = 180;
  for (const Eigen::Vector3d& side : t.longer_sides) {
    angle = std::min(angle, line_angle_deg(box.axes.col(0), in_camera(scene, side)));
  }
  return angle;
}

void expect_axes(const OrientedBox& box, const test::ObjectTruth& t, const test::ContactScene& scene) {
  const Eigen::Vector3f third = box.axes.col(2);
  const double up = test::angle_deg(third, in_camera(scene, Eigen::Vector3d::UnitZ()));
  std::printf("[robot]     axis 2 off the plane normal by %.2f deg", up);
  EXPECT_LT(up, kAxisAngleDeg) << "object " << t.object << ": box axis 2 against the plane normal";
  // A footprint whose sides are less than 10 % apart (round or square) has no
  // meaningful longer side: the first axis may lie anywhere in the plane.
  if (!t.direction_defined()) {
    std::printf("; axis 0 not checked (footprint sides %.1f, %.1f mm)\n", 1000 * t.extents.x(), 1000 * t.extents.y());
    return;
  }
  const double along = first_axis_angle(box, t, scene);
  std::printf("; axis 0 off the longer side by %.2f deg\n", along);
  EXPECT_LT(along, kAxisAngleDeg) << "object " << t.object << ": box axis 0 against the footprint's longer side";
}

void expect_object(const SegmentGeometry& g, const test::ObjectTruth& t, const test::ContactScene& scene,
                   const Tolerances& tol) {
  const double centroid_error = (g.centroid.cast<double>() - visible_centroid(scene, t.object)).norm();
  const Eigen::Vector3d extent_error = (g.obb.extents.cast<double>() - t.extents).cwiseAbs();
  const Eigen::Vector3d mm = 1000 * g.obb.extents.cast<double>(), true_mm = 1000 * t.extents;
  const Eigen::Vector3d off_mm = 1000 * extent_error;
  std::printf("[robot]   object %u -> id %u (%llu points): centroid off by %.2f mm; extents %.1f %.1f %.1f mm, "
              "true %.1f %.1f %.1f, off by %.1f %.1f %.1f\n",
              t.object, g.id, static_cast<unsigned long long>(g.points), 1000 * centroid_error, mm.x(), mm.y(), mm.z(),
              true_mm.x(), true_mm.y(), true_mm.z(), off_mm.x(), off_mm.y(), off_mm.z());
  const Eigen::Vector3d seen = visible_extents(scene, t.object);
  std::printf("[robot]     its visible points alone span %.1f %.1f mm, top %.1f mm", 1000 * seen.x(), 1000 * seen.y(),
              1000 * seen.z());
  if (t.lowest > 1e-9) std::printf("; it rests %.1f mm above the plane", 1000 * t.lowest);
  std::printf("\n");
  EXPECT_LT(centroid_error, tol.centroid_m) << "object " << t.object << ": centroid";
  const char* const axis_name[3] = {"longer footprint side", "shorter footprint side", "height"};
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(extent_error[a], tol.extent_m) << "object " << t.object << ": extent along the " << axis_name[a]
                                             << ", " << g.obb.extents[a] << " m against " << t.extents[a];
  }
  expect_axes(g.obb, t, scene);
}

// Every reported object's centroid lies inside its own box, grown by 1 mm.
void expect_centroids_in_their_boxes(const SceneSegmentation& seg) {
  for (const ObjectSegments& o : seg.segments) {
    const OrientedBox& box = o.object.obb;
    const Eigen::Vector3f local = box.axes.transpose() * (o.object.centroid - box.center);
    const Eigen::Vector3f outside = local.cwiseAbs() - box.extents / 2;
    EXPECT_LE(outside.maxCoeff(), kBoxGrowthM) << "object id " << o.object.id << ": centroid "
                                               << 1000 * outside.maxCoeff() << " mm outside its box";
  }
}

// The cases on which the robot issue's criteria are not met yet (perf/RESULTS.md,
// issue 33, says by how much and why): their checks run and print what fails,
// as "[robot] NOT MET" lines, without failing the suite; every other case must
// meet them all. A case listed here that meets them fails, so that the list
// stays exact.
void check_case(const test::RobotCase& c) {
  const test::ContactScene scene = test::contact_scene(c.layout, c.view);
  expect_every_part_seen(c, scene);
  const SceneSegmentation seg = robot_segmenter().segment(scene.cloud);
  expect_support_plane(seg, scene);  // a missing plane fails here; the truth below does not need it
  const std::vector<test::ObjectTruth> truths = test::object_truths(c.layout);
  const std::vector<const ObjectSegments*> matched = match_objects(seg, scene, truths);
  for (std::size_t k = 0; k < truths.size(); ++k) {
    if (matched[k] != nullptr) expect_object(matched[k]->object, truths[k], scene, tolerances(c.view));
  }
  expect_centroids_in_their_boxes(seg);
}

class RobotScene : public testing::TestWithParam<test::RobotCase> {};

TEST_P(RobotScene, MeetsTheRobotIssuesCriteria) {
  const test::RobotCase& c = GetParam();
  SCOPED_TRACE(c.name());
  check_case(c);
}

std::string case_name(const testing::TestParamInfo<test::RobotCase>& info) {
  std::string name;
  for (const char ch : info.param.name()) name += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(RobotBattery, RobotScene, testing::ValuesIn(test::robot_cases()), case_name);

// --- a handle under a rim hangs off it ----------------------------------------------------

// The object holding most of the points labelled exactly `label` (0: none
// does; the support and unlabelled points are no object).
std::uint32_t object_of_label(const SceneSegmentation& seg, const test::ContactScene& scene, std::uint32_t label) {
  std::map<std::uint32_t, std::size_t> votes;
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    const std::uint32_t id = seg.objects[i];
    if (scene.truth[i] == label && id != 0 && id != seg.support_id) ++votes[id];
  }
  const auto fewer = [](const auto& a, const auto& b) { return a.second < b.second; };
  const auto most = std::max_element(votes.begin(), votes.end(), fewer);
  return most == votes.end() ? 0 : most->first;
}

// The pan's handle meets the wall 3-15 mm under the rim, whose top faces up,
// and the wall's side of that junction lies higher than the handle's: the
// handle does not rest on the rim's face (a face bears what lies on it); it
// hangs off the wall and joins it. In every noise-free view the handle's
// object is no object of its own: it holds more of the pan's body than of the
// handle. (With Kinect noise the two sides' heights differ by less than the
// noise; printed, not checked. The pan's inner wall, standing on a floor 5 mm
// thick, is another matter: issue 33.)
TEST(RobotGrouping, APanHandleUnderTheRimIsOfThePan) {
  for (const test::ContactView& view : test::contact_views()) {
    const test::ContactScene scene = test::contact_scene(test::pan_with_a_long_handle(), view);
    const SceneSegmentation seg = robot_segmenter().segment(scene.cloud);
    const std::uint32_t handle = object_of_label(seg, scene, test::kHandleLabel);
    std::size_t body_points = 0, handle_points = 0;
    for (std::size_t i = 0; i < scene.truth.size(); ++i) {
      if (handle == 0 || seg.objects[i] != handle) continue;
      body_points += scene.truth[i] == test::kFirstObjectLabel;
      handle_points += scene.truth[i] == test::kHandleLabel;
    }
    std::printf("[robot] pan, %s: the handle's object %u holds %zu of its points and %zu of the body's\n",
                test::describe(view).c_str(), handle, handle_points, body_points);
    if (view.noisy) continue;
    EXPECT_NE(handle, 0u) << test::describe(view);
    EXPECT_GT(body_points, handle_points) << test::describe(view);
  }
}

// --- what stands behind a nearer box is not held by it ---------------------------------

// Box F (label 20), 6 cm wide, 5 cm deep and 12 cm tall, with `rear` (label 10
// and its parts) behind it: built facing -y, then turned to face the camera of
// the contact views (azimuth -70 deg), which see rear's middle hidden by F.
test::ContactLayout behind_a_box(const std::string& name, std::vector<test::ContactSolid> rear) {
  rear.push_back(test::box_solid({-0.03, -0.05, 0}, {0.03, 0, 0.12}, test::kSecondObjectLabel));
  return test::turned({name, rear, Eigen::Vector3d(0, 0.05, 0.05)}, 20);
}

// The share of the thing behind's points (label 10) in the box's object (20).
double held_by_the_box(const test::ContactLayout& layout, const test::ContactView& view) {
  const test::ContactScene scene = test::contact_scene(layout, view);
  const SceneSegmentation seg = robot_segmenter().segment(scene.cloud);
  const std::uint32_t box = id_holding_most(seg, scene, test::kSecondObjectLabel);
  EXPECT_NE(box, 0u);
  EXPECT_NE(box, seg.support_id);
  double held = 0, rear = 0;
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    const bool behind = of_object(scene.truth[i], test::kFirstObjectLabel);
    rear += behind, held += behind && seg.objects[i] == box;
  }
  std::printf("[robot] %s, %s: %.1f %% of it in the box's object\n", layout.name.c_str(),
              test::describe(view).c_str(), 100 * held / rear);
  return held / rear;
}

void expect_not_held_by_the_box(const test::ContactLayout& layout) {
  for (const test::ContactView& view : test::contact_views()) {
    if (!view.organized) continue;  // held_behind reads the image
    EXPECT_LT(held_by_the_box(layout, view), 0.05) << test::describe(view);
  }
}

// A part that touches nothing and vanishes behind a nearer body is held by it
// (a handle whose ends its mug hides; detail::held_behind) only if the sensor
// sees the support under it and it comes within a seed spacing of the body.
// A narrower box standing 1 cm behind a taller one shows its top alone: it
// touches nothing and vanishes behind the front box, 1 cm from it, but the
// front box hides the table under it too (it may stand on a foot of its own).
TEST(RobotHeldBehind, ABoxJustBehindATallerBoxIsNotHeldByIt) {
  const test::ContactSolid rear = test::box_solid({-0.025, 0.01, 0}, {0.025, 0.06, 0.16}, test::kFirstObjectLabel);
  expect_not_held_by_the_box(behind_a_box("a box 1 cm behind a taller box", {rear}));
}

// A bar 20 cm long, 4 to 7 cm above the table and 5 cm behind the box, on two
// posts the box hides: its ends hang in the air beside the box with the table
// seen under them, but 5 cm from it, farther than a seed spacing.
TEST(RobotHeldBehind, ABarOnHiddenPostsFarBehindABoxIsNotHeldByIt) {
  std::vector<test::ContactSolid> bar{
      test::box_solid({-0.10, 0.05, 0.04}, {0.10, 0.08, 0.07}, test::kFirstObjectLabel)};
  for (const double x : {-0.02, 0.015}) {
    bar.push_back(test::box_solid({x, 0.06, 0}, {x + 0.005, 0.07, 0.04}, test::kFirstObjectLabel + 1));
  }
  expect_not_held_by_the_box(behind_a_box("a bar on hidden posts 5 cm behind a box", bar));
}

// --- what ends against a box is not continued behind it --------------------------------

// A board 1 cm thick and 10 cm tall on the vertical plane through the line
// y = 0.8 x - 5 cm: from the point of that line at x = start, `length` along
// it (toward +x if positive).
test::ContactSolid board_on_the_line(double start, double length, std::uint32_t label) {
  test::ContactSolid board =
      test::box_solid({std::min(0.0, length), -0.005, 0}, {std::max(0.0, length), 0.005, 0.10}, label);
  board.rotation = test::yaw_matrix(std::atan(0.8) * 180 / std::numbers::pi);
  board.position = {start, 0.8 * start - 0.05, 0};
  return board;
}

// In every contact view: one object per name, the layout's solids 10, 20, ...
// (`names`, for the printed line, in that order) each mostly in one of them,
// no two in the same.
void expect_objects_apart(const test::ContactLayout& layout, const std::vector<const char*>& names,
                          bool with_noise = true) {
  for (const test::ContactView& view : test::contact_views()) {
    if (view.noisy && !with_noise) continue;
    const test::ContactScene scene = test::contact_scene(layout, view);
    const SceneSegmentation seg = robot_segmenter().segment(scene.cloud);
    std::printf("[robot] %s, %s: objects %u;", layout.name.c_str(), test::describe(view).c_str(), seg.object_count);
    std::set<std::uint32_t> ids;
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::uint32_t id = id_holding_most(seg, scene, static_cast<std::uint32_t>(10 * (k + 1)));
      std::printf(" %s in %u", names[k], id);
      ids.insert(id);
    }
    std::printf("\n");
    EXPECT_EQ(seg.object_count, names.size()) << test::describe(view);
    EXPECT_EQ(ids.size(), names.size()) << test::describe(view);
  }
}

// Box F (label 20), 6 cm wide, 5 cm deep and 12 cm tall, and two boards 15 cm
// long on one plane through it: P (10) ends against F's front face, Q (30)
// starts at its right face. Their faces continue one plane across F, and F
// hides the plane between them; but each board meets F with no jump in
// depth, so its end is no occlusion boundary: it ends against F
// (detail::hidden_continuations). Two boards, not one that F hides.
TEST(RobotHidden, TwoBoardsEndingAgainstABoxAreNotOneBoardBehindIt) {
  const test::ContactLayout layout{"two boards ending against a box",
                                   {test::box_solid({-0.03, -0.05, 0}, {0.03, 0, 0.12}, test::kSecondObjectLabel),
                                    board_on_the_line(0, -0.15, test::kFirstObjectLabel),
                                    board_on_the_line(0.03, 0.15, 30)},
                                   Eigen::Vector3d(0, -0.02, 0.05)};
  expect_objects_apart(layout, {"P", "F", "Q"});
}

// A box 8 cm tall (label 10) and one 20 cm tall (30), 10 cm wide each, side by
// side 4 cm apart with their fronts in one plane, behind box F (20) of
// behind_a_box, 12 cm tall, which hides the gap between them: their fronts
// continue one plane behind F, but one face through the low box's top and
// the tall box's would pass above F, where the sensor sees the table beyond
// (detail::hidden_continuations). Two boxes, not one.
TEST(RobotHidden, ATallAndALowBoxBehindOneNearerBoxAreTwoObjects) {
  const test::ContactLayout layout =
      behind_a_box("a tall and a low box behind a box",
                   {test::box_solid({-0.12, 0.02, 0}, {-0.02, 0.06, 0.08}, test::kFirstObjectLabel),
                    test::box_solid({0.02, 0.02, 0}, {0.12, 0.06, 0.20}, 30)});
  expect_objects_apart(layout, {"low box", "F", "tall box"});
}

// A box 12 x 12 x 4 cm (label 10) turned 45 deg, its near corner 1 cm behind
// box F (20), 6 cm wide and 20 cm tall, which hides that corner: the sensor
// sees the box's top left and right of F, each piece with one of the two
// front faces, which meet at 90 deg and continue nothing. The two pieces of
// the top are one face facing up at one height, and the sensor sees past no
// sample of that face's hull (F hides the rest of it): one box, and F
// (detail::hidden_continuations).
TEST(RobotHidden, ABoxWhoseNearCornerATallerBoxHidesIsOneObject) {
  test::ContactSolid rear = test::box_solid({-0.06, -0.06, 0}, {0.06, 0.06, 0.04}, test::kFirstObjectLabel);
  rear.rotation = test::yaw_matrix(45);
  rear.position = {0, 0.01 + 0.06 * std::numbers::sqrt2, 0};
  const test::ContactSolid front = test::box_solid({-0.03, -0.05, 0}, {0.03, 0, 0.20}, test::kSecondObjectLabel);
  const test::ContactLayout layout{"a box whose near corner a taller box hides", {rear, front}, {0, 0.05, 0.05}};
  expect_objects_apart(test::turned(layout, 20), {"box", "F"});
}

// Two boxes of one height, 6 cm, 12 cm wide each, 4 cm apart behind box F of
// behind_a_box, which hides the gap between them; the right one stands 4 cm
// farther back. Their tops are one plane at one height, and F hides the
// segment between them; but the hull of the two tops reaches behind the left
// box, where the sensor sees the table beyond (detail::hidden_continuations).
// Two boxes, not one.
TEST(RobotHidden, TwoBoxesOfOneHeightBehindOneNearerBoxAreTwoObjects) {
  const test::ContactLayout layout =
      behind_a_box("two boxes of one height behind a box",
                   {test::box_solid({-0.14, 0.01, 0}, {-0.02, 0.07, 0.06}, test::kFirstObjectLabel),
                    test::box_solid({0.02, 0.05, 0}, {0.14, 0.11, 0.06}, 30)});
  expect_objects_apart(layout, {"left box", "F", "right box"});
}

// --- a container's inside seen over its rim ------------------------------------------

// A pot 16 cm across and 8 cm tall, its wall 4 mm thick (label 10): P1 cuts its
// inside (the far inner wall, seen over the rim) from its outside at the rim,
// where the two faces of the wall meet at nearly opposite normals. In every
// organized view the object that holds most of the pot holds at least 90 % of
// the pot's points in any object (detail::seen_over_rims; 51-56 % without
// it). Unorganized clouds have no image: the rule does not apply there.
TEST(RobotContainer, APotsInsideSeenOverItsRimIsOneObjectWithIt) {
  test::ContactSolid pot;
  pot.shape = test::ContactSolid::Shape::cup;
  pot.radius_m = 0.08, pot.inner_radius_m = 0.076, pot.height_m = 0.08, pot.bottom_m = 0.005;
  pot.label = test::kFirstObjectLabel;
  const test::ContactLayout layout{"a pot", {pot}, {0, 0, 0.04}};
  for (const test::ContactView& view : test::contact_views()) {
    if (!view.organized) continue;
    const test::ContactScene scene = test::contact_scene(layout, view);
    const SceneSegmentation seg = robot_segmenter().segment(scene.cloud);
    const std::uint32_t main = id_holding_most(seg, scene, test::kFirstObjectLabel);
    double in_main = 0, in_objects = 0;
    for (std::size_t i = 0; i < scene.truth.size(); ++i) {
      if (scene.truth[i] != test::kFirstObjectLabel || seg.objects[i] == 0 || seg.objects[i] == seg.support_id) continue;
      in_objects += 1, in_main += seg.objects[i] == main;
    }
    std::printf("[robot] a pot, %s: objects %u, %.1f %% of its points in objects in the main one\n",
                test::describe(view).c_str(), seg.object_count, 100 * in_main / in_objects);
    EXPECT_GE(in_main, 0.9 * in_objects) << test::describe(view);
  }
}

// Two boxes 10 x 6 x 12 cm, one 10 cm behind the other: the sensor sees the rear
// box's front face over the front box's top, below that top, and the two tops
// are at one height, as a pot's far inner wall is seen over its rim. But the
// front box's points along that border lie on its top face, which faces up:
// the edge of a top face, not a wall's rim. Two objects.
TEST(RobotContainer, ABoxSeenOverAnEqualBoxInFrontIsNotItsInside) {
  const test::ContactSolid front = test::box_solid({-0.05, -0.06, 0}, {0.05, 0, 0.12}, test::kSecondObjectLabel);
  const test::ContactSolid rear = test::box_solid({-0.05, 0.10, 0}, {0.05, 0.16, 0.12}, test::kFirstObjectLabel);
  const test::ContactLayout layout{"a box 10 cm behind an equal box", {rear, front}, {0, 0.05, 0.06}};
  expect_objects_apart(test::turned(layout, 20), {"rear box", "front box"});
}

// Two boxes, 6 x 10 x 12 cm and 6 x 8 x 9 cm, touching face to face on a board
// 6 mm thick (label 30), a tray: neither meets the support, both stand on a
// floor raised off it, as a pan's far inner wall does; but they meet along
// their sides, not at a rim at the top of both with their tops at one height
// (join_inner_walls). Two objects; the board, flat, is none. Noise-free views:
// with the Kinect noise model, seen from 45 deg, P1 makes the two boxes one
// part, before any grouping (perf/RESULTS.md, "Session of 2026-12-07 06:56").
TEST(RobotContainer, TwoBoxesTouchingOnATrayAreTwoObjects) {
  constexpr double kBoard = 0.006;
  const test::ContactLayout layout{"two boxes touching on a tray",
                                   {test::box_solid({-0.06, -0.05, kBoard}, {0, 0.05, kBoard + 0.12},
                                                    test::kFirstObjectLabel),
                                    test::box_solid({0, -0.04, kBoard}, {0.06, 0.04, kBoard + 0.09},
                                                    test::kSecondObjectLabel),
                                    test::box_solid({-0.15, -0.12, 0}, {0.15, 0.12, kBoard}, 30)},
                                   Eigen::Vector3d(0, 0, 0.04)};
  expect_objects_apart(test::turned(layout, -20), {"A", "B"}, false);
}

// --- the truth itself, against hand computations ---------------------------------------

// A box's footprint is the box: B of the first scene, 6 x 15 x 7 cm yawed by 30
// deg, has its longer side (own y) at 120 deg; a can on its side at 30 deg is
// 12 cm along its axis, 6.6 cm across and 6.6 cm high.
TEST(RobotBatteryTruth, BoxesAndCansMeasureTheirOwnSize) {
  const test::ObjectTruth b = test::object_truths(test::two_boxes_apart())[1];
  EXPECT_NEAR((b.extents - Eigen::Vector3d(0.15, 0.06, 0.07)).norm(), 0, 1e-9);
  ASSERT_EQ(b.longer_sides.size(), 1u);
  const double c30 = std::cos(test::deg2rad(30)), s30 = std::sin(test::deg2rad(30));
  EXPECT_LT(line_angle_deg(b.longer_sides[0].cast<float>(), {-s30, c30, 0}), 1e-3);
  const test::ObjectTruth can = test::object_truths(test::can_lying(30))[0];
  EXPECT_NEAR((can.extents - Eigen::Vector3d(0.12, 0.066, 0.066)).norm(), 0, 1e-9);
  ASSERT_EQ(can.longer_sides.size(), 1u);
  EXPECT_LT(line_angle_deg(can.longer_sides[0].cast<float>(), {c30, s30, 0}), 1e-3);
  // Box B on box A: the truth's height is B's own, 6 cm, from A's top at 8 cm.
  EXPECT_NEAR(test::object_truths(test::box_on_a_box())[1].extents.z(), 0.06, 1e-12);
  EXPECT_NEAR(test::object_truths(test::box_on_a_box())[1].lowest, 0.08, 1e-12);
}

// A round body of radius R with a handle on one side: the minimum-area
// rectangle is not the one along the handle. The handle's tip: the corners
// (r, +-w) in plan, rounded by rho (a tube's radius). Turned by t, the side
// along the handle, r cos t + w sin t + rho + R, shrinks, while the side across
// stays 2 R until the tip passes the body, r sin t + w cos t + rho = R: the
// minimum is there, at +t and at its mirror image -t.
void expect_tilted_footprint(const test::ObjectTruth& t, double body_r, double reach, double half_width, double rho) {
  const double phi = std::atan2(half_width, reach);  // r sin t + w cos t = hypot(r, w) sin(t + phi)
  const double tilt = std::asin((body_r - rho) / std::hypot(reach, half_width)) - phi;
  const double longer = reach * std::cos(tilt) + half_width * std::sin(tilt) + rho + body_r;
  std::printf("[robot] truth: footprint %.1f x %.1f mm, its longer side at +-%.2f deg "
              "(along the handle: %.1f x %.1f)\n",
              1000 * t.extents.x(), 1000 * t.extents.y(), test::rad2deg(tilt), 1000 * (reach + rho + body_r),
              2000 * body_r);
  EXPECT_NEAR(t.extents.x(), longer, 1e-4);
  EXPECT_NEAR(t.extents.y(), 2 * body_r, 1e-4);  // the 0.05 deg grid misses the kink by a hair
  ASSERT_EQ(t.longer_sides.size(), 2u);
  for (const double sign : {1.0, -1.0}) {
    const Eigen::Vector3d side(std::cos(sign * tilt), std::sin(sign * tilt), 0);
    double angle = 180;
    for (const Eigen::Vector3d& s : t.longer_sides) angle = std::min(angle, line_angle_deg(s.cast<float>(), side));
    EXPECT_LT(angle, 0.1) << "sign " << sign;
  }
}

TEST(RobotBatteryTruth, AHandleTiltsTheMinimumRectangle) {
  namespace s = synthetic::detail;
  // The mug: the handle's centre line reaches x = 4.5 + 0.2 + 3 cm (scene_layout.cpp's
  // kHandleCentreX plus the arc), a tube of 5 mm radius; 10 cm high.
  const test::ObjectTruth mug = test::object_truths(test::mug_upright())[0];
  expect_tilted_footprint(mug, s::kMugOuterRadiusM, s::kMugOuterRadiusM + 0.002 + s::kHandleArcRadiusM, 0,
                          s::kHandleTubeRadiusM);
  EXPECT_NEAR(mug.extents.z(), s::kMugHeightM, 1e-12);
  // The pan: the handle's far corners at x = 28 cm, y = +-1.25 cm; the pan 5 cm high.
  const test::ObjectTruth pan = test::object_truths(test::pan_with_a_long_handle())[0];
  expect_tilted_footprint(pan, 0.10, 0.28, 0.0125, 0);
  EXPECT_NEAR(pan.extents.z(), 0.05, 1e-12);
}

// The true plane in the camera frame: every noise-free plane point on it.
TEST(RobotBatteryTruth, ThePlaneNormalInTheCameraFrame) {
  const test::ContactScene scene = test::contact_scene(test::two_boxes_apart(), test::ContactView{});
  const Eigen::Vector3d n = in_camera(scene, Eigen::Vector3d::UnitZ());
  const double d = -n.dot(scene.camera_from_world.t);
  EXPECT_GT(d, 0);  // the sensor above the plane: the normal points toward it
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    if (scene.truth[i] == test::kContactPlaneLabel) {
      ASSERT_NEAR(n.dot(scene.cloud.points[i].cast<double>()) + d, 0, 1e-5) << "point " << i;
    }
  }
}

}  // namespace
}  // namespace lccp
