// The robot preset (config/robot.yaml: support plane, P1 parts, objects grouped from them) on the
// synthetic table-top scene, frame after frame through the pipeline, scored
// against the scene's ground truth (object n's parts n * 10 + k; the mug's
// handle its own part):
// - every object's best-matching segment keeps its id in >= 97 % of the pairs of
//   consecutive frames in which the object is visible;
// - how often the handle is its own part of the mug object (its pieces one part:
//   PartGroups::part) with its centroid
//   within 1 cm of the true handle's, in the frames where >= 200 handle points
//   are visible, and where it is when it is not (in the body's part, or in an
//   object apart from the mug's). The robot issue asks for 95 % and 90 % on the
//   bundled recording; the rendered period is held to what it gives today,
//   rounded down (perf/RESULTS.md, "Issue 33").
// Run on the bundled recording and on the scene's whole 10 s period rendered in
// process; each prints its figures (perf/RESULTS.md quotes them).
#include <cstdio>
#include <filesystem>
#include <algorithm>
#include <map>
#include <optional>

#include <gtest/gtest.h>

#include "lccp/capture/openni_sources.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/pipeline/pipeline.hpp"
#include "lccp/synthetic/tabletop_scene.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;
using synthetic::object_label;
using synthetic::object_of_label;

constexpr std::size_t kMinHandlePoints = 200;   // the "at least 200 handle points visible"
constexpr std::size_t kMinVisiblePoints = 100;  // an object counts as visible for the id pairs
constexpr double kHandleCentroidToleranceM = 0.01;

const fs::path kRecording = fs::path(LCCP_TEST_DATA_DIR) / ".." / ".." / "recordings" / "synthetic_tabletop.oni";

// The id holding most of the given points in `ids` (0 and the support excluded), 0 if none.
std::uint32_t best_id(const Labels& ids, const std::vector<std::size_t>& points, std::uint32_t support_id) {
  std::map<std::uint32_t, std::size_t> votes;
  for (std::size_t i : points) {
    if (ids[i] != 0 && ids[i] != support_id) ++votes[ids[i]];
  }
  std::uint32_t best = 0;
  std::size_t most = 0;
  for (const auto& [id, count] : votes) {
    if (count > most) best = id, most = count;
  }
  return best;
}

// The part with this id, and the id of its object; null if none.
const SegmentGeometry* find_part(const SceneSegmentation& scene, std::uint32_t id, std::uint32_t& object) {
  for (const ObjectSegments& o : scene.segments) {
    for (const SegmentGeometry& part : o.parts) {
      if (part.id == id) {
        object = o.object.id;
        return &part;
      }
    }
  }
  return nullptr;
}

struct RobotFigures {
  int handle_frames = 0;    // frames with >= 200 visible handle points
  int handle_own_part = 0;  // ... where the handle is its own part of the mug object
  int handle_found = 0;     // ... and that part's centroid is within 1 cm of the true handle's
  int handle_in_body = 0;   // ... where the handle's part is the body's
  int handle_apart = 0;     // ... where the handle's part is in another object than the mug's
  double worst_centroid_error_m = 0;
  int id_pairs = 0;  // consecutive frames in which an object is visible
  int id_kept = 0;   // ... and its best segment kept its id
  std::map<std::uint32_t, std::uint32_t> previous_id;  // object n -> its segment's id in the previous frame

  void add(const FrameResult& result, const Labels& truth);
  void add_handle(const FrameResult& result, const Labels& truth);
  void add_ids(const FrameResult& result, const Labels& truth);
};

void RobotFigures::add(const FrameResult& result, const Labels& truth) {
  ASSERT_TRUE(result.error.empty()) << result.error;
  ASSERT_EQ(truth.size(), result.frame.cloud.size());
  add_handle(result, truth);
  add_ids(result, truth);
}

void RobotFigures::add_handle(const FrameResult& result, const Labels& truth) {
  const std::vector<Eigen::Vector3f>& points = result.frame.cloud.points;
  const SceneSegmentation& scene = result.segmentation;
  std::vector<std::size_t> handle, body, mug;
  Eigen::Vector3d handle_sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (!is_finite(points[i]) || object_of_label(truth[i]) != synthetic::kMugObject) continue;
    mug.push_back(i);
    if (truth[i] == object_label(synthetic::kMugObject, synthetic::kHandlePart)) {
      handle.push_back(i);
      handle_sum += points[i].cast<double>();
    } else {
      body.push_back(i);
    }
  }
  if (handle.size() < kMinHandlePoints) return;
  ++handle_frames;
  const std::uint32_t part = best_id(scene.labels, handle, scene.support_id);
  std::uint32_t part_object = 0;
  const SegmentGeometry* geometry = find_part(scene, part, part_object);
  if (geometry == nullptr) return;  // most handle points in no segment
  const bool in_body = part == best_id(scene.labels, body, scene.support_id);
  const bool apart = part_object != best_id(scene.objects, mug, scene.support_id);
  handle_in_body += in_body, handle_apart += apart && !in_body;
  if (in_body || apart) return;
  ++handle_own_part;
  const double error = (geometry->centroid.cast<double>() - handle_sum / static_cast<double>(handle.size())).norm();
  worst_centroid_error_m = std::max(worst_centroid_error_m, error);
  if (error <= kHandleCentroidToleranceM) ++handle_found;
}

void RobotFigures::add_ids(const FrameResult& result, const Labels& truth) {
  const SceneSegmentation& scene = result.segmentation;
  std::map<std::uint32_t, std::vector<std::size_t>> by_object;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (object_of_label(truth[i]) != 0 && is_finite(result.frame.cloud.points[i])) by_object[object_of_label(truth[i])].push_back(i);
  }
  std::map<std::uint32_t, std::uint32_t> ids;
  for (const auto& [object, points] : by_object) {
    if (points.size() < kMinVisiblePoints) continue;
    ids[object] = best_id(scene.objects, points, scene.support_id);
    const auto previous = previous_id.find(object);
    if (previous == previous_id.end()) continue;
    ++id_pairs;
    id_kept += previous->second == ids[object] ? 1 : 0;
  }
  previous_id = std::move(ids);
}

SceneSegmenter robot_segmenter() {
  return SceneSegmenter(load_config(fs::path(LCCP_CONFIG_DIR) / "robot.yaml"));
}

RobotFigures run(FrameSource& source, const synthetic::TabletopScene& scene) {
  const SceneSegmenter segmenter = robot_segmenter();
  RobotFigures figures;
  const PipelineOutcome outcome = Pipeline(segmenter, PipelineConfig{2}).run(source, [&](FrameResult& result) {
    figures.add(result, scene.render(synthetic::frame_of_timestamp_us(result.frame.timestamp_us)).labels);
  });
  EXPECT_TRUE(outcome.error.empty()) << outcome.error;
  EXPECT_EQ(outcome.stats.frames_failed, 0u);
  return figures;
}

// The least shares of the handle frames where the handle is its own part of the
// mug object, and where that part's centroid is also within 1 cm of the truth.
struct HandleShares {
  double own_part = 0, found = 0;
};

void report_and_check(const char* name, const RobotFigures& f, HandleShares least) {
  std::printf("%s: handle visible (>= %zu points) in %d frames; its own part of the mug in %d (%.1f %%); "
              "and centroid within 1 cm in %d (%.1f %%), worst %.1f mm; in the body's part in %d, in another "
              "object in %d; ids kept in %d of %d pairs (%.2f %%)\n",
              name, kMinHandlePoints, f.handle_frames, f.handle_own_part, 100.0 * f.handle_own_part / f.handle_frames,
              f.handle_found, 100.0 * f.handle_found / f.handle_frames, 1000 * f.worst_centroid_error_m,
              f.handle_in_body, f.handle_apart, f.id_kept,
              f.id_pairs, 100.0 * f.id_kept / f.id_pairs);
  ASSERT_GT(f.handle_frames, 0);
  ASSERT_GT(f.id_pairs, 0);
  EXPECT_GE(f.id_kept, 0.97 * f.id_pairs);
  EXPECT_GE(f.handle_own_part, least.own_part * f.handle_frames);
  EXPECT_GE(f.handle_found, least.found * f.handle_frames);
}

// The scene's frames 0..n-1 as a sensor would deliver them, timestamps at 30 Hz.
class RenderedScene : public FrameSource {
 public:
  RenderedScene(const synthetic::TabletopScene& scene, std::uint64_t frames) : scene_(scene), frames_(frames) {}
  std::optional<Frame> next(std::stop_token) override {
    if (next_ == frames_) return std::nullopt;
    Frame frame;
    frame.index = next_;
    frame.timestamp_us = synthetic::timestamp_us_of_frame(next_++);
    frame.captured = Clock::now();
    frame.depth = scene_.render(frame.index).depth;
    return frame;
  }
  std::optional<std::uint64_t> frame_count() const override { return frames_; }
  bool is_live() const override { return false; }

 private:
  const synthetic::TabletopScene& scene_;
  std::uint64_t frames_;
  std::uint64_t next_ = 0;
};

// The id holding most of the points with truth label `label` (0 and the support excluded).
std::uint32_t id_of_label(const Labels& ids, const Labels& truth, std::uint32_t label, std::uint32_t support_id) {
  std::vector<std::size_t> points;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] == label) points.push_back(i);
  }
  return best_id(ids, points, support_id);
}

// Frame `index` of the scene through the robot preset, with the mug's handle
// and body truth labels.
struct MugFrame {
  synthetic::SyntheticFrame frame;
  SceneSegmentation seg;
  std::uint32_t handle = object_label(synthetic::kMugObject, synthetic::kHandlePart);
  std::uint32_t body = object_label(synthetic::kMugObject);
};

MugFrame mug_frame(std::uint64_t index) {
  const synthetic::TabletopScene scene;
  MugFrame m{scene.render(index), {}};
  m.seg = robot_segmenter().segment(back_project(m.frame.depth));
  return m;
}

// Frame 31 of the scene: the mug's handle ends behind the mug's silhouette,
// about 1 cm from the body's nearest visible points, so no voxel of it touches
// the body, and its lowest point is 1.8 cm above the table (object_contact_m:
// 1.5). It is held by the body it vanishes behind (detail::held_behind): a
// part of the mug object, not the body's part.
TEST(RobotScene, AHandleWhoseEndsTheMugHidesIsAPartOfTheMug) {
  const auto [frame, seg, handle, body] = mug_frame(31);
  EXPECT_NE(id_of_label(seg.labels, frame.labels, handle, seg.support_id),
            id_of_label(seg.labels, frame.labels, body, seg.support_id));
  const std::uint32_t mug = id_of_label(seg.objects, frame.labels, body, seg.support_id);
  EXPECT_NE(mug, 0u);
  EXPECT_EQ(id_of_label(seg.objects, frame.labels, handle, seg.support_id), mug);
}

// Frame 12 of the scene: P1 cuts the mug's handle in two, the upper half
// resting on the lower one, both hanging off the body (a third of the handle's
// points, where it meets the body, go to the body's part). Pieces off the
// support on no body of their own that meet in one object are one part
// (group_parts, PartGroups::part): the handle's points outside the body's
// part are in one part, of the mug object.
TEST(RobotScene, AHandleCutInTwoIsOnePartOfTheMug) {
  const auto [frame, seg, handle, body] = mug_frame(12);
  const std::uint32_t body_part = id_of_label(seg.labels, frame.labels, body, seg.support_id);
  std::map<std::uint32_t, std::size_t> pieces;  // handle points per part, the body's part left out
  std::size_t outside_body = 0;
  for (std::size_t i = 0; i < frame.labels.size(); ++i) {
    if (frame.labels[i] != handle || seg.labels[i] == body_part) continue;
    ++outside_body, ++pieces[seg.labels[i]];
  }
  ASSERT_GE(outside_body, 100u);
  const auto largest = std::max_element(pieces.begin(), pieces.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; });
  EXPECT_GE(largest->second, 0.95 * static_cast<double>(outside_body));
  EXPECT_EQ(id_of_label(seg.objects, frame.labels, handle, seg.support_id),
            id_of_label(seg.objects, frame.labels, body, seg.support_id));
}

// Frame 41 of the scene: the mug's handle ends behind the mug's silhouette,
// where the mug's points nearest its ends are not of the part that stands on
// the support. The handle is held behind the mug object, whichever of its
// parts is nearest (detail::held_behind); before, only a standing part could
// hold it, and most of the handle was an object of its own.
TEST(RobotScene, AHandleHeldBehindAnyPartOfTheMugIsOfTheMug) {
  const auto [frame, seg, handle, body] = mug_frame(41);
  const std::uint32_t mug = id_of_label(seg.objects, frame.labels, body, seg.support_id);
  EXPECT_NE(id_of_label(seg.labels, frame.labels, handle, seg.support_id),
            id_of_label(seg.labels, frame.labels, body, seg.support_id));
  EXPECT_EQ(id_of_label(seg.objects, frame.labels, handle, seg.support_id), mug);
}

// Frame 38 of the scene: P1 cuts the mug's handle in two and neither half
// meets the body where the sensor sees it. The upper half vanishes behind the
// mug (held_behind); the lower half, 18 mm above the table, meets only the
// upper half. A loose piece that meets another is held by what holds that one
// (join_held_behind): the whole handle is one part, of the mug object (before,
// the lower half was an object of its own).
TEST(RobotScene, AHandleHalfMeetingOnlyTheHeldHalfIsOfTheMug) {
  const auto [frame, seg, handle, body] = mug_frame(38);
  std::map<std::uint32_t, std::size_t> parts;  // handle points per part
  std::size_t handle_points = 0, in_mug = 0;
  const std::uint32_t mug = id_of_label(seg.objects, frame.labels, body, seg.support_id);
  ASSERT_NE(mug, 0u);
  for (std::size_t i = 0; i < frame.labels.size(); ++i) {
    if (frame.labels[i] != handle || seg.labels[i] == 0) continue;
    ++handle_points, ++parts[seg.labels[i]];
    in_mug += seg.objects[i] == mug;
  }
  ASSERT_GE(handle_points, 200u);
  const auto largest = std::max_element(parts.begin(), parts.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; });
  EXPECT_GE(largest->second, 0.95 * static_cast<double>(handle_points));
  EXPECT_GE(in_mug, 0.95 * static_cast<double>(handle_points));
}

TEST(RobotScene, BundledRecordingIdsStayStable) {
  const synthetic::TabletopScene scene;
  const std::unique_ptr<FrameSource> recording = open_recording(kRecording);
  report_and_check("recording", run(*recording, scene), {0.95, 0.90});  // the shares
}

TEST(RobotScene, WholeScenePeriodIdsStayStable) {
  const synthetic::TabletopScene scene;
  RenderedScene frames(scene, 300);  // 10 s: every motion of the scene once
  report_and_check("rendered 300 frames", run(frames, scene), {0.85, 0.80});  // 136 and 130 of 160
}

}  // namespace
}  // namespace lccp
