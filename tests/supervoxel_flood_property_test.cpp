// Stage 4's flood growth (SupervoxelConfig::growth = flood) on random inputs:
// voxel adjacency graphs (symmetric rows, sorted, no self loops, no repeats, at
// most the 26 neighbours a voxel grid gives; empty rows, isolated voxels,
// several components), normals, planar flags, seed sets and configs within the
// ranges validate() accepts. Every case comes from a fixed seed.
//
// What holds whatever the input (src/core/supervoxel_flood.cpp):
//  - every voxel is in a supervoxel and none is absorbed; no supervoxel is empty;
//    each one's centroid and colour are its members' means and its normal the
//    normalized sum of its planar members' normals (of all members' if that
//    sum vanishes, the direction to the sensor if that does too);
//  - a supervoxel lies in one connected component of the adjacency: the flood
//    only crosses edges, and the refinement moves a voxel only to a patch one
//    of its neighbours is in. (Not that it is connected: the refinement can
//    move a patch's middle away.) A voxel without neighbours is one of its own;
//  - the same input gives the same bits, with one thread or four.
// What a patch admits (max_normal_angle_deg of its normal, the depth tolerance
// of its plane, 1.8 seed spacings of its centre) is tested on scenes in which
// that test alone keeps two sets of voxels apart, each with a control run that
// mixes them once the test no longer applies, so the assertion can fail.
// Not asserted: that members lie within 1.8 spacings of their final centroid.
// The reach is measured to the patch's mean when the voxel is queued (seeded
// region growing, Adams and Bischof 1994), and that mean moves on as the patch
// grows, so an early member can end up farther from it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "lccp/config.hpp"
#include "lccp/core/normals.hpp"
#include "lccp/core/supervoxels.hpp"
#include "lccp/core/voxel_grid.hpp"

namespace lccp {
namespace {

using Rng = std::mt19937;
using Vec = Eigen::Vector3f;

float uniform(Rng& rng, float low, float high) { return std::uniform_real_distribution<float>(low, high)(rng); }
float log_uniform(Rng& rng, float low, float high) { return std::exp(uniform(rng, std::log(low), std::log(high))); }
std::uint32_t below(Rng& rng, std::size_t n) {
  return std::uniform_int_distribution<std::uint32_t>(0, static_cast<std::uint32_t>(n - 1))(rng);
}
bool chance(Rng& rng, double p) { return std::bernoulli_distribution(p)(rng); }
float radians(float deg) { return deg * std::numbers::pi_v<float> / 180.0f; }

// Draws are sequenced (one declaration, or braces): the order of function
// arguments is unspecified, and the cases must not depend on the compiler.
Vec uniform_vec(Rng& rng, float low, float high) {
  const float x = uniform(rng, low, high), y = uniform(rng, low, high), z = uniform(rng, low, high);
  return {x, y, z};
}

Vec random_unit(Rng& rng) {
  std::normal_distribution<float> gauss;
  for (;;) {
    const float x = gauss(rng), y = gauss(rng), z = gauss(rng);
    const Vec n(x, y, z);
    if (n.norm() > 1e-3f) return n.normalized();
  }
}

// A random point of the disc of radius r about the origin of the plane spanned by u and w.
Vec in_disc(Rng& rng, const Vec& u, const Vec& w, float r) {
  const float radius = r * std::sqrt(uniform(rng, 0.0f, 1.0f)), angle = uniform(rng, 0.0f, 2.0f * std::numbers::pi_v<float>);
  return radius * (std::cos(angle) * u + std::sin(angle) * w);
}

// Runs f with n threads: the global limit plus an arena of n slots.
template <class F>
auto with_threads(int n, F&& f) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(n));
  tbb::task_arena arena(n);
  return arena.execute(std::forward<F>(f));
}

// ---- inputs -----------------------------------------------------------------

// An undirected graph kept as a voxel grid's adjacency is: symmetric, without
// self loops or repeats, at most 26 neighbours per voxel.
class Graph {
 public:
  explicit Graph(std::size_t n) : rows_(n) {}

  std::size_t size() const { return rows_.size(); }
  void connect(std::uint32_t a, std::uint32_t b) {
    if (a == b || rows_[a].size() == 26 || rows_[b].size() == 26) return;
    if (std::find(rows_[a].begin(), rows_[a].end(), b) != rows_[a].end()) return;
    rows_[a].push_back(b);
    rows_[b].push_back(a);
  }
  // Rows sorted; both arrays exactly as long as their content, so a read past
  // the last row leaves the allocation (AddressSanitizer).
  CompressedRows rows() const {
    std::vector<std::uint32_t> offsets(rows_.size() + 1, 0);
    for (std::size_t v = 0; v < rows_.size(); ++v) offsets[v + 1] = offsets[v] + static_cast<std::uint32_t>(rows_[v].size());
    std::vector<std::uint32_t> items(offsets.back());
    for (std::size_t v = 0; v < rows_.size(); ++v) {
      std::vector<std::uint32_t> row = rows_[v];
      std::sort(row.begin(), row.end());
      std::copy(row.begin(), row.end(), items.begin() + offsets[v]);
    }
    return {std::move(offsets), std::move(items)};
  }

 private:
  std::vector<std::vector<std::uint32_t>> rows_;
};

// About `per_voxel` random edges per voxel, most between voxels near in id
// (neighbours of one patch come in runs), some between any two.
Graph random_graph(Rng& rng, std::size_t n, float per_voxel) {
  Graph g(n);
  if (n < 2) return g;
  const auto tries = static_cast<std::size_t>(per_voxel * static_cast<float>(n));
  for (std::size_t i = 0; i < tries; ++i) {
    const std::uint32_t a = below(rng, n);
    const std::uint32_t b = chance(rng, 0.8) ? std::min<std::uint32_t>(a + 1 + below(rng, 12), n - 1) : below(rng, n);
    g.connect(a, b);
  }
  return g;
}

// Whether rows are an adjacency as voxelize() builds it: symmetric, sorted,
// without self loops or repeats, at most 26 per voxel.
bool well_formed(const CompressedRows& rows) {
  for (std::uint32_t v = 0; v < rows.rows(); ++v) {
    if (rows.count(v) > 26 || !std::is_sorted(rows.begin(v), rows.end(v)) ||
        std::adjacent_find(rows.begin(v), rows.end(v)) != rows.end(v)) {
      return false;
    }
    for (const std::uint32_t* w = rows.begin(v); w != rows.end(v); ++w) {
      if (*w == v || *w >= rows.rows() || !std::binary_search(rows.begin(*w), rows.end(*w), v)) return false;
    }
  }
  return true;
}

// Connected components, numbered in order of their lowest voxel.
std::vector<std::uint32_t> components(const CompressedRows& rows) {
  std::vector<std::uint32_t> component(rows.rows(), kNoVoxel), stack;
  std::uint32_t count = 0;
  for (std::uint32_t v = 0; v < rows.rows(); ++v) {
    if (component[v] != kNoVoxel) continue;
    component[v] = count;
    for (stack.push_back(v); !stack.empty();) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      for (const std::uint32_t* w = rows.begin(u); w != rows.end(u); ++w) {
        if (component[*w] != kNoVoxel) continue;
        component[*w] = count;
        stack.push_back(*w);
      }
    }
    ++count;
  }
  return component;
}

struct Input {
  VoxelGrid grid;
  VoxelNormals normals;
  std::vector<std::uint32_t> seeds;
  LccpConfig config;

  std::size_t size() const { return grid.size(); }
};

Supervoxels grow(const Input& in) { return grow_supervoxels(in.grid, in.normals, in.seeds, in.config); }

// The voxels of `graph` at `xyz`, grey, facing -z, all planar, no seeds.
Input make_input(const Graph& graph, std::vector<Vec> xyz, const LccpConfig& config, Binning binning) {
  Input in;
  in.grid.centroids = std::move(xyz);
  in.grid.colors.assign(graph.size(), Vec::Constant(128.0f));
  in.grid.neighbors = graph.rows();
  in.grid.points.offsets.assign(graph.size() + 1, 0);  // no points: growth does not read them
  in.grid.binning = binning;
  in.normals.directions.assign(graph.size(), Vec(0, 0, -1));
  in.normals.planar.assign(graph.size(), 1);
  in.config = config;
  return in;
}

// BucketQueue::push (supervoxel_flood.cpp) turns distance * 1023 / (the largest
// distance) into a bucket index. For two equal unit normals the normal term
// 1 - |n1.n2| can round below 0 (|n1.n2| up to 2.4e-7 above 1 for a fifth of
// all unit vectors); push files such a distance in bucket 0. The random cases
// below draw configs whose largest distance is small enough for that to matter
// (FloodProperty.NearerPatchWinsWhenTheNormalTermRoundsBelowZero is the
// reproducer it was found with).

// A weight validate() accepts: 0, below 1, up to 10, or up to 1e6.
float random_weight(Rng& rng) {
  switch (below(rng, 4)) {
    case 0: return 0.0f;
    case 1: return uniform(rng, 0.01f, 1.0f);
    case 2: return uniform(rng, 1.0f, 10.0f);
    default: return log_uniform(rng, 10.0f, 1e6f);
  }
}

// Random weights for config (its angle already set).
void random_weights(Rng& rng, SupervoxelConfig& c) {
  c.spatial_weight = random_weight(rng);
  c.normal_weight = random_weight(rng);
  c.color_weight = chance(rng, 0.5) ? 0.0f : random_weight(rng);
}

// A sensor constant: the default, the edge of its range, or anywhere in it.
float random_constant(Rng& rng, float default_value, float low, float high) {
  switch (below(rng, 4)) {
    case 0: return low;
    case 1: return low > 0.0f ? log_uniform(rng, low, high) : uniform(rng, low, high);
    default: return default_value;
  }
}

SensorConfig random_sensor(Rng& rng) {
  const SensorConfig d;
  SensorConfig s;
  s.focal_px = random_constant(rng, d.focal_px, 1.0f, 1e5f);
  s.baseline_m = random_constant(rng, d.baseline_m, 1e-4f, 10.0f);
  s.disparity_step_px = random_constant(rng, d.disparity_step_px, 0.0f, 100.0f);
  s.axial_sigma_m = random_constant(rng, d.axial_sigma_m, 0.0f, 1.0f);
  s.axial_sigma_per_m2 = random_constant(rng, d.axial_sigma_per_m2, 0.0f, 1.0f);
  s.min_range_m = random_constant(rng, d.min_range_m, 0.0f, 100.0f);
  return s;
}

// A flood config: voxel and seed sizes, seed scaling, the given angle, random weights.
LccpConfig random_config(Rng& rng, float max_normal_angle_deg) {
  LccpConfig c;
  c.supervoxels.growth = Growth::flood;
  c.voxels.voxel_size_m = log_uniform(rng, 0.002f, 0.05f);
  c.supervoxels.seed_size_m = c.voxels.voxel_size_m * uniform(rng, 1.0f, 10.0f);
  c.supervoxels.depth_scaled_seeds = chance(rng, 0.5);
  c.supervoxels.max_normal_angle_deg = max_normal_angle_deg;
  random_weights(rng, c.supervoxels);
  return c;
}

Binning random_binning(Rng& rng) { return chance(rng, 0.5) ? Binning::camera : Binning::euclidean; }

// Occupied cells of a block (each with probability `fill`) adjacent when they
// touch (the 26-neighbourhood), centroids inside their cells of side v.
std::pair<Graph, std::vector<Vec>> random_lattice(Rng& rng, float v, const Vec& origin) {
  const int nx = 2 + static_cast<int>(below(rng, 24)), ny = 2 + static_cast<int>(below(rng, 24)),
            nz = 1 + static_cast<int>(below(rng, 4));
  const float fill = uniform(rng, 0.3f, 1.0f);
  std::vector<std::uint32_t> id(static_cast<std::size_t>(nx * ny * nz), kNoVoxel);
  std::vector<Vec> xyz;
  const auto cell = [&](int x, int y, int z) { return static_cast<std::size_t>((z * ny + y) * nx + x); };
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        if (!chance(rng, fill)) continue;
        id[cell(x, y, z)] = static_cast<std::uint32_t>(xyz.size());
        const float jx = uniform(rng, 0.2f, 0.8f), jy = uniform(rng, 0.2f, 0.8f), jz = uniform(rng, 0.2f, 0.8f);
        xyz.push_back(origin + v * Vec(static_cast<float>(x) + jx, static_cast<float>(y) + jy, static_cast<float>(z) + jz));
      }
    }
  }
  Graph g(xyz.size());
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        for (int d = 0; d < 27 && id[cell(x, y, z)] != kNoVoxel; ++d) {
          const int ox = x + d % 3 - 1, oy = y + d / 3 % 3 - 1, oz = z + d / 9 - 1;
          if (ox < 0 || oy < 0 || oz < 0 || ox >= nx || oy >= ny || oz >= nz || id[cell(ox, oy, oz)] == kNoVoxel) continue;
          g.connect(id[cell(x, y, z)], id[cell(ox, oy, oz)]);
        }
      }
    }
  }
  return {std::move(g), std::move(xyz)};
}

// Small shapes: no voxel, one, none adjacent, 27 all adjacent (26 neighbours
// each), a star of 26, a path.
Graph special_graph(Rng& rng) {
  const std::uint32_t shape = below(rng, 6);
  const std::size_t n = shape == 0 ? 0 : shape == 1 ? 1 : shape == 2 ? 2 + below(rng, 40) : shape == 5 ? 2 + below(rng, 100) : 27;
  Graph g(n);
  for (std::uint32_t a = 0; a < n; ++a) {
    for (std::uint32_t b = a + 1; b < n; ++b) {
      if (shape == 3 || (shape == 4 && a == 0) || (shape == 5 && b == a + 1)) g.connect(a, b);
    }
  }
  return g;
}

// Random points in a box of side `side` about a point in the camera's view.
std::vector<Vec> random_points(Rng& rng, std::size_t n, float side) {
  const float z = uniform(rng, 0.5f, 3.0f);
  const Vec across = uniform_vec(rng, -0.5f, 0.5f), centre = z * Vec(across.x(), across.y(), 1.0f);
  std::vector<Vec> xyz(n);
  for (Vec& p : xyz) {
    p = centre + side * uniform_vec(rng, -0.5f, 0.5f);
    p.z() = std::max(p.z(), 0.05f);
  }
  return xyz;
}

// Random unit normals, all one, a few directions of either sign, or a smooth
// field; some voxels then copy a neighbour's normal, flip theirs, or turn it
// perpendicular to the line of sight.
void random_normals(Rng& rng, Input& in) {
  const std::uint32_t mode = below(rng, 4);
  const Vec one = random_unit(rng);
  const std::vector<Vec> few = {random_unit(rng), random_unit(rng), random_unit(rng)};
  std::vector<Vec>& n = in.normals.directions;
  for (std::size_t v = 0; v < in.size(); ++v) {
    const Vec& x = in.grid.centroids[v];
    const Vec random = random_unit(rng);
    const std::uint32_t pick = below(rng, few.size());
    const float sign = chance(rng, 0.5) ? 1.0f : -1.0f;
    n[v] = mode == 0 ? random
         : mode == 1 ? one
         : mode == 2 ? Vec(sign * few[pick])
                     : Vec(one + 0.3f * Vec(std::sin(40.0f * x.x()), std::sin(40.0f * x.y()), 0.0f)).normalized();
    const std::uint32_t twist = below(rng, 20);
    const CompressedRows& rows = in.grid.neighbors;
    if (twist == 0 && rows.count(v) > 0) n[v] = n[rows.begin(v)[below(rng, rows.count(v))]];
    if (twist == 1) n[v] = -n[v];
    if (twist == 2) n[v] = x.cross(random_unit(rng)).normalized();
  }
}

void random_flags_colours_seeds(Rng& rng, Input& in) {
  const double planar = std::array{0.0, 0.7, 1.0}[below(rng, 3)];
  const double seeded = std::array{0.0, 0.05, 0.3, 1.0}[below(rng, 4)];
  const bool coloured = chance(rng, 0.5);
  in.seeds.clear();
  for (std::uint32_t v = 0; v < in.size(); ++v) {
    in.normals.planar[v] = chance(rng, planar);
    if (coloured) in.grid.colors[v] = uniform_vec(rng, 0.0f, 255.0f);
    if (chance(rng, seeded)) in.seeds.push_back(v);
  }
}

Input random_input(Rng& rng) {
  const float angle = std::array{0.0f, 90.0f, log_uniform(rng, 0.05f, 5.0f), uniform(rng, 0.0f, 90.0f)}[below(rng, 4)];
  LccpConfig config = random_config(rng, angle);
  config.sensor = random_sensor(rng);
  const float s = config.supervoxels.seed_size_m;
  const std::uint32_t kind = below(rng, 3);
  std::pair<Graph, std::vector<Vec>> shape{Graph(0), {}};
  if (kind == 0) {
    const std::size_t n = 2 + below(rng, 300);
    shape = {random_graph(rng, n, uniform(rng, 0.0f, 6.0f)), random_points(rng, n, s * uniform(rng, 1.0f, 12.0f))};
  } else if (kind == 1) {
    const float z = uniform(rng, 0.5f, 3.0f);
    shape = random_lattice(rng, config.voxels.voxel_size_m, Vec(0.0f, 0.0f, z) + uniform_vec(rng, -0.3f, 0.3f).cwiseProduct(Vec(1, 1, 0)));
  } else {
    Graph g = special_graph(rng);
    shape = {g, random_points(rng, g.size(), s * uniform(rng, 0.5f, 6.0f))};
  }
  Input in = make_input(shape.first, std::move(shape.second), config, random_binning(rng));
  random_normals(rng, in);
  random_flags_colours_seeds(rng, in);
  return in;
}

// ---- what the flood promises ---------------------------------------------------

// The mean centroid and colour of `members` and the normal a patch of them has.
struct Means {
  Vec centroid, color, normal;
};
Means means_of(const Input& in, const std::vector<std::uint32_t>& members) {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rgb = xyz, all = xyz, planar = xyz;
  for (const std::uint32_t v : members) {
    xyz += in.grid.centroids[v].cast<double>();
    rgb += in.grid.colors[v].cast<double>();
    all += in.normals.directions[v].cast<double>();
    if (in.normals.planar[v]) planar += in.normals.directions[v].cast<double>();
  }
  const auto m = static_cast<double>(members.size());
  const Vec centroid = (xyz / m).cast<float>();
  const Eigen::Vector3d& sum = planar.norm() > 1e-6 ? planar : all;
  return {centroid, (rgb / m).cast<float>(), sum.norm() > 1e-6 ? Vec(sum.normalized().cast<float>()) : Vec(-centroid.normalized())};
}

bool near(const Vec& a, const Vec& b, float tolerance) { return a.allFinite() && (a - b).norm() <= tolerance * (1.0f + b.norm()); }

std::vector<std::vector<std::uint32_t>> members_of(const Supervoxels& sv) {
  std::vector<std::vector<std::uint32_t>> members(sv.size());
  for (std::uint32_t v = 0; v < sv.supervoxel_of_voxel.size(); ++v) members[sv.supervoxel_of_voxel[v]].push_back(v);
  return members;
}

::testing::AssertionResult shape_holds(const Input& in, const Supervoxels& sv) {
  const std::size_t k = sv.size();
  if (sv.supervoxel_of_voxel.size() != in.size() || sv.absorbed != std::vector<std::uint8_t>(in.size(), 0)) {
    return ::testing::AssertionFailure() << "not one supervoxel per voxel, or one absorbed";
  }
  if (sv.normals.size() != k || sv.colors.size() != k || sv.voxel_counts.size() != k) {
    return ::testing::AssertionFailure() << "per-supervoxel arrays of different lengths";
  }
  for (std::size_t v = 0; v < in.size(); ++v) {
    if (sv.supervoxel_of_voxel[v] >= k) return ::testing::AssertionFailure() << "voxel " << v << " in supervoxel " << sv.supervoxel_of_voxel[v] << " of " << k;
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult flood_invariants(const Input& in, const Supervoxels& sv) {
  if (auto shape = shape_holds(in, sv); !shape) return shape;
  const std::vector<std::uint32_t> component = components(in.grid.neighbors);
  const auto members = members_of(sv);
  for (std::size_t i = 0; i < sv.size(); ++i) {
    const std::vector<std::uint32_t>& m = members[i];
    auto failure = [&] { return ::testing::AssertionFailure() << "supervoxel " << i << " (" << m.size() << " voxels): "; };
    if (m.empty() || sv.voxel_counts[i] != m.size()) return failure() << "voxel_counts " << sv.voxel_counts[i];
    for (const std::uint32_t v : m) {
      if (component[v] != component[m[0]]) return failure() << "voxels " << m[0] << " and " << v << " are not connected";
      if (in.grid.neighbors.count(v) == 0 && m.size() > 1) return failure() << "holds voxel " << v << ", which has no neighbours";
    }
    const Means mean = means_of(in, m);
    if (!near(sv.centroids[i], mean.centroid, 1e-6f)) return failure() << "centroid is not its members' mean";
    if (!near(sv.colors[i], mean.color, 1e-5f)) return failure() << "colour is not its members' mean";
    if (!sv.normals[i].allFinite() || std::abs(sv.normals[i].norm() - 1.0f) > 1e-5f) return failure() << "normal not unit";
    if (!near(sv.normals[i], mean.normal, 1e-5f)) return failure() << "normal is not its planar members' mean";
  }
  return ::testing::AssertionSuccess();
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
bool same_bits(const Supervoxels& a, const Supervoxels& b) {
  return same_bits(a.supervoxel_of_voxel, b.supervoxel_of_voxel) && same_bits(a.absorbed, b.absorbed) &&
         same_bits(a.centroids, b.centroids) && same_bits(a.normals, b.normals) && same_bits(a.colors, b.colors) &&
         same_bits(a.voxel_counts, b.voxel_counts);
}

// Supervoxels holding voxels of two different classes.
std::size_t mixed(const Supervoxels& sv, const std::vector<std::uint32_t>& class_of) {
  std::size_t count = 0;
  for (const std::vector<std::uint32_t>& m : members_of(sv)) {
    count += std::any_of(m.begin(), m.end(), [&](std::uint32_t v) { return class_of[v] != class_of[m[0]]; });
  }
  return count;
}

// ---- random inputs ------------------------------------------------------------

TEST(FloodProperty, RandomInputsKeepEveryInvariantWithTheSameBitsOnAnyThreads) {
  std::size_t empty = 0, unseeded = 0, all_seeds = 0, without_neighbours = 0, full_rows = 0, grown = 0, split = 0;
  for (std::uint32_t c = 0; c < 400; ++c) {
    Rng rng(c);
    const Input in = random_input(rng);
    ASSERT_NO_THROW(validate(in.config)) << "case " << c;
    ASSERT_TRUE(well_formed(in.grid.neighbors)) << "case " << c;
    const Supervoxels sv = grow(in);
    ASSERT_TRUE(flood_invariants(in, sv)) << "case " << c;
    EXPECT_TRUE(same_bits(sv, grow(in))) << "case " << c << ": a second run differs";
    EXPECT_TRUE(same_bits(sv, with_threads(1, [&] { return grow(in); }))) << "case " << c << ": 1 thread differs";
    EXPECT_TRUE(same_bits(sv, with_threads(4, [&] { return grow(in); }))) << "case " << c << ": 4 threads differ";
    // What the cases cover.
    empty += in.size() == 0;
    unseeded += in.size() > 0 && in.seeds.empty();
    all_seeds += in.size() > 0 && in.seeds.size() == in.size();
    for (std::uint32_t v = 0; v < in.size(); ++v) {
      without_neighbours += in.grid.neighbors.count(v) == 0;
      full_rows += in.grid.neighbors.count(v) == 26;
    }
    const std::vector<std::uint32_t> component = components(in.grid.neighbors);
    std::vector<std::uint32_t> in_component(in.size(), 0);
    for (const std::vector<std::uint32_t>& m : members_of(sv)) {
      grown += m.size() > 1;
      split += in_component[component[m[0]]]++ > 0;
    }
  }
  EXPECT_GT(empty, 0u);
  EXPECT_GT(unseeded, 50u);
  EXPECT_GT(all_seeds, 50u);
  EXPECT_GT(without_neighbours, 1000u);
  EXPECT_GT(full_rows, 500u);
  EXPECT_GT(grown, 2000u) << "supervoxels of more than one voxel";
  EXPECT_GT(split, 10000u) << "supervoxels sharing their component with another";
}

// ---- what a patch admits ----------------------------------------------------------

// k directions whose lines lie more than min_deg apart.
std::vector<Vec> lines_apart(Rng& rng, std::size_t k, float min_deg) {
  std::vector<Vec> lines;
  while (lines.size() < k) {
    const Vec d = random_unit(rng);
    const bool apart = std::all_of(lines.begin(), lines.end(), [&](const Vec& e) { return std::abs(d.dot(e)) < std::cos(radians(min_deg)); });
    if (apart) lines.push_back(d);
  }
  return lines;
}

// A point in the view at depth 0.5-3 m.
Vec random_centre(Rng& rng) {
  const float z = uniform(rng, 0.5f, 3.0f);
  return {z * uniform(rng, -0.4f, 0.4f), z * uniform(rng, -0.4f, 0.4f), z};
}

// Voxels whose normals come from 2-4 directions more than the angle (+1.5 deg)
// apart, in a cluster narrower than the depth tolerance and the reach, so only
// the angle can part them. Without it (90 deg), patches take both.
TEST(FloodProperty, NormalsFartherApartThanTheAngleNeverShareASupervoxel) {
  std::size_t mixed_at_90 = 0;
  for (std::uint32_t c = 0; c < 100; ++c) {
    Rng rng(1000 + c);
    const float angle = uniform(rng, 1.0f, 45.0f);
    LccpConfig config = random_config(rng, angle);
    const std::vector<Vec> lines = lines_apart(rng, 2 + below(rng, 3), angle + 1.5f);
    const std::size_t n = 2 + below(rng, 200);
    const Vec centre = random_centre(rng);
    const float radius = 0.2f * std::min(config.sensor.depth_tolerance_m(0.9f * centre.z()), 1.8f * config.supervoxels.seed_size_m);
    std::vector<Vec> xyz(n);
    for (Vec& p : xyz) {
      const Vec direction = random_unit(rng);
      p = centre + radius * uniform(rng, 0.0f, 1.0f) * direction;
    }
    const Graph graph = random_graph(rng, n, uniform(rng, 1.0f, 5.0f));
    Input in = make_input(graph, std::move(xyz), config, random_binning(rng));
    random_flags_colours_seeds(rng, in);
    std::vector<std::uint32_t> line_of(n);
    for (std::size_t v = 0; v < n; ++v) {
      line_of[v] = below(rng, lines.size());
      in.normals.directions[v] = lines[line_of[v]];
    }

    const Supervoxels sv = grow(in);
    ASSERT_TRUE(flood_invariants(in, sv)) << "case " << c;
    EXPECT_EQ(mixed(sv, line_of), 0u) << "case " << c;
    const auto members = members_of(sv);
    for (std::size_t i = 0; i < sv.size(); ++i) {
      const Vec& line = lines[line_of[members[i][0]]];
      EXPECT_GE(std::abs(sv.normals[i].dot(line)), 1.0f - 1e-6f) << "case " << c << ", supervoxel " << i;
    }
    in.config.supervoxels.max_normal_angle_deg = 90.0f;
    mixed_at_90 += mixed(grow(in), line_of) > 0;
  }
  EXPECT_GT(mixed_at_90, 50u);
}

// Voxels on two parallel planes a step apart (1.25 times the depth tolerance at
// their farthest), all within the reach and of one normal, so only the plane
// test can part them. With the planes together (no step), patches take both.
TEST(FloodProperty, VoxelsOffAPatchsPlaneByMoreThanTheToleranceNeverJoinIt) {
  std::size_t mixed_without_step = 0;
  for (std::uint32_t c = 0; c < 100; ++c) {
    Rng rng(2000 + c);
    LccpConfig config = random_config(rng, log_uniform(rng, 0.2f, 90.0f));
    Vec d = random_unit(rng);
    d = d.z() > 0.0f ? Vec(-d) : d;  // facing the sensor
    const Vec u = d.unitOrthogonal(), w = d.cross(u).normalized();
    const Vec centre = random_centre(rng);
    const float radius = uniform(rng, 0.005f, 0.03f);
    const float step = 1.25f * config.sensor.depth_tolerance_m(centre.z() + 0.2f) + 1e-4f;  // |depth offset| < 0.2 m
    config.supervoxels.seed_size_m = (2.0f * radius + step) / 1.8f * uniform(rng, 1.1f, 2.0f);
    config.voxels.voxel_size_m = config.supervoxels.seed_size_m / uniform(rng, 1.0f, 8.0f);
    const std::size_t n = 2 + below(rng, 200);
    std::vector<std::uint32_t> side(n);
    std::vector<Vec> offsets(n);
    for (std::size_t v = 0; v < n; ++v) {
      side[v] = below(rng, 2);
      offsets[v] = in_disc(rng, u, w, radius);
    }
    const auto placed = [&](float h) {
      std::vector<Vec> xyz(n);
      for (std::size_t v = 0; v < n; ++v) xyz[v] = (centre.cast<double>() + (h * side[v] * d + offsets[v]).cast<double>()).cast<float>();
      return xyz;
    };
    const Graph graph = random_graph(rng, n, uniform(rng, 1.0f, 5.0f));
    Input in = make_input(graph, placed(step), config, random_binning(rng));
    random_flags_colours_seeds(rng, in);
    in.normals.directions.assign(n, d);
    ASSERT_NO_THROW(validate(in.config));

    const Supervoxels sv = grow(in);
    ASSERT_TRUE(flood_invariants(in, sv)) << "case " << c;
    EXPECT_EQ(mixed(sv, side), 0u) << "case " << c;
    in.grid.centroids = placed(0.0f);
    mixed_without_step += mixed(grow(in), side) > 0;
  }
  EXPECT_GT(mixed_without_step, 50u);
}

// The seed spacing at depth z as SupervoxelConfig::depth_scaled_seeds says: s,
// or with camera cells s z / z0 beyond z0 = s / (4 v).
float seed_spacing(const LccpConfig& c, Binning binning, float z) {
  const float s = c.supervoxels.seed_size_m, z0 = s / (4.0f * c.voxels.voxel_size_m);
  return c.supervoxels.depth_scaled_seeds && binning == Binning::camera && z > z0 ? s * z / z0 : s;
}

// n voxels on distinct points of a square lattice of the given pitch from
// (-0.3, -0.3) on the plane z = depth, facing the sensor, adjacent at random.
Input lattice_plane(Rng& rng, std::size_t n, float pitch, float depth, const LccpConfig& config, Binning binning) {
  const auto side = static_cast<std::uint32_t>(std::ceil(std::sqrt(2.0 * static_cast<double>(n))));
  std::vector<std::uint32_t> cells(side * side);
  for (std::uint32_t i = 0; i < cells.size(); ++i) cells[i] = i;
  std::shuffle(cells.begin(), cells.end(), rng);
  std::vector<Vec> xyz(n);
  for (std::size_t v = 0; v < n; ++v) {
    xyz[v] = Vec(pitch * static_cast<float>(cells[v] % side) - 0.3f, pitch * static_cast<float>(cells[v] / side) - 0.3f, depth);
  }
  return make_input(random_graph(rng, n, uniform(rng, 0.5f, 5.0f)), std::move(xyz), config, binning);
}

// Neighbours farther apart than any patch's reach (1.8 seed spacings at their
// depth), on one plane with one normal: no voxel admits another, so each is a
// supervoxel of its own, the seeds' first (in seed order), then the rest in
// voxel order. Within half the reach they grow together.
TEST(FloodProperty, NeighboursBeyondTheReachAreSupervoxelsOfTheirOwn) {
  std::size_t grown_within_reach = 0;
  for (std::uint32_t c = 0; c < 100; ++c) {
    Rng rng(3000 + c);
    const LccpConfig config = random_config(rng, log_uniform(rng, 0.2f, 90.0f));
    const Binning binning = random_binning(rng);
    const float depth = uniform(rng, 0.5f, 4.0f);
    const float reach = 1.8f * seed_spacing(config, binning, depth);
    const std::size_t n = 1 + below(rng, 150);
    const float pitch = reach * uniform(rng, 1.05f, 2.0f);
    Input in = lattice_plane(rng, n, pitch, depth, config, binning);
    random_flags_colours_seeds(rng, in);

    const Supervoxels sv = grow(in);
    ASSERT_TRUE(flood_invariants(in, sv)) << "case " << c;
    std::vector<std::uint32_t> expected(n, kNoVoxel);
    for (std::uint32_t i = 0; i < in.seeds.size(); ++i) expected[in.seeds[i]] = i;
    auto next = static_cast<std::uint32_t>(in.seeds.size());
    for (std::uint32_t& id : expected) id = id == kNoVoxel ? next++ : id;
    EXPECT_EQ(sv.supervoxel_of_voxel, expected) << "case " << c;

    const Vec origin(-0.3f, -0.3f, depth);
    for (Vec& p : in.grid.centroids) p = origin + (p - origin) * (0.9f * config.supervoxels.seed_size_m / pitch);
    grown_within_reach += grow(in).size() < n;
  }
  EXPECT_GT(grown_within_reach, 50u);
}

// Each component of the adjacency within a disc narrower than the reach, on one
// plane with one normal, with at most one seed: every voxel admits every other,
// so each component is one supervoxel, the seeded ones first (in seed order),
// then the others by their lowest voxel. On a disc four times as wide they split.
TEST(FloodProperty, ComponentsWithinTheReachAreOneSupervoxelEach) {
  std::size_t split_when_wide = 0;
  for (std::uint32_t c = 0; c < 100; ++c) {
    Rng rng(4000 + c);
    const LccpConfig config = random_config(rng, log_uniform(rng, 0.2f, 90.0f));
    const std::size_t n = 1 + below(rng, 200);
    const Graph graph = random_graph(rng, n, uniform(rng, 0.2f, 3.0f));
    Vec d = random_unit(rng);
    d = d.z() > 0.0f ? Vec(-d) : d;
    const Vec u = d.unitOrthogonal(), w = d.cross(u).normalized(), centre = random_centre(rng);
    const float radius = 0.45f * 1.8f * config.supervoxels.seed_size_m;  // diameter 0.9 of the least reach
    std::vector<Vec> offsets(n), xyz(n);
    for (Vec& o : offsets) o = in_disc(rng, u, w, radius);
    for (std::size_t v = 0; v < n; ++v) xyz[v] = centre + offsets[v];
    Input in = make_input(graph, xyz, config, random_binning(rng));
    random_flags_colours_seeds(rng, in);
    in.normals.directions.assign(n, d);
    // At most one seed per component.
    const std::vector<std::uint32_t> component = components(in.grid.neighbors);
    const std::uint32_t count = n == 0 ? 0 : *std::max_element(component.begin(), component.end()) + 1;
    std::vector<std::uint8_t> seeded(count, 0);
    std::erase_if(in.seeds, [&](std::uint32_t v) { return std::exchange(seeded[component[v]], 1) == 1; });

    const Supervoxels sv = grow(in);
    ASSERT_TRUE(flood_invariants(in, sv)) << "case " << c;
    std::vector<std::uint32_t> id_of_component(count, kNoVoxel);
    for (std::uint32_t i = 0; i < in.seeds.size(); ++i) id_of_component[component[in.seeds[i]]] = i;
    auto next = static_cast<std::uint32_t>(in.seeds.size());
    for (std::uint32_t& id : id_of_component) id = id == kNoVoxel ? next++ : id;
    std::vector<std::uint32_t> expected(n);
    for (std::size_t v = 0; v < n; ++v) expected[v] = id_of_component[component[v]];
    EXPECT_EQ(sv.supervoxel_of_voxel, expected) << "case " << c;

    for (std::size_t v = 0; v < n; ++v) in.grid.centroids[v] = centre + 4.0f * offsets[v];
    split_when_wide += grow(in).size() > count;
  }
  EXPECT_GT(split_when_wide, 50u);
}

// ---- a bug found by these tests -------------------------------------------------------------------

// A unit normal near -z whose normal term against itself, 1 - |n . n / |n||,
// rounds below 0 in float.
Vec normal_rounding_above_one() {
  for (int i = 1; i < 2000; ++i) {
    const Vec n = Vec(0.0013f * static_cast<float>(i), 0.0007f * static_cast<float>(i), -1.0f).normalized();
    if (1.0f - std::abs(n.dot(Vec(n / n.norm()))) < 0.0f) return n;
  }
  return Vec::Zero();
}

// Failed until BucketQueue::push (supervoxel_flood.cpp) filed a negative
// distance in bucket 0 (34b1bb5). Voxel x lies between seeds b (voxel 0,
// settled first) and a (voxel 1). b claims x at the normal term of 0.3 deg, 1.4e-5 (bucket ~370). a claims it
// nearer: x's normal equals a's, so with w_s = 0 the distance is the normal
// term alone, which rounds just below 0; times 1023 / 3.8e-5 (the largest
// distance at max_normal_angle_deg 0.5) that is about -3, and converting it
// to size_t was undefined (UBSan: float-cast-overflow), in practice the last
// bucket. So b's claim is popped first and wins x. a then grows the other way
// (three voxels at -0.9 reach), so the refinement finds a's mean beyond x's
// reach and x stays with b.
TEST(FloodProperty, NearerPatchWinsWhenTheNormalTermRoundsBelowZero) {
  const Vec n = normal_rounding_above_one();
  ASSERT_NE(n, Vec::Zero());
  const Vec tilted_b = Eigen::AngleAxisf(radians(0.3f), Vec::UnitY()) * n;
  const Vec tilted_z = Eigen::AngleAxisf(radians(0.3f), Vec::UnitX()) * n;
  LccpConfig config;
  config.voxels = {0.005f, Binning::euclidean};
  config.supervoxels = {.growth = Growth::flood, .seed_size_m = 0.02f, .depth_scaled_seeds = false, .spatial_weight = 0.0f,
                        .normal_weight = 1.0f, .color_weight = 0.0f, .max_normal_angle_deg = 0.5f};
  ASSERT_NO_THROW(validate(config));
  const float r = 1.8f * 0.02f;  // the reach
  Graph graph(6);                // b, a, x, then three voxels beside a
  for (const std::uint32_t beside_a : {2, 3, 4, 5}) graph.connect(1, beside_a);
  graph.connect(0, 2);
  Input in = make_input(graph, {Vec(1.4f * r, 0, 1), Vec(0, 0, 1), Vec(0.9f * r, 0, 1), Vec(-0.9f * r, 0, 1),
                                Vec(-0.9f * r, 0.1f * r, 1), Vec(-0.9f * r, -0.1f * r, 1)},
                        config, Binning::euclidean);
  in.normals.directions = {tilted_b.normalized(), n, n, tilted_z.normalized(), tilted_z.normalized(), tilted_z.normalized()};
  in.seeds = {0, 1};
  const Supervoxels sv = grow(in);
  EXPECT_EQ(sv.supervoxel_of_voxel[2], sv.supervoxel_of_voxel[1]) << "x went to b's patch, not to the nearer a's";
}

}  // namespace
}  // namespace lccp
