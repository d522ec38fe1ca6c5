#include "lccp/objects/scene.hpp"

#include <algorithm>
#include <iterator>
#include <numeric>
#include <utility>

#include <tbb/parallel_for.h>

#include "lccp/error.hpp"
#include "lccp/objects/grouping.hpp"

namespace lccp {
namespace {

constexpr std::uint32_t kSupportId = 1;  // trackers start after it when the config removes a support plane

// Point indices per object 1..K (a counting sort by object label).
std::vector<std::vector<std::uint32_t>> points_by_object(const Labels& objects, std::uint32_t object_count) {
  std::vector<std::vector<std::uint32_t>> members(object_count);
  for (std::uint32_t i = 0; i < objects.size(); ++i) {
    if (objects[i] != 0) members[objects[i] - 1].push_back(i);
  }
  return members;
}

PointCloud gather(const CloudView& cloud, const std::vector<std::uint32_t>& indices) {
  PointCloud part;
  part.width = static_cast<std::uint32_t>(indices.size());
  part.points.reserve(indices.size());
  for (std::uint32_t i : indices) part.points.push_back(cloud.points[i]);
  if (cloud.has_colors()) {
    for (std::uint32_t i : indices) part.colors.push_back(cloud.colors[i]);
  }
  if (cloud.has_normals()) {
    for (std::uint32_t i : indices) part.normals.push_back(cloud.normals[i]);
  }
  return part;
}

// Dense global part labels: object k's parts come after those of objects 1..k-1.
std::vector<std::uint32_t> part_offsets(const std::vector<std::unique_ptr<ObjectParts>>& parts) {
  std::vector<std::uint32_t> offsets(parts.size() + 1, 0);
  for (std::size_t k = 0; k < parts.size(); ++k) offsets[k + 1] = offsets[k] + parts[k]->work.result.segment_count;
  return offsets;
}

Labels dense_part_labels(const SceneWork& w, const std::vector<std::uint32_t>& offsets) {
  Labels labels(w.objects.cloud.size(), 0);
  for (std::size_t k = 0; k < w.parts.size(); ++k) {
    const ObjectParts& object = *w.parts[k];
    for (std::size_t j = 0; j < object.indices.size(); ++j) {
      const std::uint32_t local = object.work.result.labels[j];
      if (local != 0) labels[object.indices[j]] = offsets[k] + local;
    }
  }
  return labels;
}

// Dense labels (1..n, 0 none) to ids (ids[label - 1]); the support's points get its id.
Labels to_ids(const Labels& dense, const std::vector<std::uint32_t>& ids, const SegmentationWork& objects,
              std::uint32_t support_id) {
  Labels out(dense.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, dense.size()), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      if (dense[i] != 0) out[i] = ids[dense[i] - 1];
      else if (objects.support && objects.support->on_plane[i]) out[i] = support_id;
    }
  });
  return out;
}

// Drops the objects of fewer than min_points points (FilterConfig::
// min_object_points): their points and supervoxels get label 0, and the others
// are numbered 1..K again in their order (largest first, as relabel_by_size
// left them). Returns the renaming, old label -> new (0 -> 0).
std::vector<std::uint32_t> drop_small_objects(SegmentationWork& w, std::uint32_t min_points) {
  const std::uint32_t count = w.result.segment_count;
  std::vector<std::uint32_t> points(std::size_t{count} + 1, 0);
  for (const std::uint32_t label : w.result.labels) ++points[label];
  std::vector<std::uint32_t> renamed(std::size_t{count} + 1, 0);
  std::uint32_t kept = 0;
  for (std::uint32_t k = 1; k <= count; ++k) {
    if (points[k] >= min_points) renamed[k] = ++kept;
  }
  if (kept == count) return renamed;
  for (std::uint32_t& label : w.result.labels) label = renamed[label];
  for (std::uint32_t& segment : w.segment_of_supervoxel) segment = renamed[segment];
  w.result.segment_count = kept;
  return renamed;
}

// `labels` (0: none) through `map` (indexed by label).
template <typename Vector>
Vector mapped(Vector labels, const std::vector<std::uint32_t>& map) {
  for (auto& label : labels) label = map[label];
  return labels;
}

// The parts renumbered object by object (objects 1..K; a part of object 0 is
// dropped): map[old part label] = new label, and the objects' offsets.
std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> parts_by_object(
    const std::vector<std::uint32_t>& object_of_part, std::uint32_t objects) {
  std::vector<std::uint32_t> order(object_of_part.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return object_of_part[a] < object_of_part[b]; });
  std::vector<std::uint32_t> map(object_of_part.size() + 1, 0), offsets(std::size_t{objects} + 1, 0);
  std::uint32_t next = 0;
  for (const std::uint32_t part : order) {
    if (object_of_part[part] == 0) continue;
    map[part + 1] = ++next;
    offsets[object_of_part[part]] = next;
  }
  for (std::uint32_t k = 1; k <= objects; ++k) offsets[k] = std::max(offsets[k], offsets[k - 1]);
  return {std::move(map), std::move(offsets)};
}

// min_object_points applies to objects; parts keep every piece of their object.
void check_min_object_points(const SceneConfig& config) {
  if (config.parts && config.parts->filter.min_object_points != 0) {
    throw Error("config key 'parts.min_object_points' must be 0: it applies to objects; parts keep every piece");
  }
}

void rename(SegmentGeometry& segment, const std::vector<std::uint32_t>& ids, std::uint32_t offset) {
  segment.id = ids[offset + segment.id - 1];
  for (Neighbour& n : segment.adjacent) n.id = ids[offset + n.id - 1];
}

}  // namespace

SceneSegmenter::SceneSegmenter(const SceneConfig& config) : config_(config), objects_(config.objects) {
  validate(config_);
  check_min_object_points(config_);
}

SegmentTracker SceneSegmenter::new_tracker() const { return SegmentTracker(first_id()); }

std::uint32_t SceneSegmenter::first_id() const { return config_.objects.support.enabled ? kSupportId + 1 : 1; }

// The robot application on one frame (Sec. III.C, Fig. 5), one line per stage.
SceneSegmentation SceneSegmenter::segment(const CloudView& cloud) const {
  SceneWork w(cloud);
  objects_.segment(w.objects);  // stages 0-8: the objects (Fig. 5 B)
  partition_objects(w);         // 9: their parts (Fig. 5 C)
  describe(w);                  // 10: geometry
  assign_ids(w, nullptr);       // 11: ids in label order
  return w.take_result();
}

void SceneSegmenter::run_stage(Stage stage, SceneWork& w) const {
  switch (stage) {
    case Stage::support: return objects_.leave_out(w.objects);
    case Stage::voxelize: return objects_.build_voxels(w.objects);
    case Stage::normals: return objects_.compute_normals(w.objects);
    case Stage::seeds: return objects_.place_seeds(w.objects);
    case Stage::growth: return objects_.grow_patches(w.objects);
    case Stage::adjacency: return objects_.build_graph(w.objects);
    case Stage::classify: return objects_.classify_convexity(w.objects);
    case Stage::components: return objects_.merge_convex(w.objects);
    case Stage::filter: return objects_.filter_small(w.objects);
    case Stage::parts: return partition_objects(w);
    case Stage::geometry: return describe(w);
    case Stage::ids: break;
  }
  throw Error("stage ids needs the stream's tracker: SceneSegmenter::assign_ids");
}

// Stage 9 (Fig. 5 C): the objects of fewer than min_object_points points
// dropped, then every object segmented on its own with the part-level config,
// in the binning its points had at the object level. With objects_from_parts:
// group_objects.
void SceneSegmenter::partition_objects(SceneWork& w) const {
  const StageTimer timer(w.objects.result.times, Stage::parts);
  if (config_.objects.grouping.objects_from_parts) return group_objects(w);
  drop_small_objects(w.objects, config_.objects.filter.min_object_points);
  if (!config_.parts) return;
  LccpConfig config = *config_.parts;
  if (config.voxels.binning == Binning::automatic) config.voxels.binning = w.objects.grid.binning;
  const LccpSegmenter segmenter(config);
  std::vector<std::vector<std::uint32_t>> members =
      points_by_object(w.objects.result.labels, w.objects.result.segment_count);
  w.parts.resize(members.size());
  tbb::parallel_for(std::size_t{0}, members.size(), [&](std::size_t k) {
    w.parts[k] = std::make_unique<ObjectParts>(gather(w.objects.cloud, members[k]));
    w.parts[k]->indices = std::move(members[k]);
    segmenter.segment(w.parts[k]->work);
  });
}

// Stage 9 with objects_from_parts: the first level's segments are the parts;
// the objects they group into (group_parts) take over the work's labels, the
// objects of fewer than min_object_points points dropped, and the parts keep
// theirs in w.grouped, the pieces of one part (PartGroups::part) as one,
// renumbered object by object.
void SceneSegmenter::group_objects(SceneWork& w) const {
  SegmentationWork& first = w.objects;
  auto [object, one_part] = group_parts(first, config_.objects);
  object.insert(object.begin(), 0u), one_part.insert(one_part.begin(), 0u);  // indexed by part label
  const Labels part_labels = mapped(std::exchange(first.result.labels, mapped(first.result.labels, object)), one_part);
  const std::vector<std::uint32_t> part_supervoxels =
      mapped(std::exchange(first.segment_of_supervoxel, mapped(first.segment_of_supervoxel, object)), one_part);
  first.result.segment_count = object.size() > 1 ? *std::max_element(object.begin(), object.end()) : 0;
  const std::vector<std::uint32_t> renamed = drop_small_objects(first, config_.objects.filter.min_object_points);
  object = mapped(std::move(object), renamed);
  for (std::size_t k = 1; k < object.size(); ++k) object[k] = one_part[k] == k ? object[k] : 0;  // pieces of one part
  object.erase(object.begin());
  auto [map, offsets] = parts_by_object(object, first.result.segment_count);
  w.grouped = GroupedParts{mapped(part_labels, map), mapped(part_supervoxels, map), std::move(offsets)};
}

// Stage 10: the geometry of every object and of its parts, ids still dense labels.
void SceneSegmenter::describe(SceneWork& w) const {
  const StageTimer timer(w.objects.result.times, Stage::geometry);
  const std::optional<Plane> plane =
      w.objects.support ? std::optional<Plane>(w.objects.support->plane) : std::nullopt;
  std::vector<SegmentGeometry> objects = describe_segments(w.objects, plane);
  w.segments.resize(objects.size());
  tbb::parallel_for(std::size_t{0}, objects.size(), [&](std::size_t k) {
    w.segments[k].object = std::move(objects[k]);
    if (k < w.parts.size()) w.segments[k].parts = describe_segments(w.parts[k]->work, plane);
  });
  if (!w.grouped) return;
  const GroupedParts& g = *w.grouped;
  std::vector<SegmentGeometry> parts = describe_segments(w.objects, {g.labels, g.supervoxels, g.offsets.back()}, plane);
  for (std::size_t k = 0; k < w.segments.size(); ++k) {
    w.segments[k].parts.assign(std::make_move_iterator(parts.begin() + g.offsets[k]),
                               std::make_move_iterator(parts.begin() + g.offsets[k + 1]));
  }
}

// Stage 11: ids matched to the previous frame's; labels and geometry renamed to them.
void SceneSegmenter::assign_ids(SceneWork& w, SegmentTracker* tracker) const {
  const StageTimer timer(w.objects.result.times, Stage::ids);
  const bool two = config_.two_levels();
  const std::vector<std::uint32_t> offsets = w.grouped ? w.grouped->offsets : part_offsets(w.parts);
  const Labels parts = w.grouped ? std::move(w.grouped->labels) : config_.parts ? dense_part_labels(w, offsets) : Labels{};
  const SegmentationResult& level1 = w.objects.result;
  const FrameSegments frame{w.objects.cloud.points, &level1.labels, level1.segment_count, two ? &parts : nullptr,
                            offsets.back()};
  TrackedIds ids = tracker ? tracker->update(frame) : first_frame_ids(frame, first_id());
  SceneSegmentation& r = w.result;
  r.support_id = w.objects.support ? kSupportId : 0;
  r.labels = to_ids(two ? parts : level1.labels, two ? ids.part_ids : ids.object_ids, w.objects, r.support_id);
  if (two) r.objects = to_ids(level1.labels, ids.object_ids, w.objects, r.support_id);
  for (std::size_t k = 0; k < w.segments.size(); ++k) {
    rename(w.segments[k].object, ids.object_ids, 0);
    for (SegmentGeometry& part : w.segments[k].parts) rename(part, ids.part_ids, w.grouped ? 0 : offsets[k]);
  }
  r.segments = std::move(w.segments);
  r.support_plane = w.objects.support ? std::optional<Plane>(w.objects.support->plane) : std::nullopt;
  r.support_noise_m = w.objects.support ? w.objects.support->noise_m : 0.0f;
  r.new_ids = std::move(ids.new_ids);
  r.gone_ids = std::move(ids.gone_ids);
  r.voxel_count = level1.voxel_count;
  r.supervoxel_count = level1.supervoxel_count;
  r.object_count = level1.segment_count;
  r.segment_count = two ? offsets.back() : level1.segment_count;
}

}  // namespace lccp
