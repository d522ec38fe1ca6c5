#pragma once
// Stage 0 (kStages): support-plane removal, the robot application's "initial
// ground plane separation step" (paper Sec. III.C). A parallel RANSAC whose
// result does not depend on the thread count.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "lccp/cloud.hpp"
#include "lccp/config.hpp"

namespace lccp {

// The plane n . p + d = 0, n a unit vector pointing to the sensor's side
// (d > 0 when the sensor at the origin is above it), lengths in metres.
struct Plane {
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();
  float d = 0;
  float distance(const Eigen::Vector3f& p) const { return normal.dot(p) + d; }
};

struct SupportPlane {
  Plane plane;
  std::vector<std::uint8_t> on_plane;  // per point of the cloud: 1 if it belongs to the support
  std::uint64_t inliers = 0;           // points with on_plane == 1
  // The plane's noise: the robust standard deviation (1.4826 times the median
  // absolute distance) of the scoring samples within distance_m of it (metres).
  float noise_m = 0;
};

// The plane with the most finite points within config.distance_m (normal within
// max_tilt_deg of the up direction when one is given), refined by least squares
// over its inliers; empty when it holds fewer than min_inlier_share of the finite
// points. A point is on it within distance_m, or with noise_sigmas > 0 within
// the band SupportPlaneConfig describes (`sensor`: the depth step). Points i
// with skip[i] != 0 (skip: empty or one per point) take no part, and are not on
// the plane. Deterministic for a given cloud and config, whatever the thread count.
std::optional<SupportPlane> find_support_plane(const CloudView& cloud, const SupportPlaneConfig& config,
                                               const std::vector<std::uint8_t>& skip = {},
                                               const SensorConfig& sensor = {});

}  // namespace lccp
