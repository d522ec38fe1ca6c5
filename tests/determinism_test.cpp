// Whole-pipeline tests: every stage gives bitwise identical results with 1, 2 and 4
// threads, with either supervoxel growth, on real and synthetic scenes; the segmentation labels every finite point densely; LCCP separates what the
// paper says it separates; and the object scores on real mOSD scenes stay above a floor.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "lccp/config.hpp"
#include "lccp/core/adjacency.hpp"
#include "lccp/core/convexity.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/core/normals.hpp"
#include "lccp/core/segments.hpp"
#include "lccp/core/supervoxels.hpp"
#include "lccp/core/voxel_grid.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/metrics/scores.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

// The mOSD scenes, each read once.
const LabelledCloud& scene(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<LabelledCloud>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<LabelledCloud>(read_cloud(std::filesystem::path(LCCP_TEST_DATA_DIR) / (name + ".pcd")));
  }
  return *slot;
}

// A scene by name: an mOSD frame, or "box_on_table", a box on a table rendered
// by the synthetic camera (test_clouds.hpp).
const PointCloud& cloud_of(const std::string& name) {
  if (name != "box_on_table") return scene(name).cloud;
  static const PointCloud box = test::render(test::box_on_table().rects).cloud;
  return box;
}

// The default config with the given supervoxel growth.
LccpConfig with_growth(Growth growth) {
  LccpConfig config;
  config.supervoxels.growth = growth;
  return config;
}

const char* growth_name(Growth growth) { return growth == Growth::flood ? "flood" : "vccs"; }

// Runs f with at most n threads: the global limit plus an arena of exactly n slots (so 4
// threads are used even when the machine reports fewer cores).
template <class F>
auto with_threads(int n, F&& f) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(n));
  tbb::task_arena arena(n);
  return arena.execute(std::forward<F>(f));
}

struct StageOutputs {
  VoxelGrid grid;
  VoxelNormals voxel_normals;
  std::vector<std::uint32_t> seeds;
  Supervoxels sv;
  std::vector<Edge> edges;
  std::vector<std::uint8_t> convex;
  std::vector<std::uint32_t> components;
  std::vector<std::uint32_t> filtered;  // after merge_small_segments + relabel_by_size
  std::uint32_t segment_count = 0;
  SegmentationResult result;
};

StageOutputs run_stages(const PointCloud& cloud, const LccpConfig& cfg) {
  StageOutputs o;
  o.grid = voxelize(cloud, cfg.voxels);
  o.voxel_normals = estimate_voxel_normals(o.grid, cfg.normals);
  o.seeds = select_seeds(o.grid, cfg.supervoxels, cfg.voxels.voxel_size_m);
  o.sv = grow_supervoxels(o.grid, o.voxel_normals, o.seeds, cfg);
  o.edges = supervoxel_adjacency(o.grid, o.sv);
  o.convex = classify_edges(o.edges, o.sv.centroids, o.sv.normals, cfg.convexity,
                            PatchSizes{cfg.voxels.voxel_size_m, cfg.supervoxels.seed_size_m});
  o.components = convex_components(o.sv.size(), o.edges, o.convex);
  o.filtered = o.components;
  merge_small_segments(o.filtered, o.edges, cfg.filter.n_filter_supervoxels,
                       EdgeRanks{edge_convexity(o.edges, o.sv.centroids, o.sv.normals), {}});
  o.segment_count = relabel_by_size(o.filtered);
  o.result = LccpSegmenter(cfg).segment(cloud);
  return o;
}

// Bitwise equality of two arrays; on failure names the first differing element.
template <class T>
::testing::AssertionResult same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) {
    return ::testing::AssertionFailure() << "sizes differ: " << a.size() << " vs " << b.size();
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(&a[i], &b[i], sizeof(T)) != 0) return ::testing::AssertionFailure() << "first difference at " << i;
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult same_rows(const CompressedRows& a, const CompressedRows& b) {
  auto r = same_bits(a.offsets, b.offsets);
  if (!r) return r << " (offsets)";
  r = same_bits(a.items, b.items);
  if (!r) return r << " (items)";
  return r;
}

std::vector<std::uint32_t> edge_words(const std::vector<Edge>& edges) {
  std::vector<std::uint32_t> w;
  for (const Edge& e : edges) w.insert(w.end(), {e.a, e.b});
  return w;
}

void expect_identical(const StageOutputs& ref, const StageOutputs& got) {
  // Stage 1
  EXPECT_TRUE(same_bits(ref.grid.centroids, got.grid.centroids)) << "voxel centroids";
  EXPECT_TRUE(same_bits(ref.grid.colors, got.grid.colors)) << "voxel colours";
  EXPECT_TRUE(same_bits(ref.grid.mean_normals, got.grid.mean_normals)) << "voxel mean normals";
  EXPECT_TRUE(same_rows(ref.grid.points, got.grid.points)) << "voxel points";
  EXPECT_TRUE(same_rows(ref.grid.neighbors, got.grid.neighbors)) << "voxel neighbours";
  EXPECT_TRUE(same_bits(ref.grid.voxel_of_point, got.grid.voxel_of_point)) << "voxel_of_point";
  // Stage 2
  EXPECT_TRUE(same_bits(ref.voxel_normals.directions, got.voxel_normals.directions) && ref.voxel_normals.planar == got.voxel_normals.planar) << "voxel normals";
  // Stage 3
  EXPECT_TRUE(same_bits(ref.seeds, got.seeds)) << "seeds";
  EXPECT_TRUE(same_bits(ref.sv.supervoxel_of_voxel, got.sv.supervoxel_of_voxel)) << "supervoxel_of_voxel";
  EXPECT_TRUE(same_bits(ref.sv.centroids, got.sv.centroids)) << "supervoxel centroids";
  EXPECT_TRUE(same_bits(ref.sv.normals, got.sv.normals)) << "supervoxel normals";
  EXPECT_TRUE(same_bits(ref.sv.colors, got.sv.colors)) << "supervoxel colours";
  EXPECT_TRUE(same_bits(ref.sv.voxel_counts, got.sv.voxel_counts)) << "supervoxel voxel counts";
  // Stages 4-6
  EXPECT_TRUE(same_bits(edge_words(ref.edges), edge_words(got.edges))) << "adjacency";
  EXPECT_TRUE(same_bits(ref.convex, got.convex)) << "edge classification";
  EXPECT_TRUE(same_bits(ref.components, got.components)) << "convex components";
  EXPECT_TRUE(same_bits(ref.filtered, got.filtered)) << "filtered segments";
  EXPECT_EQ(ref.segment_count, got.segment_count);
  // The whole pipeline
  EXPECT_TRUE(same_bits(ref.result.labels, got.result.labels)) << "labels";
  EXPECT_EQ(ref.result.voxel_count, got.result.voxel_count);
  EXPECT_EQ(ref.result.supervoxel_count, got.result.supervoxel_count);
  EXPECT_EQ(ref.result.segment_count, got.result.segment_count);
}

// The one-thread result of a scene with a growth, computed once.
const StageOutputs& reference(const std::string& name, Growth growth) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, Growth>, std::unique_ptr<StageOutputs>> cache;
  const PointCloud& cloud = cloud_of(name);
  std::lock_guard lock(mutex);
  auto& slot = cache[{name, growth}];
  if (!slot) slot = std::make_unique<StageOutputs>(with_threads(1, [&] { return run_stages(cloud, with_growth(growth)); }));
  return *slot;
}

// --- thread-count determinism ------------------------------------------------------------

// Stage 4 grows the supervoxels in parallel loops (the flood's voxel table and
// boundary pass, VCCS's synchronous passes); the supervoxels, and the labels
// after them, must not depend on how those loops are split.
class Determinism : public ::testing::TestWithParam<std::tuple<std::string, Growth, int>> {};

TEST_P(Determinism, EveryStageMatchesTheSingleThreadResultBitwise) {
  // Not a structured binding: clang 14 cannot capture one in a lambda (P1091 is in clang 16).
  const std::string& name = std::get<0>(GetParam());
  const Growth growth = std::get<1>(GetParam());
  const int threads = std::get<2>(GetParam());
  const StageOutputs& ref = reference(name, growth);
  // Consistency of the reference itself with the pipeline's summary.
  EXPECT_EQ(ref.result.voxel_count, ref.grid.size());
  EXPECT_EQ(ref.result.supervoxel_count, ref.sv.size());
  EXPECT_EQ(ref.result.segment_count, ref.segment_count);
  // Run twice: a lucky schedule must not hide a race.
  for (int rep = 0; rep < 2; ++rep) {
    SCOPED_TRACE(testing::Message() << name << ", " << growth_name(growth) << ", " << threads << " threads, run " << rep);
    const StageOutputs got = with_threads(threads, [&] { return run_stages(cloud_of(name), with_growth(growth)); });
    expect_identical(ref, got);
  }
}

INSTANTIATE_TEST_SUITE_P(Threads, Determinism,
                         ::testing::Combine(::testing::Values("mosd_test2", "mosd_test43", "box_on_table"),
                                            ::testing::Values(Growth::flood, Growth::vccs), ::testing::Values(1, 2, 4)),
                         [](const auto& info) {
                           return std::get<0>(info.param) + "_" + growth_name(std::get<1>(info.param)) + "_" +
                                  std::to_string(std::get<2>(info.param)) + "threads";
                         });

// --- labels and scores on the real scenes ------------------------------------------------

void expect_valid_labels(const PointCloud& cloud, const SegmentationResult& r) {
  ASSERT_EQ(r.labels.size(), cloud.size());
  ASSERT_GT(r.segment_count, 0u);
  std::set<std::uint32_t> used;
  std::size_t unlabelled = 0, labelled_nan = 0, out_of_range = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const std::uint32_t l = r.labels[i];
    if (cloud.points[i].allFinite()) {
      if (l == 0) ++unlabelled;
      if (l > r.segment_count) ++out_of_range;
      used.insert(l);
    } else if (l != 0) {
      ++labelled_nan;
    }
  }
  EXPECT_EQ(unlabelled, 0u) << "finite points with label 0";
  EXPECT_EQ(labelled_nan, 0u) << "non-finite points with a label";
  EXPECT_EQ(out_of_range, 0u) << "labels above segment_count " << r.segment_count;
  EXPECT_EQ(used.size(), r.segment_count) << "labels are not dense 1..segment_count";
  EXPECT_GE(r.supervoxel_count, r.segment_count);
  EXPECT_GE(r.voxel_count, r.supervoxel_count);
}

// A real scene and its WOv floor: the value measured at P1 less about 0.015, so a
// change that costs accuracy fails here (floating-point differences across compilers
// move these scores by far less).
struct SceneFloor {
  std::string name;
  double wov_floor;
};
void PrintTo(const SceneFloor& s, std::ostream* os) { *os << s.name; }

class MosdScene : public ::testing::TestWithParam<SceneFloor> {};

TEST_P(MosdScene, LabelsDenseAndObjectWovAboveFloor) {
  const LabelledCloud& lc = scene(GetParam().name);
  ASSERT_TRUE(lc.labels.has_value()) << "the mOSD scenes carry a GT label field";
  const SegmentationResult r = LccpSegmenter(LccpConfig{}).segment(lc.cloud);  // P1
  expect_valid_labels(lc.cloud, r);
  const SegmentationScores s = score_segmentation(r.labels, *lc.labels, lc.cloud.points, LabelRange{0, 9});
  // Measured at P1 with the flood growth in bands (f4e0c3e): mosd_test2 0.9877,
  // mosd_test34 0.9411, mosd_test60 0.9525 (VCCS: 0.9862, 0.9188, 0.9451).
  // mosd_test43 is unorganized: since automatic binning takes the camera
  // transform for any cloud a camera sees (as for the organized scenes), it is
  // no longer binned in cubes, and measures 0.9193 (before the bands 0.9063;
  // 0.902-0.940 over eight grid phases, mean 0.919; cubes 0.917-0.941, mean
  // 0.929): its floor follows the rule above from that.
  EXPECT_GE(s.weighted_overlap, GetParam().wov_floor) << GetParam().name << ": WOv " << s.weighted_overlap << ", tp " << s.true_positive
                                      << ", fp " << s.false_positive << ", segments " << r.segment_count;
  RecordProperty("wov", std::to_string(s.weighted_overlap));
  std::printf("[ scores   ] %s: WOv %.4f tp %.4f fp %.4f fn %.4f Fos %.4f Fus %.4f ARI %.4f, %u voxels, %u supervoxels, %u segments\n",
              GetParam().name.c_str(), s.weighted_overlap, s.true_positive, s.false_positive, s.false_negative,
              s.over_segmentation, s.under_segmentation, s.adjusted_rand_index, r.voxel_count, r.supervoxel_count,
              r.segment_count);
}

INSTANTIATE_TEST_SUITE_P(Scenes, MosdScene, ::testing::Values(SceneFloor{"mosd_test2", 0.97}, SceneFloor{"mosd_test34", 0.925},
                                           SceneFloor{"mosd_test60", 0.935}, SceneFloor{"mosd_test43", 0.90}),
                         [](const auto& info) { return info.param.name; });

// --- LCCP on synthetic scenes ------------------------------------------------------------

TEST(LccpSynthetic, ConcaveCornerSplitsIntoTwoSegments) {
  const test::ConcaveCorner c = test::concave_corner(1.0, 0.10, 0.20);
  const auto sc = test::render({c.wall, c.table});
  const SegmentationResult r = LccpSegmenter(LccpConfig{}).segment(sc.cloud);
  expect_valid_labels(sc.cloud, r);
  const auto [wall, wall_frac] = test::majority(sc, r.labels, 0);
  const auto [table, table_frac] = test::majority(sc, r.labels, 1);
  EXPECT_NE(wall, table) << "the concave edge must separate the planes";
  EXPECT_GT(wall_frac, 0.9);
  EXPECT_GT(table_frac, 0.9);
}

TEST(LccpSynthetic, ConvexRidgeStaysOneSegment) {
  const test::ConcaveCorner c = test::convex_ridge(0.9, 0.10, 0.20);
  const auto sc = test::render({c.wall, c.table});
  const SegmentationResult r = LccpSegmenter(LccpConfig{}).segment(sc.cloud);
  expect_valid_labels(sc.cloud, r);
  const auto [a, a_frac] = test::majority(sc, r.labels, 0);
  const auto [b, b_frac] = test::majority(sc, r.labels, 1);
  EXPECT_EQ(a, b) << "a convex edge must not separate the planes";
  EXPECT_GT(a_frac, 0.95);
  EXPECT_GT(b_frac, 0.95);
}

TEST(LccpSynthetic, BoxOnTableIsSeparatedFromTheTable) {
  const test::BoxOnTable box = test::box_on_table();
  const auto sc = test::render(box.rects);
  const SegmentationResult r = LccpSegmenter(LccpConfig{}).segment(sc.cloud);
  expect_valid_labels(sc.cloud, r);
  const auto [table, table_frac] = test::majority(sc, r.labels, test::BoxOnTable::kTable);
  EXPECT_GT(table_frac, 0.9);
  // The visible box faces (convex to each other) share one label, not the table's.
  std::map<std::uint32_t, std::size_t> box_labels;
  std::size_t box_points = 0;
  for (std::size_t i = 0; i < r.labels.size(); ++i) {
    if (sc.rect_of_point[i] > test::BoxOnTable::kTable) ++box_labels[r.labels[i]], ++box_points;
  }
  ASSERT_GT(box_points, 2000u);
  auto best = std::max_element(box_labels.begin(), box_labels.end(), [](auto& x, auto& y) { return x.second < y.second; });
  EXPECT_NE(best->first, table) << "box merged with the table";
  EXPECT_GT(double(best->second) / double(box_points), 0.9) << "box split into parts";
}

TEST(LccpSegmenter, RejectsBadConfigAndCloudsWithoutFinitePoints) {
  LccpConfig bad;
  bad.voxels.voxel_size_m = 0.0f;
  EXPECT_THROW((void)LccpSegmenter{bad}, Error);
  bad = LccpConfig{};
  bad.supervoxels.seed_size_m = -0.02f;
  EXPECT_THROW((void)LccpSegmenter{bad}, Error);
  const LccpSegmenter seg{LccpConfig{}};
  EXPECT_THROW(seg.segment(test::unorganized({{test::kNaN, test::kNaN, test::kNaN}})), Error);
  EXPECT_THROW(seg.segment(PointCloud{}), Error);
}

TEST(LccpSegmenter, SmallCloudIsLabelledAndTimed) {
  const auto sc = test::render({test::fronto_parallel_rect(1.0, 0.10)});
  const LccpSegmenter seg{LccpConfig{}};
  const SegmentationResult r = seg.segment(sc.cloud);
  expect_valid_labels(sc.cloud, r);
  EXPECT_EQ(r.segment_count, 1u) << "a flat patch is one segment";
  EXPECT_GE(r.times.total_ms(), 0.0);
  EXPECT_EQ(seg.config().voxels.voxel_size_m, 0.005f);
}

}  // namespace
}  // namespace lccp
