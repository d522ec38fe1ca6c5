// Stage 3: VCCS supervoxels (seeds on a grid, flow-constrained growth).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "lccp/config.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/core/normals.hpp"
#include "lccp/core/supervoxels.hpp"
#include "lccp/core/voxel_grid.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

struct Stages {
  VoxelGrid grid;
  VoxelNormals voxel_normals;
  std::vector<std::uint32_t> seeds;
  Supervoxels sv;
};

Stages run(const PointCloud& cloud, const LccpConfig& cfg = {}) {
  Stages s;
  s.grid = voxelize(cloud, cfg.voxels);
  s.voxel_normals = estimate_voxel_normals(s.grid, cfg.normals);
  s.seeds = select_seeds(s.grid, cfg.supervoxels, cfg.voxels.voxel_size_m);
  s.sv = grow_supervoxels(s.grid, s.voxel_normals, s.seeds, cfg);
  return s;
}

// What grow_supervoxels promises whatever the scene: every voxel has a supervoxel,
// per-supervoxel arrays agree, centroids are the mean of member voxel centroids, normals
// the normalized sum of member voxel normals.
void check_supervoxels(const Stages& s) {
  const VoxelGrid& g = s.grid;
  const Supervoxels& sv = s.sv;
  ASSERT_TRUE(std::is_sorted(s.seeds.begin(), s.seeds.end()));
  ASSERT_EQ(std::adjacent_find(s.seeds.begin(), s.seeds.end()), s.seeds.end());
  for (auto seed : s.seeds) ASSERT_LT(seed, g.size());
  ASSERT_EQ(sv.supervoxel_of_voxel.size(), g.size());
  ASSERT_EQ(sv.normals.size(), sv.size());
  ASSERT_EQ(sv.colors.size(), sv.size());
  ASSERT_EQ(sv.voxel_counts.size(), sv.size());
  ASSERT_GT(sv.size(), 0u);
  std::vector<std::uint32_t> count(sv.size(), 0);
  std::vector<Eigen::Vector3d> sum(sv.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> nsum(sv.size(), Eigen::Vector3d::Zero());
  for (std::size_t v = 0; v < g.size(); ++v) {
    const std::uint32_t id = sv.supervoxel_of_voxel[v];
    ASSERT_NE(id, kNoVoxel) << "voxel " << v << " has no supervoxel";
    ASSERT_LT(id, sv.size()) << "voxel " << v;
    ++count[id];
    sum[id] += g.centroids[v].cast<double>();
    nsum[id] += s.voxel_normals.directions[v].cast<double>();
  }
  for (std::size_t i = 0; i < sv.size(); ++i) {
    ASSERT_GT(count[i], 0u) << "empty supervoxel " << i;
    ASSERT_EQ(sv.voxel_counts[i], count[i]) << "supervoxel " << i;
    EXPECT_LT((sv.centroids[i].cast<double>() - sum[i] / count[i]).norm(), 1e-5) << "supervoxel " << i;
    EXPECT_NEAR(sv.normals[i].norm(), 1.0f, 1e-4f) << "supervoxel " << i;
    EXPECT_LT((sv.normals[i].cast<double>() - nsum[i].normalized()).norm(), 1e-4) << "supervoxel " << i;
  }
}

TEST(Supervoxels, FlatPatchAtOneMetre) {
  // A 20 x 20 cm patch of the plane z = 1 m, ~105 x 105 points, P1: v = 5 mm, s = 2 cm.
  // At z = 1 the camera binning (x/z, y/z, ln z) coincides with metric 5 mm cells, so
  // there are ~40 x 40 = 1600 voxels.
  // Expected supervoxel count: about area / s^2 = (0.20 / 0.02)^2 = 100. Bounds:
  //  - upper: a 20 cm span overlaps at most 11 seed cells of 2 cm per axis, one seed per
  //    occupied cell -> at most 121 seeds; the patch is connected, so no seedless
  //    component adds supervoxels -> <= 121;
  //  - lower: at least 9 x 9 = 81 seed cells lie entirely inside the patch (16 voxels
  //    each, so their seeds are kept); we allow a ring of them (81 -> 64 = 8 x 8) to be
  //    swallowed during growth -> >= 64.
  const auto scene = test::render({test::fronto_parallel_rect(1.0, 0.20)});
  const LccpConfig cfg;  // P1
  const Stages s = run(scene.cloud, cfg);
  check_supervoxels(s);
  EXPECT_GT(s.grid.size(), 1400u);
  EXPECT_LT(s.grid.size(), 1800u);
  EXPECT_GE(s.seeds.size(), 81u);
  EXPECT_LE(s.seeds.size(), 121u);
  EXPECT_GE(s.sv.size(), 64u);
  EXPECT_LE(s.sv.size(), 121u);
  EXPECT_LE(s.sv.size(), s.seeds.size());
  // int(1.8 s / v) - 1 = 6 passes: nothing reaches farther than 6 voxels from its seed,
  // so no supervoxel exceeds 13 x 13 voxels of the plane.
  EXPECT_LE(*std::max_element(s.sv.voxel_counts.begin(), s.sv.voxel_counts.end()), 169u);
  for (std::size_t i = 0; i < s.sv.size(); ++i) {
    EXPECT_NEAR(s.sv.centroids[i].z(), 1.0f, 1e-5f) << "supervoxel " << i << " off the plane";
    EXPECT_LT(test::angle_deg(s.sv.normals[i], Eigen::Vector3d(0, 0, -1)), 1.0) << "supervoxel " << i;
  }
}

// The flood grows bands of at least 12 288 voxels apart (supervoxel_flood.cpp):
// a wall of about 28 000 voxels is two bands, whose patches meet along the
// border; the patches either side are coplanar, so LCCP joins them into one
// segment, and every band's patch keeps to the plane.
TEST(Supervoxels, FloodBandsOfOnePlaneJoinIntoOneSegment) {
  const auto scene = test::render({test::centered_rect({0, 0, 1.0}, Eigen::Vector3d::UnitX(), 0.95, Eigen::Vector3d::UnitY(), 0.75)});
  const LccpConfig cfg;
  const Stages s = run(scene.cloud, cfg);
  check_supervoxels(s);
  ASSERT_GE(s.grid.size(), 2u * 12288u) << "the plane must span two bands";
  for (std::size_t i = 0; i < s.sv.size(); ++i) {
    EXPECT_LT(test::angle_deg(s.sv.normals[i], Eigen::Vector3d(0, 0, -1)), 1.0) << "supervoxel " << i;
  }
  const std::vector<std::uint32_t> labels = LccpSegmenter(cfg).segment(scene.cloud).labels;
  std::set<std::uint32_t> segments;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (scene.cloud.points[i].allFinite()) segments.insert(labels[i]);
  }
  EXPECT_EQ(segments, std::set<std::uint32_t>{1});
}

TEST(Supervoxels, FlatPatchEuclideanBinning) {
  // The same with metric binning and a larger seed size (P2's s = 6 cm, v = 7.5 mm):
  // 20 cm spans at most ceil(20/6) + 1 = 5 seed cells per axis -> <= 25 supervoxels; at
  // least 2 x 2 cells lie fully inside -> >= 4.
  const auto scene = test::render({test::fronto_parallel_rect(1.0, 0.20)});
  LccpConfig cfg;
  cfg.voxels = VoxelConfig{0.0075f, Binning::euclidean};
  cfg.supervoxels.seed_size_m = 0.06f;
  const Stages s = run(scene.cloud, cfg);
  check_supervoxels(s);
  EXPECT_GE(s.sv.size(), 4u);
  EXPECT_LE(s.sv.size(), 25u);
}

// Beyond the paper (SupervoxelConfig::depth_scaled_seeds). A 1.6 m square facing
// the sensor at 4 m, P1: camera cells there are v z = 2 cm wide, about 80 x 80
// voxels on the square. VCCS's 2 cm seed grid gives nearly every voxel its own
// seed, so a "supervoxel" is one voxel. With the key, beyond z0 = s / (4 v) = 1 m
// seeds are 4 cells (8 cm) apart: at most 21 x 21 = 441 seed cells meet the
// square, at least 19 x 19 lie inside it, and a ring of them may be swallowed in
// growth (>= 17 x 17 = 289); each holds about 4 x 4 voxels.
TEST(Supervoxels, SeedsFarAwaySpanFourCameraCells) {
  const auto scene = test::render({test::fronto_parallel_rect(4.0, 1.6)});
  LccpConfig cfg;  // P1, camera cells: the cloud is organized
  cfg.supervoxels.depth_scaled_seeds = false;
  const Stages paper = run(scene.cloud, cfg);
  check_supervoxels(paper);
  ASSERT_EQ(paper.grid.binning, Binning::camera);
  EXPECT_GT(paper.grid.size(), 6000u);
  EXPECT_LT(paper.grid.size(), 7000u);
  EXPECT_LT(static_cast<double>(paper.grid.size()) / paper.sv.size(), 1.5) << paper.sv.size() << " supervoxels";

  cfg.supervoxels.depth_scaled_seeds = true;
  const Stages scaled = run(scene.cloud, cfg);
  check_supervoxels(scaled);
  EXPECT_EQ(scaled.grid.size(), paper.grid.size());
  EXPECT_GE(scaled.sv.size(), 289u);
  EXPECT_LE(scaled.sv.size(), 441u);
  EXPECT_LE(scaled.sv.size(), scaled.seeds.size());
  EXPECT_GT(static_cast<double>(scaled.grid.size()) / scaled.sv.size(), 12.0) << scaled.sv.size() << " supervoxels";
}

// Nearer than z0, and with cubic voxels at any depth, the key changes nothing:
// a square tilted through 0.6-0.95 m (camera cells), and the far square above
// in 2 cm cubes.
TEST(Supervoxels, DepthScaledSeedsChangeNothingNearerThanZ0OrInCubes) {
  const auto near = test::render({test::tilted_rect(0.78, 0.4, 0, 60)});
  const auto far = test::render({test::fronto_parallel_rect(4.0, 1.6)});
  LccpConfig camera, cubes;
  cubes.voxels = VoxelConfig{0.005f, Binning::euclidean};
  for (const auto& [cloud, base] : {std::pair{near.cloud, camera}, std::pair{far.cloud, cubes}}) {
    LccpConfig off = base, on = base;
    off.supervoxels.depth_scaled_seeds = false;
    on.supervoxels.depth_scaled_seeds = true;
    const Stages a = run(cloud, off), b = run(cloud, on);
    ASSERT_GT(a.grid.size(), 1000u);
    EXPECT_EQ(a.seeds, b.seeds);
    EXPECT_EQ(a.sv.supervoxel_of_voxel, b.sv.supervoxel_of_voxel);
    EXPECT_EQ(a.sv.centroids, b.sv.centroids);
  }
}

TEST(Supervoxels, ConcaveCornerDoesNotMixPlanes) {
  // Table and wall at 90 deg, concave edge 1 m in front of the camera, legs 10 cm, 20 cm
  // wide (see test_clouds.hpp). The normal weight w_n = 4 on 1 - |n1.n2| = 1 between the
  // planes dominates the spatial term, so away from the edge (where voxel normals are
  // clean: the 2-ring PCA reaches ~1 cm) no supervoxel may hold voxels of both planes.
  const test::ConcaveCorner corner = test::concave_corner(1.0, 0.10, 0.20);
  const auto scene = test::render({corner.wall, corner.table});
  const Stages s = run(scene.cloud);
  check_supervoxels(s);
  std::vector<std::uint8_t> far_wall(s.sv.size(), 0), far_table(s.sv.size(), 0);
  std::size_t far_voxels[2] = {0, 0};
  for (std::size_t v = 0; v < s.grid.size(); ++v) {
    const Eigen::Vector3d c = s.grid.centroids[v].cast<double>();
    if (corner.distance_to_edge(c) <= 0.015) continue;
    const int side = corner.side(c);
    ++far_voxels[side];
    (side == 0 ? far_wall : far_table)[s.sv.supervoxel_of_voxel[v]] = 1;
  }
  ASSERT_GT(far_voxels[0], 100u);
  ASSERT_GT(far_voxels[1], 100u);
  std::size_t wall_svs = 0, table_svs = 0;
  for (std::size_t i = 0; i < s.sv.size(); ++i) {
    EXPECT_FALSE(far_wall[i] && far_table[i]) << "supervoxel " << i << " (centroid " << s.sv.centroids[i].transpose()
                                              << ") spans both planes";
    wall_svs += far_wall[i];
    table_svs += far_table[i];
  }
  EXPECT_GT(wall_svs, 5u);
  EXPECT_GT(table_svs, 5u);
  // Supervoxels made only of far voxels have their plane's normal (toward the sensor).
  const Eigen::Vector3d n_wall = test::normal_toward_sensor(corner.wall);
  const Eigen::Vector3d n_table = test::normal_toward_sensor(corner.table);
  EXPECT_LT(test::angle_deg(n_wall, Eigen::Vector3d(0, 1, -1)), 1e-6);
  EXPECT_LT(test::angle_deg(n_table, Eigen::Vector3d(0, -1, -1)), 1e-6);
  std::vector<std::uint8_t> near_edge(s.sv.size(), 0);
  for (std::size_t v = 0; v < s.grid.size(); ++v) {
    if (corner.distance_to_edge(s.grid.centroids[v].cast<double>()) <= 0.015) near_edge[s.sv.supervoxel_of_voxel[v]] = 1;
  }
  for (std::size_t i = 0; i < s.sv.size(); ++i) {
    if (near_edge[i]) continue;
    if (far_wall[i]) {
      EXPECT_LT(test::angle_deg(s.sv.normals[i], n_wall), 3.0) << "supervoxel " << i;
    }
    if (far_table[i]) {
      EXPECT_LT(test::angle_deg(s.sv.normals[i], n_table), 3.0) << "supervoxel " << i;
    }
  }
}

TEST(Supervoxels, IsolatedVoxelsStillGetASupervoxel) {
  // PCL leaves finite points unlabelled when no supervoxel reaches their voxel. A
  // patch plus two stray points 30 cm away (each its own voxel, no neighbours): each must
  // end up in a supervoxel of its own (a seedless component becomes a supervoxel).
  auto scene = test::render({test::fronto_parallel_rect(1.0, 0.10)});
  PointCloud cloud = test::unorganized(scene.cloud.points);
  cloud.points.push_back({0.30f, 0.0f, 1.0f});
  cloud.points.push_back({-0.30f, 0.1f, 1.1f});
  cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  const Stages s = run(cloud);
  check_supervoxels(s);
  for (std::size_t k = cloud.size() - 2; k < cloud.size(); ++k) {
    const std::uint32_t v = s.grid.voxel_of_point[k];
    ASSERT_NE(v, kNoVoxel);
    const std::uint32_t id = s.sv.supervoxel_of_voxel[v];
    EXPECT_EQ(s.sv.voxel_counts[id], 1u) << "stray voxel shares supervoxel " << id;
    EXPECT_LT((s.sv.centroids[id] - s.grid.centroids[v]).norm(), 1e-6f);
  }
}

TEST(Supervoxels, ThinTailBeyondGrowthReachIsAssigned) {
  // A plane plus a 1-voxel-wide strip 12 cm long (24 voxels, farther than the 6 growth
  // passes reach from the plane's seeds): every voxel still gets a supervoxel.
  auto scene = test::render({test::fronto_parallel_rect(1.0, 0.06)});
  PointCloud cloud = test::unorganized(scene.cloud.points);
  for (int i = 0; i < 240; ++i) cloud.points.push_back({0.03f + 0.0005f * float(i), 0.0011f, 1.0f});
  cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  const Stages s = run(cloud);
  check_supervoxels(s);
}

TEST(Supervoxels, SeedsAreOnePerOccupiedSeedCell) {
  // Two small patches 1 m apart in x, each 2 x 2 cm at z = 1 (about 4 x 4 voxels): each
  // yields at least one and at most 4 seeds (a 2 cm patch overlaps at most 2 x 2 seed
  // cells), and the two patches never share a supervoxel.
  const auto scene = test::render({test::centered_rect({-0.25, 0, 1}, Eigen::Vector3d::UnitX(), 0.02,
                                                       Eigen::Vector3d::UnitY(), 0.02),
                                   test::centered_rect({0.25, 0, 1}, Eigen::Vector3d::UnitX(), 0.02,
                                                       Eigen::Vector3d::UnitY(), 0.02)});
  const Stages s = run(scene.cloud);
  check_supervoxels(s);
  std::size_t left = 0, right = 0;
  for (auto seed : s.seeds) (s.grid.centroids[seed].x() < 0 ? left : right)++;
  EXPECT_GE(left, 1u);
  EXPECT_LE(left, 4u);
  EXPECT_GE(right, 1u);
  EXPECT_LE(right, 4u);
  std::set<std::uint32_t> left_ids, right_ids;
  for (std::size_t v = 0; v < s.grid.size(); ++v) {
    (s.grid.centroids[v].x() < 0 ? left_ids : right_ids).insert(s.sv.supervoxel_of_voxel[v]);
  }
  for (auto id : left_ids) EXPECT_EQ(right_ids.count(id), 0u) << "supervoxel " << id << " spans both patches";
}

}  // namespace
}  // namespace lccp
