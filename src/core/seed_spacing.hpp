#pragma once
// Internal: the seed spacing at a depth (SupervoxelConfig::depth_scaled_seeds),
// shared by seeding and both growths.
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "lccp/config.hpp"

namespace lccp::detail {

// The seed spacing at depth z: s, or with SupervoxelConfig::depth_scaled_seeds and
// camera cells, s z / z0 beyond z0 = s / (4 v) (4 camera cells of side v z).
class SeedSpacing {
 public:
  SeedSpacing(const SupervoxelConfig& config, float voxel_size_m, Binning binning)
      : seed_size_(config.seed_size_m),
        z0_(config.depth_scaled_seeds && binning == Binning::camera ? config.seed_size_m / (4.0f * voxel_size_m)
                                                                    : std::numeric_limits<float>::infinity()) {}

  float at(float z) const { return z > z0_ ? seed_size_ * (z / z0_) : seed_size_; }  // metres

  // A point's place in a grid whose cells are at(z) wide: beyond z0, x and y
  // scaled by s / at(z) and z by z0 (1 + ln(z / z0)), whose slope s / at(z)
  // meets 1 at z0. Nearer, the point itself.
  Eigen::Vector3f grid_position(const Eigen::Vector3f& p) const {
    if (!(p.z() > z0_)) return p;
    const float ratio = p.z() / z0_;
    return {p.x() / ratio, p.y() / ratio, z0_ * (1.0f + std::log(ratio))};
  }

 private:
  float seed_size_;
  float z0_;  // infinite: s everywhere, as VCCS
};

}  // namespace lccp::detail
