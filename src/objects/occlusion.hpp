#pragma once
// What a nearer object hides (grouping.cpp): which parts continue each other
// behind an occluder, which part hanging in the air a body holds behind itself,
// and which part is a container's inside, seen over its rim.
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "lccp/config.hpp"
#include "lccp/core/lccp.hpp"

namespace lccp::detail {

// What the sensor saw first in one direction: the depth, and the part of
// that point (a label of work.result; 0: none, such as the support's).
struct Seen {
  float depth = 0;
  std::uint32_t part = 0;
};

// The nearest point seen per direction from the sensor: bins of `bin` in
// (x / z, y / z), over the cloud's finite points in front of it (z > 0).
// Built once per frame, for every question below.
class SeenDepth {
 public:
  SeenDepth(const CloudView& cloud, const Labels& parts, float bin);
  // The nearest point seen in x's direction; empty where nothing was seen.
  std::optional<Seen> at(const Eigen::Vector3f& x) const;

 private:
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  long index(const Eigen::Vector3f& p) const;  // -1: outside the bins

  float bin_, lo_u_ = 0, lo_v_ = 0;
  long columns_ = 0, rows_ = 0;
  std::vector<Seen> nearest_;
};

// Pairs of parts (0-based labels - 1, a < b) of work.result that are one
// surface seen on either side of a nearer object: parts `eligible` (per part)
// and not adjacent (`adjacent`: sorted pairs a < b), whose nearest supervoxels
// (at most config.grouping.occluded_gap_m apart) would be convexly and
// smoothly connected (eq. (1), (4); a step no larger than their angle explains
// over their distance, plus the sensor's depth tolerance), and whose
// connecting segment the sensor cannot see: along it every direction from the
// sensor (the origin) meets a nearer point or none, and at least one a nearer.
// A segment it sees past (the table or the wall behind a gap) is not hidden;
// nor is one whose end meets a third part with no jump in depth (the part
// ends against it: a board leaning on a box is not continued through it).
// And the sensor sees past no sample of the segment between the two parts'
// tops above those supervoxels: the one convex face they would be holds it.
// Where the supervoxels face up (tops), they lie at one height over the
// support and the sensor sees past no sample of the convex hull of both
// parts' tops at that height: two things of one height are one top only
// where nothing is seen beside or behind them.
// Needs the support plane (none: no pairs).
std::vector<std::pair<std::uint32_t, std::uint32_t>> hidden_continuations(
    const SegmentationWork& work, const SeenDepth& seen, const LccpConfig& config,
    const std::vector<std::uint8_t>& eligible, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& adjacent);

// Pairs (part, object) for parts (0-based labels - 1) of work.result: each
// part `loose` (per part: off the support, resting on nothing, in no object
// with a body) that the sensor sees vanish behind an object with a body
// (object_of: per part its object, object_of.size() if it is in none), which
// holds it out of sight (a mug's handle whose ends meet the mug behind its
// silhouette, whichever of the mug's parts is nearest them). Organized clouds
// only: in the image the part borders the object where the object is nearer,
// by at most occluded_gap_m; near that border their points come within one
// seed spacing (were the junction seen, their patches would be adjacent); and
// the sensor sees the support under most of the part's supervoxels (it stands
// on no foot of its own that the object hides). Per loose part, the object it
// borders along the most pixel pairs.
std::vector<std::pair<std::uint32_t, std::uint32_t>> held_behind(const SegmentationWork& work, const SeenDepth& seen,
                                                                 const LccpConfig& config,
                                                                 const std::vector<std::uint8_t>& loose,
                                                                 const std::vector<std::uint32_t>& object_of);

// Pairs (inside, container) of parts (0-based labels - 1) of work.result: the
// inside of an open container (a bowl's or a pot's inner wall and floor) that
// the sensor sees over the container's rim. Organized clouds only: along most
// of the image border where the container hides the part seen above it in the
// image (above: where the support's normal points), the container's point
// lies at its top on a surface that does not face up (a wall's top edge, not
// the edge of a top face: a box hiding another box), the part's point lies
// below that top, and both parts' tops (`tops`, per part, metres over the
// support) are at one height: the near and the far side of one rim.
std::vector<std::pair<std::uint32_t, std::uint32_t>> seen_over_rims(const SegmentationWork& work,
                                                                   const LccpConfig& config,
                                                                   const std::vector<float>& tops);

}  // namespace lccp::detail
