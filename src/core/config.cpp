#include "lccp/config.hpp"

#include <cmath>
#include <sstream>

#include "lccp/error.hpp"

namespace lccp {
namespace {

void require(bool ok, const char* key, const char* rule, double value) {
  if (ok) return;
  std::ostringstream message;
  message << "config key '" << key << "' must be " << rule << " (got " << value << ")";
  throw Error(message.str());
}

bool in_range(float value, float low, float high) { return std::isfinite(value) && value >= low && value <= high; }

}  // namespace

void validate(const LccpConfig& c) {
  require(std::isfinite(c.voxels.voxel_size_m) && c.voxels.voxel_size_m > 0.0f, "voxel_size_m", "> 0",
          c.voxels.voxel_size_m);
  require(std::isfinite(c.supervoxels.seed_size_m) && c.supervoxels.seed_size_m >= c.voxels.voxel_size_m,
          "seed_size_m", ">= voxel_size_m", c.supervoxels.seed_size_m);
  require(in_range(c.supervoxels.spatial_weight, 0.0f, 1e6f), "spatial_weight", ">= 0", c.supervoxels.spatial_weight);
  require(in_range(c.supervoxels.normal_weight, 0.0f, 1e6f), "normal_weight", ">= 0", c.supervoxels.normal_weight);
  require(in_range(c.supervoxels.color_weight, 0.0f, 1e6f), "color_weight", ">= 0", c.supervoxels.color_weight);
  require(in_range(c.convexity.beta_thresh_deg, 0.0f, 180.0f), "beta_thresh_deg", "in [0, 180]",
          c.convexity.beta_thresh_deg);
  require(in_range(c.convexity.theta_max_deg, 0.0f, 90.0f), "theta_max_deg", "in [0, 90]", c.convexity.theta_max_deg);
  require(in_range(c.convexity.beta_off_deg, 0.0f, 180.0f), "beta_off_deg", "in [0, 180]", c.convexity.beta_off_deg);
  require(in_range(c.convexity.sigmoid_slope_per_deg, 1e-6f, 1e3f), "sigmoid_slope_per_deg", "> 0",
          c.convexity.sigmoid_slope_per_deg);
  require(c.filter.n_filter_supervoxels <= 1000000u, "n_filter_supervoxels", "<= 1000000",
          c.filter.n_filter_supervoxels);
}

}  // namespace lccp
