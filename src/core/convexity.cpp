#include "lccp/core/convexity.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

namespace lccp {
namespace {

constexpr float kDegreesPerRadian = 180.0f / std::numbers::pi_v<float>;

float angle_deg(float cosine) { return std::acos(std::clamp(cosine, -1.0f, 1.0f)) * kDegreesPerRadian; }

// d_hat = (x1 - x2) / |x1 - x2|; zero when the centroids coincide.
Eigen::Vector3f centroid_direction(const Patch& p1, const Patch& p2) {
  const Eigen::Vector3f d = p1.centroid - p2.centroid;
  const float length = d.norm();
  return length > 0.0f ? Eigen::Vector3f(d / length) : Eigen::Vector3f::Zero();
}

}  // namespace

float normal_angle_deg(const Patch& p1, const Patch& p2) { return angle_deg(p1.normal.dot(p2.normal)); }

float sanity_threshold_deg(float beta_deg, const ConvexityConfig& config) {
  // Eq. (3)
  return config.theta_max_deg / (1.0f + std::exp(-config.sigmoid_slope_per_deg * (beta_deg - config.beta_off_deg)));
}

float sanity_angle_deg(const Patch& p1, const Patch& p2) {
  // Eq. (2): theta = min(angle(d, s), 180 - angle(d, s)) with s = n1 x n2.
  const Eigen::Vector3f s = p1.normal.cross(p2.normal);
  const Eigen::Vector3f d_hat = centroid_direction(p1, p2);
  const float s_length = s.norm();
  if (s_length < 1e-6f || d_hat.isZero()) return 90.0f;  // parallel normals: no intersection line
  return angle_deg(std::abs(d_hat.dot(s / s_length)));
}

float convexity_measure(const Patch& p1, const Patch& p2) {
  // Eq. (1): (n1 - n2) . d_hat
  return (p1.normal - p2.normal).dot(centroid_direction(p1, p2));
}

bool convexity_criterion(const Patch& p1, const Patch& p2, const ConvexityConfig& config) {
  // Eq. (1): (n1 - n2) . d_hat > 0, or beta < beta_thresh.
  return convexity_measure(p1, p2) > 0.0f || normal_angle_deg(p1, p2) < config.beta_thresh_deg;
}

bool sanity_criterion(const Patch& p1, const Patch& p2, const ConvexityConfig& config) {
  // Eq. (4): theta > theta_thresh(beta).
  return sanity_angle_deg(p1, p2) > sanity_threshold_deg(normal_angle_deg(p1, p2), config);
}

bool is_convex(const Patch& p1, const Patch& p2, const ConvexityConfig& config) {
  // Eq. (5)
  return convexity_criterion(p1, p2, config) && (!config.sanity_criterion || sanity_criterion(p1, p2, config));
}

float step_distance_m(const Patch& p1, const Patch& p2) {
  const Eigen::Vector3f d = p1.centroid - p2.centroid;
  return std::min(std::abs(d.dot(p1.normal)), std::abs(d.dot(p2.normal)));
}

// max(smoothness_threshold v, q z^2 / 2), z the patches' mean depth: the sensor
// rounds a depth to the nearest step, so an offset within half a step is not
// measured (SensorConfig::depth_steps).
float smoothness_slack_m(const Patch& p1, const Patch& p2, const ConvexityConfig& config, const PatchSizes& sizes) {
  const float z = 0.5f * (p1.centroid.z() + p2.centroid.z());
  return std::max(config.smoothness_threshold * sizes.voxel_size_m, 0.5f * sizes.depth_step_per_m2 * z * z);
}

bool smoothness_criterion(const Patch& p1, const Patch& p2, const ConvexityConfig& config, const PatchSizes& sizes) {
  const float explained_m = p1.normal.cross(p2.normal).norm() * sizes.seed_size_m;
  return step_distance_m(p1, p2) <= explained_m + smoothness_slack_m(p1, p2, config, sizes);
}

bool corner_criterion(const Patch& p1, const Patch& p2, const ConvexityConfig& config, const PatchSizes& sizes) {
  if (p1.normal.dot(p2.normal) > 0.0f) return true;  // less than 90 deg apart
  const Eigen::Vector3f d = p1.centroid - p2.centroid;
  const float slack = smoothness_slack_m(p1, p2, config, sizes);
  return d.dot(p1.normal) > -slack && d.dot(p2.normal) < slack;
}

std::vector<std::uint8_t> classify_edges(const std::vector<Edge>& edges, const std::vector<Eigen::Vector3f>& centroids,
                                         const std::vector<Eigen::Vector3f>& normals, const ConvexityConfig& config,
                                         const PatchSizes& sizes) {
  std::vector<std::uint8_t> convex(edges.size());
  tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t e) {
    const Patch p1{centroids[edges[e].a], normals[edges[e].a]};
    const Patch p2{centroids[edges[e].b], normals[edges[e].b]};
    convex[e] = is_convex(p1, p2, config) && (!config.smoothness_check || smoothness_criterion(p1, p2, config, sizes)) &&
                (!config.corner_check || corner_criterion(p1, p2, config, sizes));
  });
  return convex;
}

std::vector<float> edge_convexity(const std::vector<Edge>& edges, const std::vector<Eigen::Vector3f>& centroids,
                                  const std::vector<Eigen::Vector3f>& normals) {
  std::vector<float> measure(edges.size());
  tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t e) {
    measure[e] = convexity_measure({centroids[edges[e].a], normals[edges[e].a]}, {centroids[edges[e].b], normals[edges[e].b]});
  });
  return measure;
}

}  // namespace lccp
