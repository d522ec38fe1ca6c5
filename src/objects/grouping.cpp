// Objects as unions of parts (GroupingConfig, config.hpp): each part's height
// span above the support plane from its points, its footprint (the convex hull
// of its supervoxels' centroids in the plane), and its junctions with the
// other parts from the supervoxel adjacency graph; then every part that
// neither stands on the support nor rests on an upward face, and every part
// inside a neighbour's footprint below its top, joins the neighbour it shares
// most edges with; a container's far inner wall on its raised floor joins the
// wall it meets at the rim; and what a nearer object hides is read from the image and
// the depths (occlusion.hpp): one surface on either side of it, a handle held
// behind it, a container's inside seen over its rim.
#include "lccp/objects/grouping.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <utility>

#include <Eigen/Geometry>

#include "convex_hull.hpp"
#include "occlusion.hpp"
#include "lccp/core/grouped.hpp"
#include "lccp/core/union_find.hpp"

namespace lccp {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// One part on the support: heights above the plane, points, the centroid of
// its points.
struct PartShape {
  double bottom = std::numeric_limits<double>::infinity();
  double top = -std::numeric_limits<double>::infinity();
  std::uint64_t points = 0;
  Vec3 sum = Vec3::Zero();
};

// Per part (0-based) the hull of its supervoxels' centroids in plane coordinates.
using Hulls = Grouped<Vec2>;
using detail::InPlane;

std::vector<PartShape> part_shapes(const SegmentationWork& w, const Plane& plane) {
  const std::uint32_t count = w.result.segment_count;
  std::vector<PartShape> shapes(count);
  for (std::size_t i = 0; i < w.result.labels.size(); ++i) {
    const std::uint32_t label = w.result.labels[i];
    if (label == 0) continue;
    PartShape& s = shapes[label - 1];
    const double height = plane.distance(w.cloud.points[i]);
    s.bottom = std::min(s.bottom, height), s.top = std::max(s.top, height);
    s.points += 1, s.sum += w.cloud.points[i].cast<double>();
  }
  return shapes;
}

Hulls part_hulls(const SegmentationWork& w, const Plane& plane) {
  const InPlane frame(plane.normal.cast<double>());
  return detail::hulls_of(group_by_key<Vec2>(w.result.segment_count, [&](auto emit) {
    for (std::size_t v = 0; v < w.segment_of_supervoxel.size(); ++v) {
      const std::uint32_t label = w.segment_of_supervoxel[v];
      if (label != 0) emit(label - 1, frame(w.supervoxels.centroids[v].cast<double>()));
    }
  }));
}

// Where parts p < q meet: supervoxel edges between them, of those the edges
// whose supervoxel on p's side (q's side) faces up, and the sum of the heights
// of the supervoxels on each side (one per edge).
struct Junction {
  std::uint32_t p = 0, q = 0;
  std::uint32_t edges = 0;
  std::array<std::uint32_t, 2> upward{0, 0};  // [0]: p's side faces up, [1]: q's side
  std::array<double, 2> height{0, 0};         // [0]: p's side, [1]: q's side

  void add(const Junction& e) {
    edges += e.edges;
    for (int side = 0; side < 2; ++side) upward[side] += e.upward[side], height[side] += e.height[side];
  }
};

std::vector<Junction> junctions(const SegmentationWork& w, const Plane& plane, double cos_upward) {
  const auto upward = [&](std::uint32_t s) { return w.supervoxels.normals[s].dot(plane.normal) >= cos_upward; };
  std::vector<Junction> edges;
  for (const Edge& e : w.edges) {
    std::uint32_t a = e.a, b = e.b;
    if (w.segment_of_supervoxel[a] > w.segment_of_supervoxel[b]) std::swap(a, b);
    const std::uint32_t p = w.segment_of_supervoxel[a], q = w.segment_of_supervoxel[b];
    if (p == 0 || p == q) continue;
    const auto height = [&](std::uint32_t s) { return double(plane.distance(w.supervoxels.centroids[s])); };
    edges.push_back({p, q, 1, {upward(a) ? 1u : 0u, upward(b) ? 1u : 0u}, {height(a), height(b)}});
  }
  std::sort(edges.begin(), edges.end(), [](const Junction& x, const Junction& y) {
    return x.p != y.p ? x.p < y.p : x.q < y.q;
  });
  std::vector<Junction> merged;
  for (const Junction& e : edges) {
    if (merged.empty() || merged.back().p != e.p || merged.back().q != e.q) {
      merged.push_back(e);
    } else {
      merged.back().add(e);
    }
  }
  return merged;
}

// How a part meets the support: lying wholly within contact_m of the plane
// (flat: a piece of the table its band left, since nothing thinner than a
// standing object's foot can be told from it: no object), standing on it (its lowest
// point within contact_m), or off it (resting on another part, or hanging).
enum class Footing : std::uint8_t { flat, stands, off };

Footing footing(const PartShape& part, const GroupingConfig& config) {
  if (part.top <= config.contact_m) return Footing::flat;
  return part.bottom <= config.contact_m ? Footing::stands : Footing::off;
}

// Whether every vertex of `hull` lies inside `outer`, or within `margin` of it.
bool inside(std::span<const Vec2> hull, std::span<const Vec2> outer, double margin) {
  if (hull.empty()) return false;
  for (const Vec2& vertex : hull) {
    if (!detail::inside_hull(outer, vertex, margin)) return false;
  }
  return true;
}

// One direction of a junction: `part` hangs off `other` when neither rests
// on the other: on its upward face (most of the junction's supervoxels on
// that side face up) or on its top (sits_on).
struct Side {
  std::uint32_t part = 0, other = 0, edges = 0;
  bool hangs = false;
  bool rests = false;  // part rests on other
};

// Whether a junction lies in the lowest third of `part` (`height`: the mean
// height of its supervoxels there) and the highest third of `other`: part
// sits on other's top even where other's top face is hidden or flush with
// part's sides (stacked boxes seen edge on). A handle meets its body at both
// of its ends, around its middle height, and low on the body: it never does.
bool sits_on(const PartShape& part, double height, const PartShape& other, double other_height) {
  return height <= part.bottom + (part.top - part.bottom) / 3 && other_height >= other.top - (other.top - other.bottom) / 3;
}

// Whether a junction lies in the highest third of `part`: part hangs from it,
// whatever way the other side faces (the inside of a mug, seen through its
// opening in pieces, meets the rim at the top of each piece; what rests on a
// face bears on it from above).
bool at_its_top(const PartShape& part, double height) { return height >= part.top - (part.top - part.bottom) / 3; }

// Whether `part` rests on `other` across a junction: it meets other's upward
// face below its own top (at_its_top) and not from below the face (what a
// face bears lies on it: a pan's handle meets the wall just under its rim,
// whose top faces up, and the wall's side of the junction is the higher), or
// sits on other's top (sits_on). A part standing on the support rests on
// nothing else.
bool rests_on(const PartShape& part, Footing feet, double height, const PartShape& other, double other_height,
              bool upward_face) {
  if (feet != Footing::off) return false;
  const bool on_face = upward_face && other_height <= height && !at_its_top(part, height);
  return on_face || sits_on(part, height, other, other_height);
}

std::vector<Side> sides_of(const std::vector<Junction>& all, const std::vector<PartShape>& shapes,
                           const std::vector<Footing>& feet) {
  std::vector<Side> sides;
  for (const Junction& j : all) {  // ascending (p, q)
    const std::uint32_t p = j.p - 1, q = j.q - 1;
    const double hp = j.height[0] / j.edges, hq = j.height[1] / j.edges;
    const bool p_rests = rests_on(shapes[p], feet[p], hp, shapes[q], hq, 2 * j.upward[1] >= j.edges);
    const bool q_rests = rests_on(shapes[q], feet[q], hq, shapes[p], hp, 2 * j.upward[0] >= j.edges);
    const bool hangs = !p_rests && !q_rests;  // where one rests on the other, neither hangs off it
    sides.push_back({p, q, j.edges, hangs, p_rests});
    sides.push_back({q, p, j.edges, hangs, q_rests});
  }
  return sides;
}

// The bodies objects are built on: parts that stand on the support, and
// parts that rest on a body (a box on a box on the table), until no more do.
// A part resting on a loose piece (one half of a handle on the other) is none.
std::vector<std::uint8_t> anchors(const std::vector<Footing>& feet, const std::vector<Side>& sides) {
  std::vector<std::uint8_t> anchor(feet.size(), 0);
  for (std::size_t k = 0; k < feet.size(); ++k) anchor[k] = feet[k] == Footing::stands;
  for (bool grew = true; grew;) {
    grew = false;
    for (const Side& s : sides) {
      if (s.rests && anchor[s.other] && !anchor[s.part]) anchor[s.part] = 1, grew = true;
    }
  }
  return anchor;
}

// The other parts off the support that hang off each other form clusters
// (the inside of a mug, seen in pieces); each cluster joins the body it hangs
// off across most edges (ties: the smaller part). A cluster that hangs off no
// body stays apart, part by part: two pieces that touch only each other give
// no reason to be one object (objects whose feet another hides).
void hang_clusters(ConcurrentUnionFind& sets, const std::vector<std::uint8_t>& anchor,
                   const std::vector<Footing>& feet, const std::vector<Side>& sides) {
  const auto loose = [&](std::uint32_t k) { return !anchor[k] && feet[k] == Footing::off; };
  ConcurrentUnionFind clusters(static_cast<std::uint32_t>(feet.size()));
  for (const Side& s : sides) {
    if (s.hangs && loose(s.part) && loose(s.other)) clusters.unite(s.part, s.other);
  }
  // (cluster, body, edges) per side of a loose part on a body; summed per (cluster, body) in that order.
  std::vector<std::array<std::uint32_t, 3>> links;
  for (const Side& s : sides) {
    if (s.hangs && loose(s.part) && anchor[s.other]) links.push_back({clusters.find(s.part), s.other, s.edges});
  }
  std::sort(links.begin(), links.end());
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> best(feet.size(), {0, kNone});  // per cluster: (edges, body)
  for (std::size_t first = 0, last = 0; first < links.size(); first = last) {
    const auto same = [&](std::size_t i) { return links[i][0] == links[first][0] && links[i][1] == links[first][1]; };
    std::uint32_t edges = 0;
    for (last = first; last < links.size() && same(last); ++last) edges += links[last][2];
    auto& b = best[links[first][0]];
    if (edges > b.first) b = {edges, links[first][1]};
  }
  for (std::uint32_t k = 0; k < feet.size(); ++k) {
    if (loose(k) && best[clusters.find(k)].second != kNone) sets.unite(k, best[clusters.find(k)].second);
  }
}

// A part alone whose footprint lies inside the footprint of a neighbouring
// object, not above its top, is that object's inside (a container's floor,
// or its inner wall seen through the opening): it joins it, until no more do. An
// object's footprint is the hull of its parts' hulls; joining a part inside
// it changes neither that nor its top. Both are hulls of noisy patch centroids:
// the part's may reach past the object's by the sensor's depth tolerance at
// the part's depth (a floor's patches against the wall it meets).
void join_insides(ConcurrentUnionFind& sets, const std::vector<PartShape>& shapes, const Hulls& hulls,
                  const std::vector<Side>& sides, const LccpConfig& lccp) {
  const GroupingConfig& config = lccp.grouping;
  const auto count = static_cast<std::uint32_t>(shapes.size());
  std::vector<double> top(count, -std::numeric_limits<double>::infinity());
  for (std::uint32_t k = 0; k < count; ++k) top[sets.find(k)] = std::max(top[sets.find(k)], shapes[k].top);
  const Hulls footprints = detail::hulls_of(group_by_key<Vec2>(count, [&](auto emit) {
    for (std::uint32_t k = 0; k < count; ++k) {
      for (const Vec2& corner : hulls[k]) emit(sets.find(k), corner);
    }
  }));
  std::vector<std::uint32_t> footprint(count);  // per object (root): its row of footprints
  std::iota(footprint.begin(), footprint.end(), 0u);
  for (bool joined = true; joined;) {
    joined = false;
    for (const Side& s : sides) {
      if (sets.find(s.part) != s.part) continue;  // one part alone
      const std::uint32_t object = sets.find(s.other);
      if (object == s.part || shapes[s.part].top > top[object] + config.contact_m) continue;
      const PartShape& part = shapes[s.part];
      const double margin = lccp.sensor.depth_tolerance_m(float(part.sum.z() / double(part.points)));
      if (!inside(hulls[s.part], footprints[footprint[object]], margin)) continue;
      sets.unite(s.part, object);
      const std::uint32_t root = sets.find(object);
      if (root != object) footprint[root] = footprint[object], top[root] = top[object];
      joined = true;
    }
  }
}

// Per part (0-based): whether it meets the support (a supervoxel edge to one
// of the support's, segment 0) and whether it meets a flat part.
struct Neighbours {
  std::vector<std::uint8_t> support, flat;
};

Neighbours neighbours(const SegmentationWork& w, const std::vector<Footing>& feet) {
  Neighbours n{std::vector<std::uint8_t>(feet.size(), 0), std::vector<std::uint8_t>(feet.size(), 0)};
  const auto mark = [&](std::uint32_t part, std::uint32_t other) {
    if (part == 0 || part == other) return;
    if (other == 0) n.support[part - 1] = 1;
    if (other != 0 && feet[other - 1] == Footing::flat) n.flat[part - 1] = 1;
  };
  for (const Edge& e : w.edges) {
    const std::uint32_t p = w.segment_of_supervoxel[e.a], q = w.segment_of_supervoxel[e.b];
    mark(p, q), mark(q, p);
  }
  return n;
}

// A part that reaches down to the support (it stands) but meets a flat part
// and no supervoxel of the support stands on a floor raised off the support
// (a pan's or a tray's, too thin to be told from the table by height alone).
// Where it meets a part that is not flat at the top of both, their tops at
// one height (within contact_m), it is the far inner wall of that part's
// container, the two walls meeting at the rim: it joins it, and so do the
// raised parts that meet it (the inner wall seen in pieces), until no more
// do. Its floor then lies inside the container's footprint (join_insides).
// Two objects standing side by side on a tray meet along their sides, not
// at their tops at one height: they stay apart.
void join_inner_walls(ConcurrentUnionFind& sets, const SegmentationWork& w, const std::vector<Junction>& all,
                      const std::vector<PartShape>& shapes, const std::vector<Footing>& feet,
                      const GroupingConfig& config) {
  const Neighbours n = neighbours(w, feet);
  const auto raised = [&](std::uint32_t k) { return feet[k] == Footing::stands && !n.support[k] && n.flat[k]; };
  std::vector<std::uint8_t> wall(feet.size(), 0);
  for (const Junction& j : all) {
    const std::uint32_t p = j.p - 1, q = j.q - 1;
    if (feet[p] == Footing::flat || feet[q] == Footing::flat || !(raised(p) || raised(q))) continue;
    const bool rim = at_its_top(shapes[p], j.height[0] / j.edges) && at_its_top(shapes[q], j.height[1] / j.edges);
    if (!rim || std::abs(shapes[p].top - shapes[q].top) > config.contact_m) continue;
    sets.unite(p, q);
    wall[p] |= raised(p), wall[q] |= raised(q);
  }
  for (bool grew = true; grew;) {
    grew = false;
    for (const Junction& j : all) {
      const std::uint32_t p = j.p - 1, q = j.q - 1;
      if (!raised(p) || !raised(q) || wall[p] == wall[q]) continue;
      sets.unite(p, q);
      wall[p] = wall[q] = 1, grew = true;
    }
  }
}

// Per part the smallest part it is one with: parts off the support on no body
// of their own (neither standing nor resting on one) that meet each other in
// one object are pieces of one part (a handle the segmentation cut in two,
// one half resting on the other; the inside of a mug seen in pieces).
std::vector<std::uint32_t> one_part(ConcurrentUnionFind& sets, const std::vector<std::uint8_t>& bodies,
                                    const std::vector<Footing>& feet, const std::vector<Side>& sides) {
  const auto count = static_cast<std::uint32_t>(feet.size());
  const auto piece = [&](std::uint32_t k) { return !bodies[k] && feet[k] == Footing::off; };
  ConcurrentUnionFind pieces(count);
  for (const Side& s : sides) {
    if (piece(s.part) && piece(s.other) && sets.find(s.part) == sets.find(s.other)) pieces.unite(s.part, s.other);
  }
  std::vector<std::uint32_t> part(count);
  for (std::uint32_t k = 0; k < count; ++k) part[k] = pieces.find(k);
  return part;
}

// Objects: the sets, numbered by decreasing points (ties: the set whose
// smallest part is smaller first); a flat part alone is no object (0).
std::vector<std::uint32_t> number_objects(ConcurrentUnionFind& sets, const std::vector<PartShape>& shapes,
                                          const std::vector<Footing>& feet) {
  const auto count = static_cast<std::uint32_t>(shapes.size());
  std::vector<std::uint64_t> points(count, 0), members(count, 0);
  for (std::uint32_t k = 0; k < count; ++k) points[sets.find(k)] += shapes[k].points, members[sets.find(k)] += 1;
  std::vector<std::uint32_t> roots;
  for (std::uint32_t k = 0; k < count; ++k) {
    if (sets.find(k) == k && !(members[k] == 1 && feet[k] == Footing::flat)) roots.push_back(k);
  }
  std::stable_sort(roots.begin(), roots.end(), [&](std::uint32_t a, std::uint32_t b) { return points[a] > points[b]; });
  std::vector<std::uint32_t> number(count, 0), object(count);
  for (std::size_t r = 0; r < roots.size(); ++r) number[roots[r]] = static_cast<std::uint32_t>(r + 1);
  for (std::uint32_t k = 0; k < count; ++k) object[k] = number[sets.find(k)];
  return object;
}

// Parts a nearer object splits (detail::hidden_continuations), among those
// that are not flat, are one.
void join_hidden(ConcurrentUnionFind& sets, const SegmentationWork& w, const detail::SeenDepth& seen,
                 const LccpConfig& config, const std::vector<Footing>& feet, const std::vector<Side>& sides) {
  std::vector<std::uint8_t> eligible(feet.size());
  for (std::size_t k = 0; k < feet.size(); ++k) eligible[k] = feet[k] != Footing::flat;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> adjacent;
  for (const Side& s : sides) {
    if (s.part < s.other) adjacent.emplace_back(s.part, s.other);
  }
  std::sort(adjacent.begin(), adjacent.end());
  for (const auto& [p, q] : detail::hidden_continuations(w, seen, config, eligible, adjacent)) sets.unite(p, q);
}

// Parts off the support in no object with a body (loose: hang_clusters found
// none they hang off), each joined to the object with a body that holds it
// behind itself (detail::held_behind), and with it the loose parts it meets,
// and those they meet: a loose piece that rests on another (a handle cut in
// two, one half on the other) has no support but what holds that one.
void join_held_behind(ConcurrentUnionFind& sets, const SegmentationWork& w, const detail::SeenDepth& seen,
                      const LccpConfig& config, const std::vector<std::uint8_t>& bodies,
                      const std::vector<Footing>& feet, const std::vector<Side>& sides) {
  const auto count = static_cast<std::uint32_t>(feet.size());
  std::vector<std::uint8_t> with_body(count, 0), loose(count, 0);
  for (std::uint32_t k = 0; k < count; ++k) with_body[sets.find(k)] |= bodies[k];
  std::vector<std::uint32_t> object_of(count, count);  // per part its object's set, if that has a body
  for (std::uint32_t k = 0; k < count; ++k) {
    loose[k] = feet[k] == Footing::off && !with_body[sets.find(k)];
    if (with_body[sets.find(k)]) object_of[k] = sets.find(k);
  }
  ConcurrentUnionFind pieces(count);  // loose parts that meet
  for (const Side& s : sides) {
    if (loose[s.part] && loose[s.other]) pieces.unite(s.part, s.other);
  }
  std::vector<std::uint32_t> holder(count, count);  // per set of pieces: the object holding one of them
  for (const auto& [part, object] : detail::held_behind(w, seen, config, loose, object_of)) {
    if (holder[pieces.find(part)] == count) holder[pieces.find(part)] = object;
  }
  for (std::uint32_t k = 0; k < count; ++k) {
    if (loose[k] && holder[pieces.find(k)] != count) sets.unite(k, holder[pieces.find(k)]);
  }
}

// Each container's inside seen over its rim (detail::seen_over_rims) joins
// the container; flat parts have no top to compare.
void join_seen_over_rims(ConcurrentUnionFind& sets, const SegmentationWork& w, const LccpConfig& config,
                         const std::vector<PartShape>& shapes, const std::vector<Footing>& feet) {
  std::vector<float> tops(shapes.size(), -std::numeric_limits<float>::infinity());
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    if (feet[k] != Footing::flat) tops[k] = static_cast<float>(shapes[k].top);
  }
  for (const auto& [inside, container] : detail::seen_over_rims(w, config, tops)) sets.unite(inside, container);
}

}  // namespace

PartGroups group_parts(const SegmentationWork& w, const LccpConfig& lccp) {
  const GroupingConfig& config = lccp.grouping;
  const std::uint32_t count = w.result.segment_count;
  std::vector<std::uint32_t> own(count);
  std::iota(own.begin(), own.end(), 1u);
  if (!w.support || count == 0) return {own, own};
  const Plane& plane = w.support->plane;
  const double cos_upward = config.cos_upward();
  const std::vector<PartShape> shapes = part_shapes(w, plane);
  const Hulls hulls = part_hulls(w, plane);
  std::vector<Footing> feet(count);
  for (std::uint32_t k = 0; k < count; ++k) feet[k] = footing(shapes[k], config);
  const std::vector<Junction> meeting = junctions(w, plane, cos_upward);
  const std::vector<Side> sides = sides_of(meeting, shapes, feet);
  ConcurrentUnionFind sets(count);
  std::optional<detail::SeenDepth> seen;  // what nearer objects hide: occluded_gap_m 0 asks nothing of it
  if (config.occluded_gap_m > 0.0f) seen.emplace(w.cloud, w.result.labels, lccp.voxels.voxel_size_m);
  if (seen) join_hidden(sets, w, *seen, lccp, feet, sides);
  const std::vector<std::uint8_t> bodies = anchors(feet, sides);
  hang_clusters(sets, bodies, feet, sides);
  if (seen) join_held_behind(sets, w, *seen, lccp, bodies, feet, sides);
  join_inner_walls(sets, w, meeting, shapes, feet, config);
  join_insides(sets, shapes, hulls, sides, lccp);
  join_seen_over_rims(sets, w, lccp, shapes, feet);
  std::vector<std::uint32_t> part = one_part(sets, bodies, feet, sides);
  for (std::uint32_t& p : part) p += 1;  // labels
  return {number_objects(sets, shapes, feet), std::move(part)};
}

}  // namespace lccp
