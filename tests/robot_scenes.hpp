#pragma once
// The robot battery's scenes (robot_battery_test.cpp): objects a robot meets on
// a table, built from the contact machinery (contact_scenes.hpp,
// contact_clutter.hpp) on the plane z = 0, world z up, ground truth in mOSD's
// convention (1 the plane, n * 10 + k part k of object n). And what each object
// truly measures, from its solids alone (hidden faces included): the
// minimum-area rectangle of its footprint on the plane, longer side first, and
// its own height.
//
// The truth is exact: a solid's extent along a direction is its support
// function h(u) = max over the solid of u . p, known in closed form for every
// shape used here (a box: its corners; a cylinder or cup: its two end discs; a
// tube: its centre line's points plus the tube radius, the capsules' union).
// The footprint rectangle at angle t has the sides h(u) + h(-u) and h(v) +
// h(-v) (u = (cos t, sin t, 0), v = u turned by 90 deg); t is brute-forced over
// [0, 180) deg in 0.05 deg steps.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "../src/synthetic/scene_layout.hpp"
#include "contact_clutter.hpp"
#include "contact_scenes.hpp"

namespace lccp::test {

// --- truth: support functions and the footprint rectangle ---------------------------

// h(u) of one solid, u a unit world direction. A cap (not used by the battery)
// gives NaN, so that any truth built on it fails loudly rather than quietly.
inline double solid_support(const ContactSolid& s, const Eigen::Vector3d& u) {
  const auto world = [&s](const Eigen::Vector3d& p) { return Eigen::Vector3d(s.rotation * p + s.position); };
  double h = -std::numeric_limits<double>::infinity();
  switch (s.shape) {
    case ContactSolid::Shape::box:
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d corner(c & 1 ? s.hi.x() : s.lo.x(), c & 2 ? s.hi.y() : s.lo.y(),
                                     c & 4 ? s.hi.z() : s.lo.z());
        h = std::max(h, u.dot(world(corner)));
      }
      return h;
    case ContactSolid::Shape::cylinder:
    case ContactSolid::Shape::cup: {  // the hull of its end discs: radius times u's part across the axis
      const double across = std::sqrt(std::max(0.0, 1 - std::pow(u.dot(s.rotation.col(2)), 2)));
      for (const double z : {0.0, s.height_m}) h = std::max(h, u.dot(world({0, 0, z})) + s.radius_m * across);
      return h;
    }
    case ContactSolid::Shape::tube:
      for (const Eigen::Vector3d& p : s.centre_line) h = std::max(h, u.dot(world(p)) + s.radius_m);
      return h;
    case ContactSolid::Shape::cap: break;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// h(u) of the union of solids: the largest of theirs.
inline double support(const std::vector<ContactSolid>& solids, const Eigen::Vector3d& u) {
  double h = -std::numeric_limits<double>::infinity();
  for (const ContactSolid& s : solids) h = std::max(h, solid_support(s, u));
  return h;
}

// What an object (all its solids) truly measures on the plane z = 0.
struct ObjectTruth {
  std::uint32_t object = 0;                // mOSD object label n * 10
  std::vector<ContactSolid> solids;        // its parts
  Eigen::Vector3d extents = Eigen::Vector3d::Zero();  // footprint rectangle longer, shorter side; top above the plane
  // The world directions (z = 0) of the rectangle's longer side: more than one
  // when mirror-image rectangles share the minimum area (a footprint
  // symmetric about a line, as the mug's and the pan's about their handle's).
  std::vector<Eigen::Vector3d> longer_sides;
  double area = 0;                         // the rectangle's, m^2
  double lowest = 0;                       // its lowest point above the plane: 0 standing on it
  // Sides less than 10 % apart: a round or square footprint, whose longer side
  // (the box's first axis) is as good as undefined.
  bool direction_defined() const { return extents.x() - extents.y() >= 0.1 * extents.x(); }
};

inline constexpr double kFootprintStepDeg = 0.05;
// Rectangles whose area is within this share of the smallest are the same
// minimum (mirror images; the grid meets both kinks alike).
inline constexpr double kSameAreaShare = 1e-6;
// Longer sides closer than 0.5 deg are the same line (cos 0.5 deg).
inline constexpr double kSameLineCos = 0.99996192306;

// The footprint rectangle's sides at angle t (deg): along u and along u turned by 90 deg.
inline Eigen::Vector2d footprint_sides(const std::vector<ContactSolid>& solids, double t_deg) {
  const double t = deg2rad(t_deg);
  const Eigen::Vector3d u(std::cos(t), std::sin(t), 0), v(-std::sin(t), std::cos(t), 0);
  return {support(solids, u) + support(solids, -u), support(solids, v) + support(solids, -v)};
}

inline ObjectTruth object_truth(std::uint32_t object, const std::vector<ContactSolid>& solids) {
  ObjectTruth truth{object, solids, Eigen::Vector3d::Zero(), {}, std::numeric_limits<double>::infinity()};
  const int steps = static_cast<int>(std::lround(180.0 / kFootprintStepDeg));
  std::vector<double> areas(static_cast<std::size_t>(steps));
  for (int k = 0; k < steps; ++k) {
    const Eigen::Vector2d sides = footprint_sides(solids, k * kFootprintStepDeg);
    areas[static_cast<std::size_t>(k)] = sides.prod();
    truth.area = std::min(truth.area, sides.prod());
  }
  for (int k = 0; k < steps; ++k) {
    if (areas[static_cast<std::size_t>(k)] > truth.area * (1 + kSameAreaShare)) continue;
    const double t = deg2rad(k * kFootprintStepDeg);
    const Eigen::Vector2d sides = footprint_sides(solids, k * kFootprintStepDeg);
    const Eigen::Vector3d u(std::cos(t), std::sin(t), 0), v(-std::sin(t), std::cos(t), 0);
    const Eigen::Vector3d side = sides.x() >= sides.y() ? u : v;
    // Every rectangle comes round twice in 180 deg (turned by 90 deg, its sides swap): keep one of each.
    const auto same_line = [&side](const Eigen::Vector3d& s) { return std::abs(s.dot(side)) > kSameLineCos; };
    if (std::none_of(truth.longer_sides.begin(), truth.longer_sides.end(), same_line)) {
      truth.longer_sides.push_back(side);
    }
    truth.extents.head<2>() = Eigen::Vector2d(sides.maxCoeff(), sides.minCoeff());
  }
  // Its own height: from its lowest point up (an object resting on another's
  // top is boxed from its own bottom, not through the object under it).
  truth.lowest = -support(solids, -Eigen::Vector3d::UnitZ());
  truth.extents.z() = support(solids, Eigen::Vector3d::UnitZ()) - truth.lowest;  // the plane is z = 0
  return truth;
}

// Every object of a layout (solids grouped by label / 10), ascending label.
inline std::vector<ObjectTruth> object_truths(const ContactLayout& layout) {
  std::set<std::uint32_t> objects;
  for (const ContactSolid& s : layout.solids) objects.insert(s.label / 10 * 10);
  std::vector<ObjectTruth> truths;
  for (const std::uint32_t object : objects) {
    std::vector<ContactSolid> solids;
    for (const ContactSolid& s : layout.solids) {
      if (s.label / 10 * 10 == object) solids.push_back(s);
    }
    truths.push_back(object_truth(object, solids));
  }
  return truths;
}

// --- the scenes -----------------------------------------------------------------------

// The camera looks at the middle of the solids' bounding box in plan, a third
// of their height up.
inline ContactLayout aimed_at_the_middle(ContactLayout layout) {
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY();
  const auto& s = layout.solids;
  layout.target = {(support(s, x) - support(s, -x)) / 2, (support(s, y) - support(s, -y)) / 2,
                   support(s, Eigen::Vector3d::UnitZ()) / 3};
  return layout;
}

// 1. Box A (label 10), 10 x 8 x 12 cm, on x in [-10, 0] cm, and box B (label
// 20), 6 x 15 x 7 cm, yawed by 30 deg, both centred on y = 0. Yawed, B shows A
// a vertical edge, not a face: the 21 cm gap is the clearance along x from A's
// +x face to B's nearest edge (B's half extent along x: 3 cos 30 + 7.5 sin 30 cm).
inline ContactLayout two_boxes_apart() {
  constexpr double kGap = 0.21;
  const double half_b = 0.03 * std::cos(deg2rad(30)) + 0.075 * std::sin(deg2rad(30));
  ContactLayout layout;
  layout.name = "two boxes 21 cm apart";
  layout.solids = {box_solid({-0.10, -0.04, 0}, {0, 0.04, 0.12}, kFirstObjectLabel),
                   box_solid({-0.03, -0.075, 0}, {0.03, 0.075, 0.07}, kSecondObjectLabel)};
  layout.solids[1].rotation = yaw_matrix(30);
  layout.solids[1].position = {kGap + half_b, 0, 0};
  return aimed_at_the_middle(layout);
}

// 2. Two boxes face to face (contact_clutter.hpp): A 6 x 10 x 12 cm, B 6 x 8 x 9 cm.
inline ContactLayout two_boxes_touching() {
  return aimed_at_the_middle(boxes_face_to_face(0.06, 0.10, 0.12, 0.08, 0.09));
}

// 3. Box A (label 10), 14 x 12 x 8 cm, on the plane at the origin; box B (label
// 20), 8 x 7 x 6 cm, standing on A's top, centred on it, yawed by 15 deg
// against A: two objects, B resting on A alone. B's true height, as the issue
// states it for every object (its top above the plane), is 14 cm, not its own 6 cm.
inline ContactLayout box_on_a_box() {
  ContactLayout layout;
  layout.name = "box on a box, yawed 15 deg";
  layout.solids = {box_solid({-0.07, -0.06, 0}, {0.07, 0.06, 0.08}, kFirstObjectLabel),
                   box_solid({-0.04, -0.035, 0}, {0.04, 0.035, 0.06}, kSecondObjectLabel)};
  layout.solids[1].rotation = yaw_matrix(15);
  layout.solids[1].position = {0, 0, 0.08};
  return aimed_at_the_middle(layout);
}

// 4. The synthetic scene's mug (scene_layout.hpp, built as mug_on_its_side
// builds it) upright at the origin in its own frame: body label 10, handle 11
// (a tube in the mug's x-z plane, toward +x: sideways to the default view,
// which looks along +y, 20 deg toward -x).
inline ContactLayout mug_upright() {
  namespace s = synthetic::detail;
  ContactSolid body;
  body.shape = ContactSolid::Shape::cup;
  body.radius_m = s::kMugOuterRadiusM, body.inner_radius_m = s::kMugInnerRadiusM;
  body.height_m = s::kMugHeightM, body.bottom_m = s::kMugBottomM, body.label = kFirstObjectLabel;
  ContactSolid handle;
  handle.shape = ContactSolid::Shape::tube;
  handle.radius_m = s::kHandleTubeRadiusM, handle.label = kHandleLabel;
  const auto line = s::handle_centre_line();
  handle.centre_line.assign(line.begin(), line.end());
  return aimed_at_the_middle({"mug upright, handle toward +x", {body, handle}, Eigen::Vector3d::Zero()});
}

// 5. A pan: a cup of outer radius 10 cm, inner 9.5 cm, 5 cm high with a 5 mm
// bottom (label 10), and a handle (label 11), a box 18 cm long, 2.5 cm wide,
// 1.2 cm thick, out of its wall along +x (x from 9.9 to 28 cm: 1 mm into the
// wall; z from 3.5 to 4.7 cm: clear of the plane): one object.
inline ContactLayout pan_with_a_long_handle() {
  ContactSolid pan;
  pan.shape = ContactSolid::Shape::cup;
  pan.radius_m = 0.10, pan.inner_radius_m = 0.095, pan.height_m = 0.05, pan.bottom_m = 0.005;
  pan.label = kFirstObjectLabel;
  const ContactSolid handle = box_solid({0.099, -0.0125, 0.035}, {0.28, 0.0125, 0.047}, kHandleLabel);
  return aimed_at_the_middle({"pan with a long handle toward +x", {pan, handle}, Eigen::Vector3d::Zero()});
}

// 6. A can on its side (contact_clutter.hpp), its ends edge-on (30 deg) or one in view (-20 deg).
inline ContactLayout can_lying(double yaw_deg) { return aimed_at_the_middle(can_on_its_side(yaw_deg)); }

inline std::vector<ContactLayout> robot_scenes() {
  return {two_boxes_apart(), two_boxes_touching(),  box_on_a_box(), mug_upright(),
          pan_with_a_long_handle(), can_lying(30), can_lying(-20)};
}

// One case of the battery: a scene seen from one view.
struct RobotCase {
  ContactLayout layout;
  ContactView view;
  std::string name() const { return layout.name + ", " + describe(view); }
};

inline void PrintTo(const RobotCase& c, std::ostream* os) { *os << c.name(); }

// Every scene from each of the eight contact views.
inline std::vector<RobotCase> robot_cases() {
  std::vector<RobotCase> cases;
  for (const ContactLayout& layout : robot_scenes()) {
    for (const ContactView& view : contact_views()) cases.push_back({layout, view});
  }
  return cases;
}

}  // namespace lccp::test
