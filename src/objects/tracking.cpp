#include "lccp/objects/tracking.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "lccp/error.hpp"

// Matching by overlap of occupied cells. Every segment of a frame is the set of
// cells its points fall in; a segment inherits the id of the previous frame's
// segment its cell set overlaps most, greedily, best overlap first.
//
// Why overlap and not centroid + extent: two objects that touch (a mug standing
// against a box) have centroids a few centimetres apart and overlapping boxes,
// so a centroid rule swaps their ids as soon as one moves, and the centroid of
// a partly occluded object jumps by half its size when a hand covers it. Cell
// sets do neither: touching objects share at most their boundary cells, and the
// visible remainder of an occluded object still lies in the cells it occupied.
//
// Why intersection over union (IoU) and not over the smaller set: at 30 Hz an
// object moves a few millimetres between frames, much less than its size, so it
// overlaps its own previous cells almost entirely, IoU near 1; occlusion grows
// by a few centimetres a frame at most, so even a hand sweeping over an object
// keeps consecutive frames' IoU high. Over the smaller set, every fragment that
// lies inside its predecessor scores 1: when an object splits, its small piece
// would tie with the large one, and a speck of noise where an object vanished
// would inherit its id. IoU ranks the larger piece first and leaves small
// fragments below the threshold.
//
// Merged and split again. The largest surfaces in view (a wall, the floor) meet
// at a seam, and where noise bridges it for a frame or a few, they are one
// object; then they split again. In the merged frame the merged object inherits
// the larger surface's id (the higher IoU) and the smaller one's id is gone, so
// when it splits off it would get a new id, every few frames (the synthetic
// recording's wall, 27 500 points, 3 -> 179 -> 518 -> 908 ...). IoU cannot
// help: the merged object is already taken by the larger surface, and the
// wall's own id is no longer in the previous frame. The geometry is clear
// though: the wall did not move, its cells are inside the merged object's. So a
// previous object that no segment inherited, but of whose cells a current
// object holds at least kMinOverlap (the least share its own successor would
// need), is absorbed: its id and its last cells go with that object (the one
// holding most of them) while it lives; and a later object without an id that
// lies in those cells (IoU >= kMinOverlap, the rule for any match) takes the id
// back. An absorbed id lapses after kAbsorbedFrames (its cells grow stale as
// things move: at 3-5 mm a frame, 30 frames are 10-15 cm) or when its carrier
// is gone; an object that vanished without being absorbed still comes back new.
namespace lccp {
namespace {

constexpr std::uint32_t kNone = kNoObject;  // no id, no segment, no object

// One frame's segments as the tracker keeps them.
struct TrackedFrame {
  std::array<std::vector<OccupiedCell>, 2> cells;  // per grid: ascending (cell, segment), no repeats
  std::vector<std::uint32_t> sizes;            // per segment: how many cells it occupies, both grids
  std::vector<std::uint32_t> ids;              // per segment: its stable id
  std::vector<std::uint32_t> owner_ids;        // per part: the stable id of its object
  std::uint32_t object_count = 0;
};

// Ids of objects that merged into a neighbour ("Merged and split again" above):
// each as a segment of its own with the cells it had when last seen.
struct AbsorbedIds {
  TrackedFrame segments;                // every segment an object; ids: the absorbed ids
  std::vector<std::uint32_t> carriers;  // per absorbed id: the id of the object that took it in
  std::vector<std::uint32_t> ages;      // per absorbed id: frames since it was absorbed
};

// 1 cm cells: twice and more the 3-5 mm an object moves between frames at 30 Hz
// (so most of its cells stay occupied), and small next to table-top objects
// (5-30 cm: tens of cells across, so the few boundary cells it shares with a
// touching neighbour are a small part of either). Kinect-class depth noise at
// 1-2 m is 2-8 mm, about a cell.
constexpr float kCellSize = 0.01f;
// On two grids, half a cell apart: lccp/core/occupied_cells.hpp says why.
// Below this IoU there is no match. The same object in consecutive frames scores
// near 1 (1/3 in the worst case above); a segment that appeared where another
// vanished, or a small piece split off, shares far less.
constexpr double kMinOverlap = 0.25;
// Frames an absorbed id waits with its carrier for a split (1 s at 30 Hz).
constexpr std::uint32_t kAbsorbedFrames = 30;
void check_labels(const Labels* labels, std::size_t point_count, const char* what) {
  if (labels != nullptr && labels->size() != point_count)
    throw Error(std::string("segment tracking: ") + what + " labels and points differ in number");
}

void check_frame(const FrameSegments& frame) {
  if (frame.object_count > 0 && (frame.points.empty() || frame.objects == nullptr))
    throw Error("segment tracking: object_count > 0 without points or object labels");
  const std::size_t n = frame.points.size();
  check_labels(frame.objects, n, "object");
  check_labels(frame.parts, n, "part");
  if (frame.parts != nullptr && frame.objects == nullptr)
    throw Error("segment tracking: part labels without object labels");
  if (std::uint64_t{frame.object_count} + frame.part_count >= kNone)
    throw Error("segment tracking: too many segments");
}

// A segment of this frame and one of the previous frame, at the same level,
// sharing cells.
struct Candidate {
  std::uint32_t current = 0;
  std::uint32_t previous = 0;
  std::uint32_t previous_id = 0;
  std::uint64_t shared = 0;    // cells in both
  std::uint64_t combined = 0;  // cells in either
};

// Calls count(current, previous) for every cell of a grid that a segment of
// this frame shares with one of the previous frame at the same level.
template <typename Count>
void for_each_shared_cell(const TrackedFrame& now, const TrackedFrame& before, int grid, Count&& count) {
  const OccupiedCell *i = now.cells[grid].data(), *i_last = i + now.cells[grid].size();
  const OccupiedCell *j = before.cells[grid].data(), *j_last = j + before.cells[grid].size();
  while (i != i_last && j != j_last) {
    if (i->cell != j->cell) {
      i->cell < j->cell ? ++i : ++j;
      continue;
    }
    const OccupiedCell *i_end = i + 1, *j_end = j + 1;
    while (i_end != i_last && i_end->cell == i->cell) ++i_end;
    while (j_end != j_last && j_end->cell == j->cell) ++j_end;
    for (const OccupiedCell* a = i; a != i_end; ++a)
      for (const OccupiedCell* b = j; b != j_end; ++b)
        if ((a->segment < now.object_count) == (b->segment < before.object_count)) count(a->segment, b->segment);
    i = i_end;
    j = j_end;
  }
}

// The shared cells of every pair of segments (current * previous count +
// previous) that shares any, ascending: counted in a table per grid (in
// parallel) while that is small (at most 2^20 pairs: 100 parts in each frame
// make 10^4), else as one key per shared cell and pair, radix-sorted (linear in
// the shared cells: a cluttered room's 2 000 segments make 4 * 10^6 pairs).
std::vector<std::pair<std::uint64_t, std::uint64_t>> shared_counts(const TrackedFrame& now,
                                                                   const TrackedFrame& before) {
  const std::uint64_t before_count = before.sizes.size(), pairs = now.sizes.size() * before_count;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> out;
  if (pairs <= (std::uint64_t{1} << 20)) {
    std::array<std::vector<std::uint32_t>, 2> table;
    tbb::parallel_for(0, 2, [&](int g) {
      table[g].assign(pairs, 0);
      for_each_shared_cell(now, before, g, [&](std::uint32_t u, std::uint32_t v) { ++table[g][u * before_count + v]; });
    });
    for (std::uint64_t k = 0; k < pairs; ++k)
      if (table[0][k] + table[1][k] != 0) out.emplace_back(k, table[0][k] + table[1][k]);
    return out;
  }
  std::vector<std::uint64_t> keys;
  for (int g = 0; g < 2; ++g)
    for_each_shared_cell(now, before, g, [&](std::uint32_t u, std::uint32_t v) { keys.push_back(u * before_count + v); });
  sort_keys(keys, static_cast<int>(std::bit_width(pairs - 1)));
  for (std::size_t i = 0, end = 0; i < keys.size(); i = end) {
    for (end = i + 1; end < keys.size() && keys[end] == keys[i];) ++end;
    out.emplace_back(keys[i], end - i);
  }
  return out;
}

using SharedCounts = std::vector<std::pair<std::uint64_t, std::uint64_t>>;  // shared_counts()

// The pairs of segments whose overlap (IoU) reaches kMinOverlap.
std::vector<Candidate> candidates(const TrackedFrame& now, const TrackedFrame& before, const SharedCounts& counts) {
  const std::uint64_t before_count = before.sizes.size();
  std::vector<Candidate> found;
  for (const auto& [pair, shared] : counts) {
    Candidate c{static_cast<std::uint32_t>(pair / before_count), static_cast<std::uint32_t>(pair % before_count), 0,
                shared, 0};
    c.previous_id = before.ids[c.previous];
    c.combined = now.sizes[c.current] + before.sizes[c.previous] - c.shared;
    if (static_cast<double>(c.shared) >= kMinOverlap * static_cast<double>(c.combined)) found.push_back(c);
  }
  return found;
}

// Greedy order: higher IoU first (compared exactly), then the older previous id,
// then the lower current label.
bool better(const Candidate& a, const Candidate& b) {
  using Wide = unsigned __int128;
  const Wide lhs = Wide{a.shared} * b.combined, rhs = Wide{b.shared} * a.combined;
  if (lhs != rhs) return lhs > rhs;
  if (a.previous_id != b.previous_id) return a.previous_id < b.previous_id;
  return a.current < b.current;
}

// Gives each segment the id of its best still-free predecessor; before_taken
// marks the previous frame's segments already inherited.
void match(std::vector<Candidate> found, std::vector<std::uint32_t>& ids, std::vector<char>& before_taken) {
  std::sort(found.begin(), found.end(), better);
  for (const Candidate& c : found) {
    if (ids[c.current] != kNone || before_taken[c.previous]) continue;
    ids[c.current] = c.previous_id;
    before_taken[c.previous] = 1;
  }
}

// Objects first; then parts, each only from a part of the previous object its own
// object inherited from (a part does not jump objects). part_object: 0-based.
void match_levels(std::vector<Candidate> found, const TrackedFrame& now, const TrackedFrame& before,
                  const std::vector<std::uint32_t>& part_object, std::vector<std::uint32_t>& ids,
                  std::vector<char>& before_taken) {
  const auto parts_begin = std::partition(found.begin(), found.end(),
                                          [&](const Candidate& c) { return c.current < now.object_count; });
  std::vector<Candidate> parts(parts_begin, found.end());
  found.erase(parts_begin, found.end());
  match(std::move(found), ids, before_taken);
  std::erase_if(parts, [&](const Candidate& c) {
    const std::uint32_t owner = part_object[c.current - now.object_count];
    return owner == kNone || ids[owner] == kNone || ids[owner] != before.owner_ids[c.previous - before.object_count];
  });
  match(std::move(parts), ids, before_taken);
}

// Objects of this frame still without an id that lie where an absorbed object
// was (IoU >= kMinOverlap with its last cells) take its id back, best first.
void reclaim_absorbed(const AbsorbedIds& absorbed, TrackedFrame& now, std::vector<char>& reclaimed) {
  if (absorbed.segments.ids.empty()) return;
  std::vector<Candidate> found =
      candidates(now, absorbed.segments, shared_counts(now, absorbed.segments));
  std::erase_if(found, [&](const Candidate& c) { return c.current >= now.object_count || now.ids[c.current] != kNone; });
  match(std::move(found), now.ids, reclaimed);
}

// Previous objects that nothing inherited, each with the id of the current
// object holding most of its cells if that is at least kMinOverlap of them:
// (previous object, carrier id), ascending.
std::vector<std::pair<std::uint32_t, std::uint32_t>> absorptions(const TrackedFrame& now, const TrackedFrame& before,
                                                                  const std::vector<char>& before_taken,
                                                                  const SharedCounts& counts) {
  const std::uint64_t before_count = before.sizes.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> best(before.object_count, {0, kNone});  // (shared, current)
  for (const auto& [pair, shared] : counts) {
    const auto u = static_cast<std::uint32_t>(pair / before_count), v = static_cast<std::uint32_t>(pair % before_count);
    if (u < now.object_count && v < before.object_count && !before_taken[v] && shared > best[v].first)
      best[v] = {shared, u};
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t v = 0; v < before.object_count; ++v) {
    if (best[v].second != kNone && static_cast<double>(best[v].first) >= kMinOverlap * before.sizes[v])
      out.emplace_back(v, now.ids[best[v].second]);
  }
  return out;
}

// The cells of the chosen segments of `from` (segment -> its new index, kNone:
// not chosen) per grid, ascending: a monotone renumbering keeps the order.
std::array<std::vector<OccupiedCell>, 2> chosen_cells(const TrackedFrame& from, const std::vector<std::uint32_t>& index) {
  std::array<std::vector<OccupiedCell>, 2> out;
  if (std::all_of(index.begin(), index.end(), [](std::uint32_t i) { return i == kNone; })) return out;
  for (int g = 0; g < 2; ++g)
    for (const OccupiedCell& c : from.cells[g])
      if (index[c.segment] != kNone) out[g].push_back({c.cell, index[c.segment]});
  return out;
}

// The absorbed ids that go on: those kept (by `keep`: the new carrier id, kNone
// to drop) of `old`, one frame older, then the new absorptions of `before`'s
// objects at age 0.
AbsorbedIds next_absorbed(const AbsorbedIds& old, const std::vector<std::uint32_t>& keep,
                                  const TrackedFrame& before,
                                  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& absorbed_now) {
  AbsorbedIds next;
  std::vector<std::uint32_t> old_index(old.segments.ids.size(), kNone), new_index(before.ids.size(), kNone);
  const auto add = [&](std::uint32_t id, std::uint32_t size, std::uint32_t carrier, std::uint32_t age) {
    next.segments.ids.push_back(id);
    next.segments.sizes.push_back(size);
    next.carriers.push_back(carrier);
    next.ages.push_back(age);
    return static_cast<std::uint32_t>(next.segments.ids.size() - 1);
  };
  for (std::size_t e = 0; e < keep.size(); ++e)
    if (keep[e] != kNone) old_index[e] = add(old.segments.ids[e], old.segments.sizes[e], keep[e], old.ages[e] + 1);
  for (const auto& [v, carrier] : absorbed_now) new_index[v] = add(before.ids[v], before.sizes[v], carrier, 0);
  next.segments.object_count = static_cast<std::uint32_t>(next.segments.ids.size());
  const auto kept_cells = chosen_cells(old.segments, old_index), new_cells = chosen_cells(before, new_index);
  for (int g = 0; g < 2; ++g) {
    next.segments.cells[g].resize(kept_cells[g].size() + new_cells[g].size());
    std::merge(kept_cells[g].begin(), kept_cells[g].end(), new_cells[g].begin(), new_cells[g].end(),
               next.segments.cells[g].begin());
  }
  return next;
}

// What becomes of the absorbed ids after this frame: an id not taken back goes
// on with its carrier while the carrier is in this frame (or with the object
// that absorbed the carrier itself) and it is younger than kAbsorbedFrames;
// previous objects absorbed now join.
AbsorbedIds carry_absorbed(const AbsorbedIds& old, const std::vector<char>& reclaimed,
                                   const TrackedFrame& now, const TrackedFrame& before,
                                   const std::vector<char>& before_taken, const SharedCounts& counts) {
  const auto absorbed_now = absorptions(now, before, before_taken, counts);
  std::vector<std::uint32_t> alive(now.ids.begin(), now.ids.begin() + now.object_count);
  std::sort(alive.begin(), alive.end());
  std::vector<std::uint32_t> keep(old.segments.ids.size(), kNone);
  for (std::size_t e = 0; e < keep.size(); ++e) {
    if (reclaimed[e] || old.ages[e] + 1 >= kAbsorbedFrames) continue;
    const std::uint32_t carrier = old.carriers[e];
    if (std::binary_search(alive.begin(), alive.end(), carrier)) keep[e] = carrier;
    for (const auto& [v, new_carrier] : absorbed_now)
      if (before.ids[v] == carrier) keep[e] = new_carrier;
  }
  return next_absorbed(old, keep, before, absorbed_now);
}

// What occupied_cells checks as it scans the points: no label above its count.
void check_label_counts(const FrameSegments& frame) {
  const auto above = [](const Labels* labels, std::uint32_t count) {
    return labels != nullptr && std::any_of(labels->begin(), labels->end(), [&](std::uint32_t l) { return l > count; });
  };
  if (above(frame.objects, frame.object_count) || above(frame.parts, frame.part_count))
    throw Error("segment tracking: a label above its count");
}

}  // namespace

TrackedIds first_frame_ids(const FrameSegments& frame, std::uint32_t first_id) {
  check_frame(frame);
  check_label_counts(frame);
  const std::uint32_t objects = frame.object_count, parts = frame.parts ? frame.part_count : 0;
  if (std::uint64_t{first_id} + objects + parts > kNone) throw Error("segment tracking: the ids are used up");
  TrackedIds out;
  out.new_ids.resize(objects + parts);
  std::iota(out.new_ids.begin(), out.new_ids.end(), first_id);
  out.object_ids.assign(out.new_ids.begin(), out.new_ids.begin() + objects);
  out.part_ids.assign(out.new_ids.begin() + objects, out.new_ids.end());
  return out;
}

struct SegmentTracker::History {
  TrackedFrame previous;  // what the next frame is matched against
  AbsorbedIds absorbed;   // ids merged into a previous object, which a split gives back
};

SegmentTracker::SegmentTracker(std::uint32_t first_id) : next_id_(first_id), history_(std::make_unique<History>()) {}
SegmentTracker::~SegmentTracker() = default;
SegmentTracker::SegmentTracker(SegmentTracker&&) noexcept = default;
SegmentTracker& SegmentTracker::operator=(SegmentTracker&&) noexcept = default;

TrackedIds SegmentTracker::update(const FrameSegments& frame) {
  check_frame(frame);
  const std::uint32_t objects = frame.object_count, parts = frame.parts ? frame.part_count : 0;
  OccupiedCells occupied = occupied_cells(frame, kCellSize);
  const std::vector<std::uint32_t>& part_object = occupied.part_object;
  TrackedFrame now;
  now.sizes = cell_counts(occupied, objects + parts);
  now.cells = std::move(occupied.grids);
  now.object_count = objects;
  now.ids.assign(objects + parts, kNone);
  std::vector<char> before_taken(history_->previous.ids.size(), 0);
  const SharedCounts counts = shared_counts(now, history_->previous);
  match_levels(candidates(now, history_->previous, counts), now, history_->previous, part_object, now.ids, before_taken);
  std::vector<char> reclaimed(history_->absorbed.segments.ids.size(), 0);
  reclaim_absorbed(history_->absorbed, now, reclaimed);

  TrackedIds out;
  for (std::uint32_t& id : now.ids) {
    if (id != kNone) continue;
    if (next_id_ == kNone) throw Error("segment tracking: the ids are used up");
    out.new_ids.push_back(id = next_id_++);
  }
  for (std::size_t v = 0; v < before_taken.size(); ++v)
    if (!before_taken[v]) out.gone_ids.push_back(history_->previous.ids[v]);
  std::sort(out.gone_ids.begin(), out.gone_ids.end());
  for (const std::uint32_t owner : part_object) now.owner_ids.push_back(owner == kNone ? kNone : now.ids[owner]);
  out.object_ids.assign(now.ids.begin(), now.ids.begin() + objects);
  out.part_ids.assign(now.ids.begin() + objects, now.ids.end());
  history_->absorbed = carry_absorbed(history_->absorbed, reclaimed, now, history_->previous, before_taken, counts);
  history_->previous = std::move(now);
  return out;
}

}  // namespace lccp
