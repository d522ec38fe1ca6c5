#include "supervoxel_flood.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <tbb/enumerable_thread_specific.h>

#include "neighbour_owners.hpp"
#include "parallel.hpp"
#include "seed_spacing.hpp"

namespace lccp::detail {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;
constexpr float kUnreached = std::numeric_limits<float>::infinity();
constexpr float kReachSeeds = 1.8f;  // VCCS's reach, int(1.8 s / v) - 1 rings of v: 1.8 seed spacings
// Voxels a flood band holds at least (a 640 x 480 table-top frame at P1 has
// about 50 000: four bands). A band's border cuts patches that would cross
// it; both sides lie on one surface, so LCCP's convexity joins them again.
constexpr std::size_t kBandVoxels = 12288;

// What the flood reads of a voxel, in one place: its centroid, the sensor's
// depth tolerance at its depth, its normal.
struct Voxel {
  Eigen::Vector3f xyz;
  float tolerance_m;
  Eigen::Vector3f normal;
};

// A voxel in the flood: its patch once settled, and the distance of its
// nearest claim so far, side by side: a neighbour is checked with one memory access.
struct alignas(8) Claim {
  std::uint32_t owner = kNone;
  float distance = kUnreached;
};

// A patch as a voxel is measured against it: its members' mean as it
// stands (seeded region growing, Adams and Bischof 1994: a voxel is measured
// against the region, not its seed), 1 / s for the seed spacing s at its
// seed's depth, and the square of its reach.
struct Patch {
  Eigen::Vector3f centre;
  Eigen::Vector3f normal;
  Eigen::Vector3f rgb;
  float inverse_spacing;
  float reach_squared;
};

// The sums over a patch's members, updated as voxels settle.
struct PatchSums {
  Eigen::Vector3f xyz = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  Eigen::Vector3f rgb = Eigen::Vector3f::Zero();
  float count = 0;

  // colour: null where the colour weight is 0 (the patch's colour is then not read).
  void add(const Eigen::Vector3f& x, const Eigen::Vector3f& n, const Eigen::Vector3f* colour, Patch& mean) {
    xyz += x;
    normal += n;
    count += 1;
    mean.centre = xyz / count;
    if (colour) {
      rgb += *colour;
      mean.rgb = rgb / count;
    }
    const float length = normal.norm();
    mean.normal = length > 1e-6f ? Eigen::Vector3f(normal / length) : n;
  }
};

// Entries (voxel, patch) in buckets of the VCCS distance: popped smallest
// first, in the order pushed within a bucket (so the same for any run).
class BucketQueue {
 public:
  explicit BucketQueue(float max_distance) : scale_(max_distance > 0 ? (kBuckets - 1) / max_distance : 0) {}

  void push(float distance, std::uint32_t voxel, std::uint32_t patch) {
    // An entry nearer than the bucket being popped joins that bucket: the
    // flood never goes back (a voxel's distance is to a patch, not along a path).
    // Rounding can make 1 - |n1.n2| a hair below 0: such a distance is 0.
    const float bucket = std::min(std::max(distance, 0.0f) * scale_, static_cast<float>(kBuckets - 1));
    const auto b = std::max(static_cast<std::size_t>(bucket), current_);
    buckets_[b].push_back(std::uint64_t{voxel} << 32 | patch);
    highest_ = std::max(highest_, b);
  }

  // Calls visit(voxel, patch) for every entry, smallest bucket first, until
  // none is left; visit may push. Before each, ahead(voxel) for the entry
  // kAhead places on in its bucket.
  template <typename Visit, typename Ahead>
  void drain(Visit visit, Ahead ahead) {
    for (current_ = 0; current_ <= highest_; ++current_) {
      std::vector<std::uint64_t>& bucket = buckets_[current_];
      for (std::size_t i = 0; i < bucket.size(); ++i) {
        if (i + kAhead < bucket.size()) ahead(static_cast<std::uint32_t>(bucket[i + kAhead] >> 32));
        visit(static_cast<std::uint32_t>(bucket[i] >> 32), static_cast<std::uint32_t>(bucket[i]));
      }
      bucket.clear();
    }
    current_ = highest_ = 0;
  }

 private:
  static constexpr std::size_t kBuckets = 1024;
  static constexpr std::size_t kAhead = 8;   // growth 12 % faster than without (4: 7 %, 16: 11 %, 32: 8 %)
  float scale_;
  std::size_t current_ = 0, highest_ = 0;
  std::vector<std::vector<std::uint64_t>> buckets_ = std::vector<std::vector<std::uint64_t>>(kBuckets);
};

// A run of voxel ids [first, last) flooded on its own: ids are x-major, so a
// band is a slab of the grid across x. Its patches and their sums.
struct Band {
  std::uint32_t first = 0, last = 0;
  std::vector<Patch> patches;
  std::vector<PatchSums> sums;
};

class Flood {
 public:
  Flood(const VoxelGrid& grid, const VoxelNormals& normals, const LccpConfig& config)
      : grid_(grid), planar_(normals.planar), config_(config.supervoxels),
        spacing_(config.supervoxels, config.voxels.voxel_size_m, grid.binning),
        cos_max_angle_(std::cos(config.supervoxels.max_normal_angle_deg * std::numbers::pi_v<float> / 180.0f)),
        coloured_(config.supervoxels.color_weight > 0.0f), voxels_(grid.size()), claims_(grid.size()) {
    parallel_for_each_index(grid.size(), [&](std::size_t v) {
      const Eigen::Vector3f& x = grid.centroids[v];
      voxels_[v] = {x, config.sensor.depth_tolerance_m(x.z()), normals.directions[v]};
    });
  }

  // The voxels in bands of fixed size, each flooded on its own, in parallel:
  // a band's seeds' patches flood its voxels together; what none of them
  // admits seeds patches of its own, in voxel order. Patch ids follow the
  // bands. A thread's bands take turns with one queue, which a flood leaves
  // empty: its buckets' memory is allocated once (growth 8 % faster than a queue per band).
  void grow(const std::vector<std::uint32_t>& seeds) {
    std::vector<Band> bands = make_bands();
    tbb::enumerable_thread_specific<BucketQueue> queues(max_distance());
    parallel_for_each_index(bands.size(), [&](std::size_t b) { flood(bands[b], queues.local(), seeds); });
    owner_.resize(claims_.size());
    for (Band& band : bands) {
      const auto offset = static_cast<std::uint32_t>(patches_.size());
      for (std::uint32_t v = band.first; v < band.last; ++v) owner_[v] = offset + claims_[v].owner;
      patches_.insert(patches_.end(), band.patches.begin(), band.patches.end());
    }
  }

  void refine();
  Supervoxels finish() const;

 private:
  // The largest distance an admitted voxel can have: the normal term at the
  // largest angle, the colour term, the spatial term at the reach.
  float max_distance() const {
    return config_.normal_weight * (1.0f - cos_max_angle_) + config_.color_weight * std::sqrt(3.0f) +
           config_.spatial_weight * kReachSeeds;
  }

  // Bands of at least kBandVoxels voxels (one if fewer), equal in size: they
  // depend on the grid alone, never on the thread count, so the labels do not either.
  std::vector<Band> make_bands() const {
    const std::size_t n = claims_.size(), count = std::max<std::size_t>(1, n / kBandVoxels);
    std::vector<Band> bands;
    for (std::size_t b = 0; b < count; ++b) {
      bands.push_back(Band{static_cast<std::uint32_t>(n * b / count), static_cast<std::uint32_t>(n * (b + 1) / count),
                           {}, {}});
    }
    return bands;
  }

  void flood(Band& band, BucketQueue& queue, const std::vector<std::uint32_t>& seeds) {
    const auto drain = [&] {
      queue.drain([&](std::uint32_t u, std::uint32_t k) { settle(band, queue, u, k); },
                  [&](std::uint32_t u) { fetch(u); });
    };
    for (const std::uint32_t v : seeds) {
      if (v >= band.first && v < band.last) plant(band, queue, v);
    }
    drain();
    for (std::uint32_t v = band.first; v < band.last; ++v) {
      if (claims_[v].owner != kNone) continue;
      plant(band, queue, v);
      drain();
    }
  }

  void plant(Band& band, BucketQueue& queue, std::uint32_t v) {
    const float spacing = spacing_.at(voxels_[v].xyz.z());
    const float reach = kReachSeeds * spacing;
    band.patches.push_back({voxels_[v].xyz, voxels_[v].normal, grid_.colors[v], 1.0f / spacing, reach * reach});
    band.sums.emplace_back();
    claims_[v].distance = 0;
    queue.push(0, v, static_cast<std::uint32_t>(band.patches.size() - 1));
  }

  // What settle(u) reads first, fetched early: u's claim and its neighbour
  // list, scattered over a band that does not fit a core's cache (perf:
  // settle waited most on the list). Inlined: GCC 12 takes a function that
  // only prefetches for one without effect and drops the calls to it.
  [[gnu::always_inline]] void fetch(std::uint32_t u) const {
    __builtin_prefetch(&claims_[u]);
    __builtin_prefetch(grid_.neighbors.begin(u));
  }

  // Voxel u joins patch k of its band (its first and nearest claim); its free
  // neighbours in the band that k admits are queued at their distance to k as
  // it now stands, if nearer than their nearest claim so far.
  void settle(Band& band, BucketQueue& queue, std::uint32_t u, std::uint32_t k) {
    if (claims_[u].owner != kNone) return;
    claims_[u].owner = k;
    band.sums[k].add(voxels_[u].xyz, voxels_[u].normal, coloured_ ? &grid_.colors[u] : nullptr, band.patches[k]);
    const Patch& patch = band.patches[k];
    // The free neighbours in the band, listed without branches (which of
    // them are free is unpredictable), then measured.
    std::array<std::uint32_t, 26> free;
    std::size_t count = 0;
    const std::uint32_t span = band.last - band.first;
    for (const std::uint32_t* w = grid_.neighbors.begin(u); w != grid_.neighbors.end(u); ++w) {
      const std::uint32_t x = *w - band.first < span ? *w : u;  // u is settled: never listed
      free[count] = x;
      count += claims_[x].owner == kNone;
    }
    for (std::size_t i = 0; i < count; ++i) {
      Claim& claim = claims_[free[i]];
      const float d = admitted_distance(free[i], patch);
      if (!(d < claim.distance)) continue;
      claim.distance = d;
      queue.push(d, free[i], k);
    }
  }

  float distance(std::uint32_t v, const Patch& p) const;
  float admitted_distance(std::uint32_t v, const Patch& p) const;

  const VoxelGrid& grid_;
  const std::vector<std::uint8_t>& planar_;
  const SupervoxelConfig& config_;
  const SeedSpacing spacing_;
  const float cos_max_angle_;
  const bool coloured_;
  std::vector<Voxel> voxels_;
  std::vector<Claim> claims_;
  std::vector<std::uint32_t> owner_;  // per voxel, its patch once the flood is done
  std::vector<Patch> patches_;  // every band's, in band order
};

// D = w_n (1 - |n1.n2|) + w_c |drgb| / 255 + w_s |dx| / s   (VCCS distance; s at the seed's depth)
float Flood::distance(std::uint32_t v, const Patch& p) const {
  const Voxel& x = voxels_[v];
  const float colour = coloured_ ? config_.color_weight * (grid_.colors[v] - p.rgb).norm() / 255.0f : 0.0f;
  return config_.normal_weight * (1.0f - std::abs(x.normal.dot(p.normal))) + colour +
         config_.spatial_weight * (x.xyz - p.centre).norm() * p.inverse_spacing;
}

// D if patch p admits voxel v, else infinity. A patch admits a voxel on its
// own surface: its normal within max_normal_angle_deg of the patch's (a larger
// change is a crease), its centroid within the sensor's depth tolerance of the
// patch's plane (farther is a step, where two faces meet), and within 1.8 s of its centre.
float Flood::admitted_distance(std::uint32_t v, const Patch& p) const {
  const Voxel& x = voxels_[v];
  const Eigen::Vector3f offset = x.xyz - p.centre;
  const float cosine = std::abs(x.normal.dot(p.normal)), squared = offset.squaredNorm();
  const bool admitted = cosine >= cos_max_angle_ && std::abs(offset.dot(p.normal)) <= x.tolerance_m &&
                        squared <= p.reach_squared;
  if (!admitted) return kUnreached;
  const float colour = coloured_ ? config_.color_weight * (grid_.colors[v] - p.rgb).norm() / 255.0f : 0.0f;
  return config_.normal_weight * (1.0f - cosine) + colour + config_.spatial_weight * std::sqrt(squared) * p.inverse_spacing;
}

// One VCCS pass against the flooded patches' means (a boundary refinement):
// a voxel moves to the neighbouring patch nearest to it if that patch admits
// it. Every voxel reads the flood's owners and writes its own, so the pass is
// parallel and the same for any thread count; the sums are taken after it.
void Flood::refine() {
  std::vector<std::uint32_t> next(owner_.size());
  parallel_for_each_index(owner_.size(), [&](std::size_t index) {
    const auto v = static_cast<std::uint32_t>(index);
    const std::uint32_t own = owner_[v];
    // The neighbours' other patches, then measured.
    std::array<std::uint32_t, 26> foreign;
    const std::size_t count = neighbour_owners(
        grid_.neighbors, v, owner_.data(), [own](std::uint32_t, std::uint32_t k) { return k != own; }, foreign);
    std::uint32_t best = own;
    float best_distance = count > 0 ? distance(v, patches_[own]) : 0.0f;
    for (std::size_t i = 0; i < count; ++i) {
      const float d = admitted_distance(v, patches_[foreign[i]]);
      const bool nearer = d < best_distance || (d == best_distance && foreign[i] < best);
      best = nearer ? foreign[i] : best;
      best_distance = nearer ? d : best_distance;
    }
    next[v] = best;
  });
  owner_.swap(next);
}

// Patches as LCCP reads them: the mean centroid and colour of their members,
// in voxel order, and the normalized sum of their planar members' normals (of
// all members' if none is planar): a member whose normal straddles a crease
// or a step would turn the patch's toward the surface beside it. Patches the
// refinement emptied are dropped.
Supervoxels Flood::finish() const {
  std::vector<Eigen::Vector3d> xyz(patches_.size(), Eigen::Vector3d::Zero()), normal = xyz, planar = xyz, rgb = xyz;
  std::vector<std::uint32_t> count(patches_.size(), 0);
  for (std::size_t v = 0; v < owner_.size(); ++v) {
    const std::uint32_t k = owner_[v];
    xyz[k] += voxels_[v].xyz.cast<double>();
    normal[k] += voxels_[v].normal.cast<double>();
    if (planar_[v]) planar[k] += voxels_[v].normal.cast<double>();
    rgb[k] += grid_.colors[v].cast<double>();
    ++count[k];
  }
  Supervoxels result;
  std::vector<std::uint32_t> new_id(patches_.size(), kNone);
  for (std::size_t k = 0; k < patches_.size(); ++k) {
    if (count[k] == 0) continue;
    new_id[k] = static_cast<std::uint32_t>(result.size());
    const Eigen::Vector3f centroid = (xyz[k] / count[k]).cast<float>();
    const Eigen::Vector3d& sum = planar[k].norm() > 1e-6 ? planar[k] : normal[k];
    const double length = sum.norm();
    result.centroids.push_back(centroid);
    result.normals.push_back(length > 1e-6 ? Eigen::Vector3f((sum / length).cast<float>()) : Eigen::Vector3f(-centroid.normalized()));
    result.colors.push_back((rgb[k] / count[k]).cast<float>());
    result.voxel_counts.push_back(count[k]);
  }
  result.supervoxel_of_voxel.resize(owner_.size());
  for (std::size_t v = 0; v < owner_.size(); ++v) result.supervoxel_of_voxel[v] = new_id[owner_[v]];
  result.absorbed.assign(owner_.size(), 0);
  return result;
}

}  // namespace

Supervoxels flood_supervoxels(const VoxelGrid& grid, const VoxelNormals& voxel_normals,
                              const std::vector<std::uint32_t>& seeds, const LccpConfig& config) {
  Flood flood(grid, voxel_normals, config);
  flood.grow(seeds);
  flood.refine();
  return flood.finish();
}

}  // namespace lccp::detail
