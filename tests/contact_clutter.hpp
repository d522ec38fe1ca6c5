#pragma once
// Several objects on the plane of contact_scenes.hpp, touching the plane and
// each other as real clutter does (no gaps: touching solids share a face, a
// line or a point exactly), with their ground truth in mOSD's convention (1
// the plane, 10, 20, ... the objects, 11 a mug's handle); and the verdict on a
// segmentation of any contact scene: is an object lost into the plane, merged
// with its neighbour, or does it stand apart.
//
// The default view (ContactView: 0.9 m away, azimuth -70 deg) looks along
// +y and a little toward -x; the two-box layouts are built in their own frame
// and turned by -20 deg about z, so that the camera sees their fronts (-y) and
// their +x sides, 40 and 50 deg off their normals in plan.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "../src/synthetic/scene_layout.hpp"
#include "contact_scenes.hpp"
#include "lccp/metrics/scores.hpp"

namespace lccp::test {

inline constexpr std::uint32_t kFirstObjectLabel = 10, kSecondObjectLabel = 20, kHandleLabel = 11;

inline Eigen::Matrix3d yaw_matrix(double yaw_deg) {
  return Eigen::AngleAxisd(deg2rad(yaw_deg), Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

inline ContactSolid box_solid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::uint32_t label) {
  ContactSolid s;
  s.lo = lo, s.hi = hi, s.label = label;
  return s;
}

// The whole layout turned by `yaw_deg` about the world z axis.
inline ContactLayout turned(ContactLayout layout, double yaw_deg) {
  const Eigen::Matrix3d R = yaw_matrix(yaw_deg);
  for (ContactSolid& s : layout.solids) s.rotation = R * s.rotation, s.position = R * s.position;
  layout.target = R * layout.target;
  return layout;
}

inline std::string cm(double m) { return std::to_string(int(std::lround(m * 100))); }

// Box A (label 10), width x depth_a x height_a, on x in [-width, 0], and box B
// (label 20), width x depth_b x height_b, on x in [0, width]: A's +x face and
// B's -x face touch over the smaller of the two, both centred on y = 0. Where
// one box is deeper its front stands (depth_a - depth_b) / 2 proud of the
// other's, a strip of its side showing beside the other's front; where one is
// taller its side shows above the other's top. Turned by -20 deg (file
// comment); the camera looks at the middle of the shared face, a sixth of the
// summed heights up.
inline ContactLayout boxes_face_to_face(double width, double depth_a, double height_a, double depth_b,
                                        double height_b) {
  ContactLayout layout;
  layout.name = "boxes face to face " + cm(width) + " cm, A " + cm(depth_a) + "x" + cm(height_a) + " B " +
                cm(depth_b) + "x" + cm(height_b);
  layout.solids = {box_solid({-width, -depth_a / 2, 0}, {0, depth_a / 2, height_a}, kFirstObjectLabel),
                   box_solid({0, -depth_b / 2, 0}, {width, depth_b / 2, height_b}, kSecondObjectLabel)};
  layout.target = {0, 0, (height_a + height_b) / 6};
  return turned(layout, -20);
}

// Box A (label 10), 10 x 12 x 16 cm (x, y, z), on x in [-10, 0] cm, and box B
// (label 20), 3 x 10 x 15 cm, a book-like slab tilted by `lean_deg` from the
// vertical toward A: B's own x, y, z axes are world (cos l, 0, sin l), y and
// (-sin l, 0, cos l). B rests on the plane along its bottom edge (own x = z =
// 0), at x = 15 sin l, and its top edge (own x = 0, z = 15 cm) lies against
// A's +x face at x = 0, 15 cos l above the plane (below A's top for any lean
// up to 90 deg). Centred on y = 0, A 1 cm wider than B on either side. Turned
// by -20 deg (file comment).
inline ContactLayout box_leaning_on_a_box(double lean_deg) {
  constexpr double kThickness = 0.03, kDepth = 0.10, kLength = 0.15;
  ContactLayout layout;
  layout.name = "box leaning on a box, " + std::to_string(int(std::lround(lean_deg))) + " deg";
  layout.solids = {box_solid({-0.10, -0.06, 0}, {0, 0.06, 0.16}, kFirstObjectLabel),
                   box_solid({0, -kDepth / 2, 0}, {kThickness, kDepth / 2, kLength}, kSecondObjectLabel)};
  ContactSolid& leaning = layout.solids.back();
  leaning.rotation = Eigen::AngleAxisd(-deg2rad(lean_deg), Eigen::Vector3d::UnitY()).toRotationMatrix();
  leaning.position = {kLength * std::sin(deg2rad(lean_deg)), 0, 0};
  layout.target = {0.02, 0, 0.05};
  return turned(layout, -20);
}

// A solid lying on its side: its own z axis (the cylinder's) horizontal at
// `yaw_deg` from world +x, its own x axis straight up, so a body of radius r
// about that axis touches the plane along the line below it; centred on the
// origin along its `length`.
inline void lay_on_side(ContactSolid& s, double radius, double length, double yaw_deg) {
  const Eigen::Vector3d axis = yaw_matrix(yaw_deg) * Eigen::Vector3d::UnitX();
  s.rotation.col(0) = Eigen::Vector3d::UnitZ();
  s.rotation.col(1) = axis.cross(Eigen::Vector3d::UnitZ());
  s.rotation.col(2) = axis;
  s.position = Eigen::Vector3d(0, 0, radius) - length / 2 * axis;
}

// A can on its side (label 10): a solid cylinder of radius 3.3 cm and length
// 12 cm, touching the plane along a line, its axis at `yaw_deg`: at 30 deg its
// flat ends are turned 80 deg from the line of sight in plan (edge-on, out of
// view), at -20 deg one end faces the camera, 50 deg off in plan, and meets
// the plane at one point.
inline ContactLayout can_on_its_side(double yaw_deg) {
  ContactSolid can;
  can.shape = ContactSolid::Shape::cylinder;
  can.radius_m = 0.033, can.height_m = 0.12, can.label = kFirstObjectLabel;
  lay_on_side(can, can.radius_m, can.height_m, yaw_deg);
  const bool end_in_view = std::abs(std::cos(deg2rad(yaw_deg + 70))) > std::cos(deg2rad(75));
  return {std::string("can on its side r 3.3 cm, ") + (end_in_view ? "an end in view" : "ends edge-on"),
          {can},
          Eigen::Vector3d(0, 0, 0.02)};
}

// The synthetic table-top scene's mug (src/synthetic/scene_layout.hpp: outer
// radius 4.5 cm, inner 3.9 cm, 10 cm long, 8 mm bottom; a handle of 5 mm tube
// bent on a 3 cm arc) on its side: body label 10, handle 11 (one object, two
// parts). The body touches the plane along a line; the handle points straight
// up. The opening faces yaw `yaw_deg`: toward the camera (-20 deg: 50 deg off
// the line of sight in plan, its inside in view) or away from it.
inline ContactLayout mug_on_its_side(double yaw_deg) {
  namespace s = synthetic::detail;
  ContactSolid body;
  body.shape = ContactSolid::Shape::cup;
  body.radius_m = s::kMugOuterRadiusM, body.inner_radius_m = s::kMugInnerRadiusM;
  body.height_m = s::kMugHeightM, body.bottom_m = s::kMugBottomM, body.label = kFirstObjectLabel;
  lay_on_side(body, body.radius_m, body.height_m, yaw_deg);
  ContactSolid handle = body;
  handle.shape = ContactSolid::Shape::tube;
  handle.radius_m = s::kHandleTubeRadiusM, handle.label = kHandleLabel;
  const auto line = s::handle_centre_line();
  handle.centre_line.assign(line.begin(), line.end());
  const bool toward = std::cos(deg2rad(yaw_deg + 70)) > 0;  // the opening in plan, against the view's azimuth
  return {std::string("mug on its side, opening ") + (toward ? "toward" : "away from") + " the camera",
          {body, handle},
          Eigen::Vector3d(0, 0, 0.03)};
}

// Objects touching each other on the plane: two boxes face to face, 2 to 10 cm
// wide, A 2 cm deeper (1 cm proud in front) and 3 cm taller than B, or 2 cm
// deeper and 1 cm taller (offset by 1 cm only in front and on top, as
// box_scene.hpp's two_touching_boxes), or the taller, deeper box behind (A's
// top runs into B's side, out of view); a box leaning on a box, steeply (10
// deg) and at 25 deg; a can and a mug on their sides.
inline std::vector<ContactLayout> contact_clutter() {
  std::vector<ContactLayout> layouts;
  for (const double width : {0.02, 0.04, 0.06, 0.10}) {
    layouts.push_back(boxes_face_to_face(width, 0.10, 0.12, 0.08, 0.09));
    layouts.push_back(boxes_face_to_face(width, 0.09, 0.10, 0.07, 0.09));
  }
  layouts.push_back(boxes_face_to_face(0.04, 0.08, 0.09, 0.10, 0.12));
  for (const ContactLayout& l : {box_leaning_on_a_box(10), box_leaning_on_a_box(25), can_on_its_side(30),
                                 can_on_its_side(-20), mug_on_its_side(-20), mug_on_its_side(160)}) {
    layouts.push_back(l);
  }
  return layouts;
}

// Every scene of the battery: one object on the plane (contact_objects), then clutter.
inline std::vector<ContactLayout> contact_battery_layouts() {
  std::vector<ContactLayout> layouts;
  for (const ContactObject& o : contact_objects()) layouts.push_back(contact_layout(o));
  for (ContactLayout& l : contact_clutter()) layouts.push_back(std::move(l));
  return layouts;
}

// How an object fares in a segmentation: its best segment (the one holding
// most of it, S_i of the paper's eq. 7) and what share of that segment it is.
struct ObjectShare {
  std::uint32_t object = 0;    // object label, n * 10
  double share = 0;            // |G ∩ S| / |S|, S's finite points of any label
  std::uint32_t dominant = 0;  // the label (plane 1, or an object) with most points in S
  double coverage = 0;         // |G ∩ S| / |G|: the object's share in its best segment
  double with_plane = 0;       // the object's share in the plane's best segment
  double overlap = 0;          // OV: the largest IoU of the object with a segment (the paper's eq. 6, one object)
};

struct ContactVerdict {
  double weighted_overlap = 0;        // WOv, objects only (score_objects, ground truth 0-9 ignored)
  std::vector<std::uint32_t> lost;    // objects lost into the plane
  std::vector<ObjectShare> objects;   // ascending object label
  // Not lost, WOv >= 0.8 for the scene and for every object on its own (its
  // OV), and every object's best segment mostly that object.
  bool held() const {
    bool apart = lost.empty() && weighted_overlap >= 0.8;
    for (const ObjectShare& o : objects) apart = apart && o.overlap >= 0.8 && o.share > 0.5;
    return apart;
  }
  // "" when held; else what failed and where every object went, e.g. "WOv
  // 0.52; 10 in 20's segment; 10: 38 % of a segment, 55 % of 10 in it, 0 % with
  // the plane; 20: ...".
  std::string failures() const {
    if (held()) return "";
    std::ostringstream out;
    out.precision(3);
    out << "WOv " << weighted_overlap;
    for (const std::uint32_t l : lost) out << "; " << l << " lost into the plane";
    for (const ObjectShare& o : objects) {
      if (o.share <= 0.5) out << "; " << o.object << " in " << o.dominant << "'s segment";
    }
    for (const ObjectShare& o : objects) {
      out << "; " << o.object << ": OV " << o.overlap << ", " << std::lround(100 * o.share) << " % of a segment, "
          << std::lround(100 * o.coverage)
          << " % of " << o.object << " in it, " << std::lround(100 * o.with_plane) << " % with the plane";
    }
    return out.str();
  }
};

namespace detail {

// Per object label: points per segment; per segment: points per label (finite points).
struct ContactTally {
  std::map<std::uint32_t, std::map<std::uint32_t, std::uint64_t>> object_segments, segment_labels;
};

inline ContactTally tally(const Labels& predicted, const Labels& object_truth) {
  ContactTally t;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    if (object_truth[i] == 0) continue;  // no return
    ++t.segment_labels[predicted[i]][object_truth[i]];
    if (object_truth[i] >= kLabelsPerObject) ++t.object_segments[object_truth[i]][predicted[i]];
  }
  return t;
}

// The segment holding most points of `label` (ties: the smaller segment label, as score_objects).
inline std::uint32_t best_segment(std::uint32_t label, const ContactTally& t) {
  std::uint32_t best = 0;
  std::uint64_t most = 0;
  for (const auto& [segment, labels] : t.segment_labels) {
    const auto it = labels.find(label);
    if (it != labels.end() && it->second > most) best = segment, most = it->second;
  }
  return best;
}

inline ObjectShare share_of(std::uint32_t object, const std::map<std::uint32_t, std::uint64_t>& segments,
                            const ContactTally& t) {
  const std::uint32_t best = best_segment(object, t), plane = best_segment(kContactPlaneLabel, t);
  std::uint64_t size = 0, dominant_count = 0, total = 0;
  ObjectShare o{object, 0, 0, 0, 0, 0};
  for (const auto& [label, count] : t.segment_labels.at(best)) {
    size += count;
    if (count > dominant_count) o.dominant = label, dominant_count = count;
  }
  for (const auto& [segment, count] : segments) total += count;
  for (const auto& [segment, count] : segments) {
    std::uint64_t segment_size = 0;
    for (const auto& [label, n] : t.segment_labels.at(segment)) segment_size += n;
    o.overlap = std::max(o.overlap, double(count) / double(total + segment_size - count));
  }
  const auto in_plane = segments.find(plane);
  o.share = double(segments.at(best)) / double(size);
  o.coverage = double(segments.at(best)) / double(total);
  o.with_plane = in_plane == segments.end() ? 0.0 : double(in_plane->second) / double(total);
  return o;
}

}  // namespace detail

inline ContactVerdict contact_verdict(const Labels& predicted, const ContactScene& scene) {
  const SegmentationScores s = score_objects(predicted, scene.truth, scene.cloud.points, LabelRange{0, 9});
  ContactVerdict v;
  v.weighted_overlap = s.weighted_overlap;
  v.lost = s.lost_labels;
  const detail::ContactTally t = detail::tally(predicted, merge_object_parts(scene.truth));
  for (const auto& [object, segments] : t.object_segments) v.objects.push_back(detail::share_of(object, segments, t));
  return v;
}

}  // namespace lccp::test
