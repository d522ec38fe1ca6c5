#pragma once
// Stage 6 (kStages): edge classification, paper Appendix A.2, eq. (1)-(5).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lccp/config.hpp"
#include "lccp/core/adjacency.hpp"

namespace lccp {

struct Patch {
  Eigen::Vector3f centroid;
  Eigen::Vector3f normal;  // unit
};

// beta = angle between the normals, degrees.
float normal_angle_deg(const Patch& p1, const Patch& p2);
// Eq. (3): theta_thresh(beta) = theta_max / (1 + exp(-a (beta - beta_off))), degrees.
float sanity_threshold_deg(float beta_deg, const ConvexityConfig& config);
// Eq. (2): angle between d = x1 - x2 and s = n1 x n2, folded to [0, 90] degrees;
// 90 when s vanishes (parallel normals: no singular configuration).
float sanity_angle_deg(const Patch& p1, const Patch& p2);
// Eq. (1)'s left side: (n1 - n2) . d_hat, d_hat = (x1 - x2) / |x1 - x2|;
// positive where the patches meet convexly, negative where concavely, the
// same whichever patch is first.
float convexity_measure(const Patch& p1, const Patch& p2);
// Eq. (1): (n1 - n2) . d_hat > 0 or beta < beta_thresh.
bool convexity_criterion(const Patch& p1, const Patch& p2, const ConvexityConfig& config);
// Eq. (4): theta > theta_thresh(beta).
bool sanity_criterion(const Patch& p1, const Patch& p2, const ConvexityConfig& config);
// Eq. (5): CC and (SC if enabled).
bool is_convex(const Patch& p1, const Patch& p2, const ConvexityConfig& config);

// The sizes the smoothness check measures steps against: v, s, and in a
// camera's frame the sensor's depth step q z^2 (SensorConfig::depth_steps).
struct PatchSizes {
  float voxel_size_m;
  float seed_size_m;
  float depth_step_per_m2 = 0.0f;  // q; 0: no sensor step
};
// The patches' offset along their normals: min(|d . n1|, |d . n2|), d = x1 - x2, metres.
float step_distance_m(const Patch& p1, const Patch& p2);
// PCL's smoothness check (beyond the paper; pcl/segmentation/impl/
// lccp_segmentation.hpp, connIsConvex): the step is at most |n1 x n2| s, what
// the patches' angle explains over a seed spacing, plus a slack: smoothness_threshold * v,
// or half the sensor's depth step at the patches' mean depth where that is larger.
bool smoothness_criterion(const Patch& p1, const Patch& p2, const ConvexityConfig& config, const PatchSizes& sizes);
// The corner check (beyond the paper, ConvexityConfig::corner_check): true below
// 90 deg between the normals; otherwise d . n1 > -slack and d . n2 < slack, d =
// x1 - x2, slack as in smoothness_criterion: each centroid behind the other's plane.
bool corner_criterion(const Patch& p1, const Patch& p2, const ConvexityConfig& config, const PatchSizes& sizes);

// One flag per edge (1 = convex: eq. (5), and smooth and a corner if those checks are on),
// computed in parallel without locks.
std::vector<std::uint8_t> classify_edges(const std::vector<Edge>& edges,
                                         const std::vector<Eigen::Vector3f>& centroids,
                                         const std::vector<Eigen::Vector3f>& normals,
                                         const ConvexityConfig& config, const PatchSizes& sizes);

// Eq. (1)'s measure per edge (convexity_measure), computed in parallel: what
// the noise filter (FilterConfig::by_convexity) ranks a small segment's
// neighbours by.
std::vector<float> edge_convexity(const std::vector<Edge>& edges, const std::vector<Eigen::Vector3f>& centroids,
                                  const std::vector<Eigen::Vector3f>& normals);

}  // namespace lccp
