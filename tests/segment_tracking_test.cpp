// Stable segment ids across frames (SegmentTracker): the same physical object or
// part keeps its id while it stays in view, new segments get fresh ids.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "lccp/error.hpp"
#include "lccp/objects/tracking.hpp"

namespace lccp {
namespace {

using Ids = std::vector<std::uint32_t>;
using Points = std::vector<Eigen::Vector3f>;

// The surface of an axis-aligned box from `lo` to `hi`, sampled every 2 mm (the
// spacing of a VGA depth image at 1 m), all six faces.
Points box(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  constexpr float kStep = 0.002f;
  Points points;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (float a = lo[u]; a <= hi[u]; a += kStep)
      for (float b = lo[v]; b <= hi[v]; b += kStep)
        for (const float side : {lo[axis], hi[axis]}) {
          Eigen::Vector3f p;
          p[axis] = side;
          p[u] = a;
          p[v] = b;
          points.push_back(p);
        }
  }
  return points;
}

Points moved(Points points, const Eigen::Vector3f& by) {
  for (auto& p : points) p += by;
  return points;
}

// One frame: points with their object and part labels, segments added in dense order.
struct Scene {
  Points points;
  Labels objects;
  Labels parts;
  std::uint32_t object_count = 0;
  std::uint32_t part_count = 0;

  // Adds points to object `object` (1-based; 0 = a new object) as part `part`
  // (0 = none, else 1-based); returns the object's label.
  std::uint32_t add(const Points& more, std::uint32_t object = 0, std::uint32_t part = 0) {
    if (object == 0) object = ++object_count;
    part_count = std::max(part_count, part);
    points.insert(points.end(), more.begin(), more.end());
    objects.insert(objects.end(), more.size(), object);
    parts.insert(parts.end(), more.size(), part);
    return object;
  }
  FrameSegments frame(bool with_parts = false) const {
    return {points, &objects, object_count, with_parts ? &parts : nullptr, with_parts ? part_count : 0};
  }
};

const Eigen::Vector3f kA(0.0f, 0.0f, 1.0f);  // a box's near lower corner, 1 m out

TEST(SegmentTracker, FirstFrameIdsFollowDenseOrderObjectsThenParts) {
  Scene scene;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3f at = kA + Eigen::Vector3f(0.15f * k, 0, 0);
    const std::uint32_t object = scene.add(box(at, at + Eigen::Vector3f(0.05f, 0.1f, 0.05f)), 0, 2 * k + 1);
    scene.add(box(at + Eigen::Vector3f(0.06f, 0, 0), at + Eigen::Vector3f(0.1f, 0.1f, 0.05f)), object, 2 * k + 2);
  }
  SegmentTracker tracker;
  const TrackedIds ids = tracker.update(scene.frame(true));
  EXPECT_EQ(ids.object_ids, (Ids{1, 2, 3}));
  EXPECT_EQ(ids.part_ids, (Ids{4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(ids.new_ids, (Ids{1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_TRUE(ids.gone_ids.empty());

  // Without parts and from 1: the ids are the dense labels (single-cloud output).
  SegmentTracker objects_only;
  const TrackedIds plain = objects_only.update(scene.frame(false));
  EXPECT_EQ(plain.object_ids, (Ids{1, 2, 3}));
  EXPECT_TRUE(plain.part_ids.empty());
  // From another first id (a support plane holds 1).
  SegmentTracker from_two(2);
  EXPECT_EQ(from_two.update(scene.frame(true)).object_ids, (Ids{2, 3, 4}));
}

// A frame on its own gets, without a tracker, the ids a new tracker's first
// update gives it, with and without parts, from either first id.
TEST(SegmentTracker, FirstFrameIdsWithoutATrackerAreThoseOfANewTracker) {
  Scene scene;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3f at = kA + Eigen::Vector3f(0.15f * k, 0, 0);
    const std::uint32_t object = scene.add(box(at, at + Eigen::Vector3f(0.05f, 0.1f, 0.05f)), 0, k + 1);
    if (k % 2 == 0) scene.add(box(at + Eigen::Vector3f(0.06f, 0, 0), at + Eigen::Vector3f(0.1f, 0.1f, 0.05f)), object);
  }
  for (const bool with_parts : {false, true}) {
    for (const std::uint32_t first : {1u, 2u}) {
      SegmentTracker tracker(first);
      const TrackedIds expected = tracker.update(scene.frame(with_parts));
      const TrackedIds ids = first_frame_ids(scene.frame(with_parts), first);
      EXPECT_EQ(ids.object_ids, expected.object_ids) << with_parts << " " << first;
      EXPECT_EQ(ids.part_ids, expected.part_ids) << with_parts << " " << first;
      EXPECT_EQ(ids.new_ids, expected.new_ids) << with_parts << " " << first;
      EXPECT_TRUE(ids.gone_ids.empty());
      EXPECT_EQ(ids.object_ids.size(), 4u);
      EXPECT_EQ(ids.part_ids.size(), with_parts ? 4u : 0u);
    }
  }
  // A label above its count, labels that do not match the points, ids beyond the last.
  FrameSegments above = scene.frame(true);
  above.part_count = 3;
  EXPECT_THROW(first_frame_ids(above, 1), Error);
  Labels short_labels(scene.points.size() - 1, 1);
  FrameSegments mismatched = scene.frame();
  mismatched.objects = &short_labels;
  EXPECT_THROW(first_frame_ids(mismatched, 1), Error);
  EXPECT_THROW(first_frame_ids(scene.frame(true), std::numeric_limits<std::uint32_t>::max() - 7), Error);
  EXPECT_NO_THROW(first_frame_ids(scene.frame(true), std::numeric_limits<std::uint32_t>::max() - 8));
}

// 5 mm per frame for 30 frames: along the depth axis (a face square to the
// motion crosses a cell layer every other frame, the worst case for cells) and
// diagonally, next to a touching neighbour that stands still.
TEST(SegmentTracker, ObjectMovingFiveMillimetresPerFrameKeepsItsId) {
  for (const Eigen::Vector3f& step : {Eigen::Vector3f(0, 0, 0.005f), Eigen::Vector3f(0.0029f, -0.0029f, 0.0029f)}) {
    SegmentTracker tracker;
    const Points still = box(kA + Eigen::Vector3f(0.1f, 0, 0), kA + Eigen::Vector3f(0.2f, 0.1f, 0.1f));
    const Points mover = box(kA, kA + Eigen::Vector3f(0.1f, 0.1f, 0.1f));
    for (int f = 0; f < 30; ++f) {
      Scene scene;
      scene.add(moved(mover, step * static_cast<float>(f)));
      scene.add(still);
      const TrackedIds ids = tracker.update(scene.frame());
      EXPECT_EQ(ids.object_ids, (Ids{1, 2})) << "frame " << f;
      if (f > 0) {
        EXPECT_TRUE(ids.new_ids.empty() && ids.gone_ids.empty()) << "frame " << f;
      }
    }
  }
}

TEST(SegmentTracker, TouchingObjectsSwappingDenseLabelsKeepTheirIds) {
  const Points left = box(kA, kA + Eigen::Vector3f(0.08f, 0.1f, 0.08f));
  const Points right = box(kA + Eigen::Vector3f(0.08f, 0, 0), kA + Eigen::Vector3f(0.16f, 0.12f, 0.08f));
  SegmentTracker tracker;
  Scene first;
  first.add(left);
  first.add(right);
  EXPECT_EQ(tracker.update(first.frame()).object_ids, (Ids{1, 2}));
  Scene second;  // right is object 1 now, and both moved 3 mm
  second.add(moved(right, Eigen::Vector3f(0.003f, 0, 0)));
  second.add(moved(left, Eigen::Vector3f(0, 0.003f, 0)));
  const TrackedIds ids = tracker.update(second.frame());
  EXPECT_EQ(ids.object_ids, (Ids{2, 1}));
  EXPECT_TRUE(ids.new_ids.empty());
  EXPECT_TRUE(ids.gone_ids.empty());
}

TEST(SegmentTracker, VanishedObjectIsGoneAndNewcomerGetsAFreshId) {
  const Points a = box(kA, kA + Eigen::Vector3f(0.1f, 0.1f, 0.1f));
  const Points b = box(kA + Eigen::Vector3f(0.2f, 0, 0), kA + Eigen::Vector3f(0.3f, 0.1f, 0.1f));
  const Points c = box(kA + Eigen::Vector3f(0, 0.2f, 0), kA + Eigen::Vector3f(0.1f, 0.3f, 0.1f));
  SegmentTracker tracker;
  Scene first;
  first.add(a);
  first.add(b);
  tracker.update(first.frame());
  Scene second;  // b left, c came
  second.add(c);
  second.add(a);
  const TrackedIds ids = tracker.update(second.frame());
  EXPECT_EQ(ids.object_ids, (Ids{3, 1}));
  EXPECT_EQ(ids.new_ids, (Ids{3}));
  EXPECT_EQ(ids.gone_ids, (Ids{2}));
}

// A 20 cm bar breaks into 13 and 7 cm pieces; the smaller piece is dense label 1.
TEST(SegmentTracker, SplitObjectLargerPieceKeepsTheIdSmallerIsNew) {
  SegmentTracker tracker;
  Scene whole;
  whole.add(box(kA, kA + Eigen::Vector3f(0.2f, 0.05f, 0.05f)));
  whole.add(box(kA + Eigen::Vector3f(0, 0.2f, 0), kA + Eigen::Vector3f(0.1f, 0.3f, 0.1f)));
  tracker.update(whole.frame());
  Scene split;
  split.add(box(kA + Eigen::Vector3f(0.13f, 0, 0), kA + Eigen::Vector3f(0.2f, 0.05f, 0.05f)));
  split.add(box(kA + Eigen::Vector3f(0, 0.2f, 0), kA + Eigen::Vector3f(0.1f, 0.3f, 0.1f)));
  split.add(box(kA, kA + Eigen::Vector3f(0.13f, 0.05f, 0.05f)));
  const TrackedIds ids = tracker.update(split.frame());
  EXPECT_EQ(ids.object_ids, (Ids{3, 2, 1}));
  EXPECT_EQ(ids.new_ids, (Ids{3}));
  EXPECT_TRUE(ids.gone_ids.empty());
}

// Object A = parts R1 + R2, object B = part R3 (R2 touches R3). Next frame R2
// belongs to B: it overlaps A's old part R2 perfectly, but that part was A's, so
// it gets a new id; R1 and R3 keep theirs.
TEST(SegmentTracker, PartCannotInheritAnIdFromAnotherObjectsPart) {
  const Points r1 = box(kA, kA + Eigen::Vector3f(0.12f, 0.1f, 0.1f));
  const Points r2 = box(kA + Eigen::Vector3f(0.12f, 0, 0), kA + Eigen::Vector3f(0.16f, 0.1f, 0.1f));
  const Points r3 = box(kA + Eigen::Vector3f(0.16f, 0, 0), kA + Eigen::Vector3f(0.3f, 0.1f, 0.1f));
  SegmentTracker tracker;
  Scene first;
  const std::uint32_t a = first.add(r1, 0, 1);
  first.add(r2, a, 2);
  first.add(r3, 0, 3);
  const TrackedIds before = tracker.update(first.frame(true));
  ASSERT_EQ(before.object_ids, (Ids{1, 2}));
  ASSERT_EQ(before.part_ids, (Ids{3, 4, 5}));  // R1 3, R2 4, R3 5
  Scene second;
  second.add(r1, 0, 1);
  const std::uint32_t b = second.add(r2, 0, 2);
  second.add(r3, b, 3);
  const TrackedIds ids = tracker.update(second.frame(true));
  EXPECT_EQ(ids.object_ids, (Ids{1, 2}));
  EXPECT_EQ(ids.part_ids, (Ids{3, 6, 5}));
  EXPECT_EQ(ids.new_ids, (Ids{6}));
  EXPECT_EQ(ids.gone_ids, (Ids{4}));
}

// Objects come and go at the same two places; an object that is back after a
// frame away is a new one, and no id is ever handed out twice.
TEST(SegmentTracker, IdsAreNeverReused) {
  const Points places[] = {box(kA, kA + Eigen::Vector3f(0.1f, 0.1f, 0.1f)),
                           box(kA + Eigen::Vector3f(0.2f, 0, 0), kA + Eigen::Vector3f(0.3f, 0.1f, 0.1f))};
  SegmentTracker tracker;
  std::set<std::uint32_t> handed_out;
  Ids previous;
  for (int f = 0; f < 12; ++f) {
    Scene scene;
    if (f % 3 != 1) scene.add(places[0]);
    if (f % 2 == 0) scene.add(places[1]);
    const TrackedIds ids = tracker.update(scene.frame());
    for (const std::uint32_t id : ids.new_ids) EXPECT_TRUE(handed_out.insert(id).second) << "id " << id << " again";
    for (const std::uint32_t id : ids.object_ids) EXPECT_TRUE(handed_out.count(id)) << "id " << id;
    Ids gone;  // the previous ids not in this frame
    for (const std::uint32_t id : previous)
      if (std::find(ids.object_ids.begin(), ids.object_ids.end(), id) == ids.object_ids.end()) gone.push_back(id);
    std::sort(gone.begin(), gone.end());
    EXPECT_EQ(ids.gone_ids, gone) << "frame " << f;
    previous = ids.object_ids;
  }
  // Place 0 is back in frames 0, 2, 5, 8, 11; place 1 in frames 0, 2, 4, 6, 8, 10.
  EXPECT_EQ(handed_out.size(), 11u);
}

// A flat square seen head-on, moving 5 mm a frame along its normal (the viewing
// axis): every frame it crosses a cell boundary of one of the two grids, the
// worst case for cells (with one grid it would share no cell every other frame).
TEST(SegmentTracker, FlatFaceMovingAlongItsNormalKeepsItsId) {
  SegmentTracker tracker;
  for (int f = 0; f < 30; ++f) {
    const float z = 1.0012f + 0.005f * static_cast<float>(f);
    Scene scene;
    scene.add(box(Eigen::Vector3f(0, 0, z), Eigen::Vector3f(0.1f, 0.1f, z)));
    const TrackedIds ids = tracker.update(scene.frame());
    EXPECT_EQ(ids.object_ids, (Ids{1})) << "frame " << f;
  }
}

// A plane from `corner` along the axes u and v (metres), sampled every 4 mm, with
// noise of up to +-3 mm along its normal `n` from a fixed generator.
Points noisy_plane(const Eigen::Vector3f& corner, const Eigen::Vector3f& u, const Eigen::Vector3f& v,
                   const Eigen::Vector3f& n, std::mt19937& random) {
  std::uniform_real_distribution<float> noise(-0.003f, 0.003f);
  Points points;
  for (float a = 0; a <= u.norm(); a += 0.004f)
    for (float b = 0; b <= v.norm(); b += 0.004f)
      points.push_back(corner + a * u.normalized() + b * v.normalized() + noise(random) * n);
  return points;
}

// A floor (1.2 x 1.2 m) and a wall (1.2 x 0.6 m) meeting at a seam, with a box
// on the floor: in frames 5-8 and 20 the seam is bridged (floor and wall are
// one object, as when noise joins them), in the others they are two. The wall
// never moves: it must keep its id through every merge and split, as the box
// keeps its own.
TEST(SegmentTracker, LargeSurfaceKeepsItsIdThroughMergesWithItsNeighbour) {
  std::mt19937 random(7);
  const Eigen::Vector3f x(1.2f, 0, 0), z(0, 0, 1.2f), up(0, -0.6f, 0);
  SegmentTracker tracker;
  std::optional<std::uint32_t> wall_id, floor_id, box_id;
  for (int f = 0; f < 30; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const Points floor = noisy_plane({-0.6f, 0.5f, 1.0f}, x, z, Eigen::Vector3f::UnitY(), random);
    const Points wall = noisy_plane({-0.6f, 0.5f, 2.2f}, x, up, Eigen::Vector3f::UnitZ(), random);
    const bool merged = (f >= 5 && f <= 8) || f == 20;
    Scene scene;
    const std::uint32_t floor_object = scene.add(floor);
    const std::uint32_t wall_object = scene.add(wall, merged ? floor_object : 0);
    const std::uint32_t box_object = scene.add(box({0, 0.4f, 1.5f}, {0.1f, 0.5f, 1.6f}));
    const TrackedIds ids = tracker.update(scene.frame());
    if (f == 0) {
      floor_id = ids.object_ids[floor_object - 1];
      wall_id = ids.object_ids[wall_object - 1];
      box_id = ids.object_ids[box_object - 1];
    }
    EXPECT_EQ(ids.object_ids[floor_object - 1], *floor_id);  // the larger surface: the merged object's id
    EXPECT_EQ(ids.object_ids[box_object - 1], *box_id);
    if (!merged) {
      EXPECT_EQ(ids.object_ids[wall_object - 1], *wall_id);
      EXPECT_TRUE(f == 0 || ids.new_ids.empty());
    }
  }
}

// An object that merged into its neighbour and never split off again: its id
// lapses with its carrier, and an object appearing there later is new.
TEST(SegmentTracker, AbsorbedIdLapsesWhenItsCarrierIsGone) {
  const Points a = box(kA, kA + Eigen::Vector3f(0.2f, 0.1f, 0.1f));
  const Points b = box(kA + Eigen::Vector3f(0.2f, 0, 0), kA + Eigen::Vector3f(0.3f, 0.1f, 0.1f));
  SegmentTracker tracker;
  Scene apart;
  apart.add(a);
  apart.add(b);
  EXPECT_EQ(tracker.update(apart.frame()).object_ids, (Ids{1, 2}));
  Scene joined;
  const std::uint32_t ab = joined.add(a);
  joined.add(b, ab);
  const TrackedIds merged = tracker.update(joined.frame());
  EXPECT_EQ(merged.object_ids, (Ids{1}));
  EXPECT_EQ(merged.gone_ids, (Ids{2}));
  tracker.update(FrameSegments{});  // the merged object leaves
  const TrackedIds back = tracker.update(apart.frame());
  EXPECT_EQ(back.object_ids, (Ids{3, 4}));
}

// Everything leaves: all previous ids are gone; an empty frame has no ids.
TEST(SegmentTracker, EmptyFrameEndsEveryId) {
  SegmentTracker tracker;
  Scene scene;
  const std::uint32_t a = scene.add(box(kA, kA + Eigen::Vector3f(0.1f, 0.1f, 0.1f)), 0, 1);
  scene.add(box(kA + Eigen::Vector3f(0.1f, 0, 0), kA + Eigen::Vector3f(0.2f, 0.1f, 0.1f)), a, 2);
  tracker.update(scene.frame(true));
  const TrackedIds none = tracker.update(FrameSegments{});
  EXPECT_TRUE(none.object_ids.empty() && none.part_ids.empty() && none.new_ids.empty());
  EXPECT_EQ(none.gone_ids, (Ids{1, 2, 3}));
  EXPECT_EQ(tracker.update(scene.frame(true)).object_ids, (Ids{4}));
}

// Missing measurements (NaN, label 0) are skipped; a labelled NaN point (bad
// input) adds no cell.
TEST(SegmentTracker, NonFinitePointsAddNoCells) {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  SegmentTracker tracker;
  for (int f = 0; f < 3; ++f) {
    Scene scene;
    scene.add(moved(box(kA, kA + Eigen::Vector3f(0.1f, 0.1f, 0.1f)), Eigen::Vector3f(0.003f * f, 0, 0)));
    scene.points.insert(scene.points.begin() + 100, Eigen::Vector3f::Constant(kNaN));
    scene.objects.insert(scene.objects.begin() + 100, f == 1 ? 1u : 0u);
    scene.parts.insert(scene.parts.begin() + 100, 0u);
    EXPECT_EQ(tracker.update(scene.frame()).object_ids, (Ids{1})) << "frame " << f;
  }
}

// Objects 30 m apart (beyond the compact packing's 20 m): the same ids.
TEST(SegmentTracker, FarApartObjectsKeepTheirIds) {
  SegmentTracker tracker;
  for (int f = 0; f < 4; ++f) {
    const Eigen::Vector3f step(0.003f * f, 0, 0.002f * f);
    Scene scene;
    scene.add(moved(box(kA, kA + Eigen::Vector3f(0.1f, 0.1f, 0.1f)), step));
    scene.add(moved(box(kA + Eigen::Vector3f(0, 0, 30), kA + Eigen::Vector3f(0.1f, 0.1f, 30.1f)), step));
    const TrackedIds ids = tracker.update(scene.frame());
    EXPECT_EQ(ids.object_ids, (Ids{1, 2})) << "frame " << f;
  }
}

TEST(SegmentTracker, LabelsThatDoNotFitTheFrameAreRefused) {
  Scene scene;
  scene.add(box(kA, kA + Eigen::Vector3f(0.05f, 0.05f, 0.05f)), 0, 1);
  SegmentTracker tracker;
  FrameSegments above = scene.frame(true);
  above.object_count = 0;
  EXPECT_THROW(tracker.update(above), Error);
  above = scene.frame(true);
  above.part_count = 0;  // part labels 1 with no parts: above the count
  EXPECT_THROW(tracker.update(above), Error);
  Labels short_labels(scene.points.size() - 1, 1);
  FrameSegments mismatched = scene.frame();
  mismatched.objects = &short_labels;
  EXPECT_THROW(tracker.update(mismatched), Error);
}

// A VGA depth image (640 x 480, fx = fy = 525) of a wavy surface about 1 m out,
// cut into 10 touching objects side by side with 10 parts each (bands), all
// sliding `shift` to the right; the dense labels are shuffled by `seed`. World
// object `absent` (if any) is out of view: its points unlabelled, the others
// numbered densely.
struct VgaScene {
  static constexpr int kObjects = 10, kBands = 10;
  Points points;
  Labels objects, parts;
  std::vector<int> dense;  // [world object]: its dense label - 1 (-1: absent)

  VgaScene() {
    for (int v = 0; v < 480; ++v)
      for (int u = 0; u < 640; ++u) {
        const float z = 1.0f + 0.03f * std::sin(u / 40.0f) + 0.02f * std::cos(v / 30.0f);
        points.emplace_back((u - 319.5f) / 525.0f * z, (v - 239.5f) / 525.0f * z, z);
      }
  }
  FrameSegments label(float shift, unsigned seed, int absent = -1) {
    std::vector<int> order(kObjects - (absent >= 0));
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(seed));
    dense.assign(kObjects, -1);
    for (int k = 0, next = 0; k < kObjects; ++k)
      if (k != absent) dense[k] = order[next++];
    objects.assign(points.size(), 0);
    parts.assign(points.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const int k = static_cast<int>(std::floor((points[i].x() - shift + 0.6f) / 0.12f));
      const int band = std::clamp(static_cast<int>(std::floor((points[i].y() + 0.46f) / 0.092f)), 0, kBands - 1);
      if (k < 0 || k >= kObjects || k == absent) continue;
      objects[i] = dense[k] + 1;
      parts[i] = dense[k] * kBands + band + 1;
    }
    const auto count = static_cast<std::uint32_t>(order.size());
    return {points, &objects, count, &parts, count * kBands};
  }
};

// 10 objects and 100 parts over 21 frames, 2 mm apart, shuffled labels every
// frame: every world object and part keeps its first id. Prints the median time
// of update() over the last 20 frames.
TEST(SegmentTracker, VgaFrameWithShuffledLabelsKeepsEveryId) {
  VgaScene scene;
  SegmentTracker tracker;
  Ids object_id(VgaScene::kObjects), part_id(VgaScene::kObjects * VgaScene::kBands);
  std::vector<double> ms;
  for (int f = 0; f <= 20; ++f) {
    const FrameSegments frame = scene.label(0.002f * f, f);
    const auto start = std::chrono::steady_clock::now();
    const TrackedIds ids = tracker.update(frame);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    for (int k = 0; k < VgaScene::kObjects; ++k) {
      const int d = scene.dense[k];
      if (f == 0) object_id[k] = ids.object_ids[d];
      EXPECT_EQ(ids.object_ids[d], object_id[k]) << "frame " << f << " object " << k;
      for (int b = 0; b < VgaScene::kBands; ++b) {
        const std::uint32_t id = ids.part_ids[d * VgaScene::kBands + b];
        if (f == 0) part_id[k * VgaScene::kBands + b] = id;
        EXPECT_EQ(id, part_id[k * VgaScene::kBands + b]) << "frame " << f << " object " << k << " band " << b;
      }
    }
    if (f > 0) {
      EXPECT_TRUE(ids.new_ids.empty() && ids.gone_ids.empty()) << "frame " << f;
    }
  }
  std::sort(ms.begin() + 1, ms.end());
  std::printf("update() on a VGA frame (10 objects, 100 parts): median %.3f ms of 20\n", ms[10]);
}

// A cluttered frame: 40 x 40 small squares (2 cm, 3 cm apart), far more segments
// than the counting table takes (1 600^2 pairs > 2^20, so the pairs are sorted),
// moving 2 mm a frame with their labels shuffled: every square keeps its id.
TEST(SegmentTracker, ClutterOfSixteenHundredSegmentsKeepsEveryId) {
  constexpr int kSide = 40, kSquares = kSide * kSide;
  const auto square = [](int k) {
    const Eigen::Vector3f lo(0.03f * static_cast<float>(k % kSide), 0.03f * static_cast<float>(k / kSide), 1.0f);
    Points points;
    for (float a = 0; a <= 0.02f; a += 0.002f)
      for (float b = 0; b <= 0.02f; b += 0.002f) points.push_back(lo + Eigen::Vector3f(a, b, 0));
    return points;
  };
  std::vector<int> order(kSquares);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 random(5);
  SegmentTracker tracker;
  Ids first(kSquares);
  for (int f = 0; f < 4; ++f) {
    std::shuffle(order.begin(), order.end(), random);
    Scene scene;
    std::vector<std::uint32_t> label(kSquares);
    for (const int k : order) label[k] = scene.add(moved(square(k), Eigen::Vector3f(0.002f * f, 0, 0)));
    const TrackedIds ids = tracker.update(scene.frame());
    for (int k = 0; k < kSquares; ++k) {
      if (f == 0) first[k] = ids.object_ids[label[k] - 1];
      ASSERT_EQ(ids.object_ids[label[k] - 1], first[k]) << "frame " << f << " square " << k;
    }
    if (f > 0) {
      EXPECT_TRUE(ids.new_ids.empty() && ids.gone_ids.empty()) << "frame " << f;
    }
  }
}

// The VGA scene over frames in which an object leaves and comes back: the same
// ids, new and gone, with 1 and 2 oneTBB threads.
TEST(SegmentTracker, SameIdsWithOneAndTwoThreads) {
  const auto run = [](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    VgaScene scene;
    SegmentTracker tracker;
    std::vector<TrackedIds> all;
    for (int f = 0; f < 8; ++f) all.push_back(tracker.update(scene.label(0.004f * f, f, f % 3 == 2 ? 4 : -1)));
    return all;
  };
  const std::vector<TrackedIds> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t f = 0; f < one.size(); ++f) {
    EXPECT_EQ(one[f].object_ids, two[f].object_ids) << "frame " << f;
    EXPECT_EQ(one[f].part_ids, two[f].part_ids) << "frame " << f;
    EXPECT_EQ(one[f].new_ids, two[f].new_ids) << "frame " << f;
    EXPECT_EQ(one[f].gone_ids, two[f].gone_ids) << "frame " << f;
  }
  EXPECT_EQ(one[2].gone_ids.size(), 11u);  // one object away, and its 10 parts
  EXPECT_EQ(one[3].new_ids.size(), 11u);   // back: new ids
}

}  // namespace
}  // namespace lccp
