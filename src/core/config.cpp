#include "lccp/config.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "lccp/error.hpp"

namespace lccp {
namespace {

void require(bool ok, const char* key, const std::string& rule, double value) {
  if (ok) return;
  std::ostringstream message;
  message << "config key '" << key << "' must be " << rule << " (got " << value << ")";
  throw Error(message.str());
}

bool in_range(float value, float low, float high) { return std::isfinite(value) && value >= low && value <= high; }

void validate_limits(const LccpConfig& c) {
  const LimitsConfig& l = c.limits;
  require(l.max_points > 0, "max_points", "> 0", l.max_points);
  require(l.max_voxels > 0 && l.max_voxels <= (1u << 31), "max_voxels", "in [1, 2^31]", l.max_voxels);
  require(l.max_growth_passes > 0 && l.max_growth_passes <= 100000u, "max_growth_passes", "in [1, 100000]",
          l.max_growth_passes);
  // A float's spacing at range r is r / 2^23; at most v / 16 keeps voxels apart.
  require(in_range(l.max_coordinate_m, 0.0f, c.voxels.voxel_size_m * 524288.0f) && l.max_coordinate_m > 0.0f,
          "max_coordinate_m", "> 0 and <= voxel_size_m * 2^19 (float spacing below v/16)", l.max_coordinate_m);
  const int passes = growth_passes(c.supervoxels.seed_size_m, c.voxels.voxel_size_m);
  require(passes <= static_cast<int>(l.max_growth_passes), "seed_size_m",
          "small enough for max_growth_passes (" + std::to_string(l.max_growth_passes) +
              ") growth passes, int(1.8 s / v) - 1", passes);
}

void validate_support(const SupportPlaneConfig& s) {
  require(in_range(s.distance_m, 1e-6f, 10.0f), "support_distance_m", "in (0, 10]", s.distance_m);
  require(in_range(s.up_x, -1e6f, 1e6f) && in_range(s.up_y, -1e6f, 1e6f) && in_range(s.up_z, -1e6f, 1e6f),
          "support_up_x", "finite (so must support_up_y and support_up_z be)", s.up_x);
  require(in_range(s.max_tilt_deg, 0.0f, 90.0f), "support_max_tilt_deg", "in [0, 90]", s.max_tilt_deg);
  require(in_range(s.min_inlier_share, 0.0f, 1.0f), "support_min_share", "in [0, 1]", s.min_inlier_share);
  require(s.iterations > 0 && s.iterations <= 100000u, "support_iterations", "in [1, 100000]", s.iterations);
  require(in_range(s.noise_sigmas, 0.0f, 100.0f), "support_noise_sigmas", "in [0, 100]", s.noise_sigmas);
}

void validate_grouping(const LccpConfig& c) {
  const GroupingConfig& g = c.grouping;
  require(in_range(g.contact_m, 0.0f, 10.0f), "object_contact_m", "in [0, 10]", g.contact_m);
  require(in_range(g.upward_max_tilt_deg, 0.0f, 90.0f), "upward_max_tilt_deg", "in [0, 90]", g.upward_max_tilt_deg);
  require(in_range(g.occluded_gap_m, 0.0f, 10.0f), "occluded_gap_m", "in [0, 10]", g.occluded_gap_m);
  require(!g.objects_from_parts || c.support.enabled, "objects_from_parts",
          "false without support_plane: true (parts are grouped by how they rest on the support)", g.objects_from_parts);
}

void validate_sensor(const SensorConfig& s) {
  require(in_range(s.focal_px, 1.0f, 1e5f), "sensor_focal_px", "in [1, 1e5]", s.focal_px);
  require(in_range(s.baseline_m, 1e-4f, 10.0f), "sensor_baseline_m", "in [1e-4, 10]", s.baseline_m);
  require(in_range(s.disparity_step_px, 0.0f, 100.0f), "sensor_disparity_step_px", "in [0, 100]", s.disparity_step_px);
  require(in_range(s.axial_sigma_m, 0.0f, 1.0f), "sensor_axial_sigma_m", "in [0, 1]", s.axial_sigma_m);
  require(in_range(s.axial_sigma_per_m2, 0.0f, 1.0f), "sensor_axial_sigma_per_m2", "in [0, 1]", s.axial_sigma_per_m2);
  require(in_range(s.min_range_m, 0.0f, 100.0f), "sensor_min_range_m", "in [0, 100]", s.min_range_m);
}

void validate_region(const RegionConfig& r) {
  const auto axis = [](float low, float high, const char* min_key) {
    require(!std::isnan(low) && !std::isnan(high) && low < high, min_key,
            "below its max key (a number; inf and -inf: unbounded)", low);
  };
  axis(r.min_x_m, r.max_x_m, "region_min_x_m");
  axis(r.min_y_m, r.max_y_m, "region_min_y_m");
  axis(r.min_z_m, r.max_z_m, "region_min_z_m");
}

}  // namespace

bool RegionConfig::bounded() const {
  return std::isfinite(min_x_m) || std::isfinite(max_x_m) || std::isfinite(min_y_m) || std::isfinite(max_y_m) ||
         std::isfinite(min_z_m) || std::isfinite(max_z_m);
}

float SensorConfig::depth_tolerance_m(float z_m) const {
  const float z = std::max(z_m, min_range_m);
  const float beyond = z - min_range_m;
  return depth_step_m(z) + 2.0f * (axial_sigma_m + axial_sigma_per_m2 * beyond * beyond);
}

void validate(const SceneConfig& c) {
  validate(c.objects);
  if (!c.parts) return;
  if (c.objects.grouping.objects_from_parts) {
    throw Error("config key 'objects_from_parts' makes the objects from this level's segments: drop the parts: map");
  }
  try {
    validate(*c.parts);
  } catch (const Error& e) {
    throw Error(std::string("parts: ") + e.what());
  }
  if (c.parts->grouping.objects_from_parts) {
    throw Error("config key 'parts.objects_from_parts' must be false: objects are grouped at the first level");
  }
  if (c.parts->support.enabled) {
    throw Error("config key 'parts.support_plane' must be false: the support plane is removed once, before the objects");
  }
}

void validate(const LccpConfig& c) {
  validate_region(c.region);
  validate_support(c.support);
  validate_grouping(c);
  require(std::isfinite(c.voxels.voxel_size_m) && c.voxels.voxel_size_m > 0.0f, "voxel_size_m", "> 0",
          c.voxels.voxel_size_m);
  require(std::isfinite(c.supervoxels.seed_size_m) && c.supervoxels.seed_size_m >= c.voxels.voxel_size_m,
          "seed_size_m", ">= voxel_size_m", c.supervoxels.seed_size_m);
  require(in_range(c.supervoxels.spatial_weight, 0.0f, 1e6f), "spatial_weight", ">= 0", c.supervoxels.spatial_weight);
  require(in_range(c.supervoxels.normal_weight, 0.0f, 1e6f), "normal_weight", ">= 0", c.supervoxels.normal_weight);
  require(in_range(c.supervoxels.color_weight, 0.0f, 1e6f), "color_weight", ">= 0", c.supervoxels.color_weight);
  require(in_range(c.normals.planar_variation, 0.0f, 1.0f / 3.0f), "planar_variation", "in [0, 1/3]",
          c.normals.planar_variation);
  require(in_range(c.supervoxels.max_normal_angle_deg, 0.0f, 90.0f), "max_normal_angle_deg", "in [0, 90]",
          c.supervoxels.max_normal_angle_deg);
  validate_sensor(c.sensor);
  require(in_range(c.convexity.beta_thresh_deg, 0.0f, 180.0f), "beta_thresh_deg", "in [0, 180]",
          c.convexity.beta_thresh_deg);
  require(in_range(c.convexity.theta_max_deg, 0.0f, 90.0f), "theta_max_deg", "in [0, 90]", c.convexity.theta_max_deg);
  require(in_range(c.convexity.beta_off_deg, 0.0f, 180.0f), "beta_off_deg", "in [0, 180]", c.convexity.beta_off_deg);
  require(in_range(c.convexity.sigmoid_slope_per_deg, 1e-6f, 1e3f), "sigmoid_slope_per_deg", "> 0",
          c.convexity.sigmoid_slope_per_deg);
  require(in_range(c.convexity.smoothness_threshold, 0.0f, 1e6f), "smoothness_threshold", ">= 0",
          c.convexity.smoothness_threshold);
  require(c.filter.n_filter_supervoxels <= 1000000u, "n_filter_supervoxels", "<= 1000000",
          c.filter.n_filter_supervoxels);
  validate_limits(c);
}

int growth_passes(float seed_size_m, float voxel_size_m) {
  const float passes = 1.8f * seed_size_m / voxel_size_m;  // float, as the stage always computed it
  if (!(passes < 1e9f)) return 1'000'000'000;
  return std::max(1, static_cast<int>(passes) - 1);
}

}  // namespace lccp
