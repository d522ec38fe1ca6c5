#pragma once
// First hits of a ray with the scene's solids, each in its own local frame
// (z up). A ray's direction is not normalized: it is the pixel's direction
// scaled to unit depth along the camera's optical axis, so the ray parameter t
// of a hit is the depth the sensor measures there.
#include <limits>
#include <span>

#include <Eigen/Core>

namespace lccp::synthetic::detail {

inline constexpr double kNoHit = std::numeric_limits<double>::infinity();

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // not normalized
};

struct Hit {
  double t = kNoHit;                                // ray parameter; kNoHit if none
  Eigen::Vector3d normal = Eigen::Vector3d::Zero(); // unit, out of the solid, in the ray's frame
};

// The box [lo, hi] (axis-aligned in the ray's frame).
Hit intersect_box(const Ray& ray, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

// The upright solid cylinder of `radius` about the z axis between z = 0 and `height`.
Hit intersect_cylinder(const Ray& ray, double radius, double height);

// An upright cup on z = 0: the cylinder of outer_radius and `height` minus the
// open-topped cavity of inner_radius above z = bottom. Its inside (inner wall
// and bottom) is seen through the opening.
Hit intersect_cup(const Ray& ray, double outer_radius, double inner_radius, double height, double bottom);

// A tube of `radius` around a polyline: the union of capsules between
// consecutive points.
Hit intersect_tube(const Ray& ray, std::span<const Eigen::Vector3d> centre_line, double radius);

}  // namespace lccp::synthetic::detail
