#pragma once
// One object resting on a plane, where the object meets the support: a box, a
// dome (a half sphere) or an upside-down bowl (a spherical cap whose rim meets
// the plane at less than 90 deg), ray cast by a Kinect-class camera (640 x 480,
// fx = fy = 525 px) looking down at it. Organized, or unorganized (the same
// finite points, shuffled); noise-free, or with the Kinect v1 depth model of
// src/synthetic/kinect_model.hpp (axial noise, disparity quantization, no
// return beyond 80 deg incidence, random dropouts; the projector's shadow is
// left out). Ground truth in mOSD's convention: 1 the plane, 10 the object.
// World frame: z up, the plane z = 0; the object stands at the origin.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "../src/synthetic/kinect_model.hpp"
#include "../src/synthetic/ray_cast.hpp"
#include "test_clouds.hpp"

namespace lccp::test {

inline constexpr std::uint32_t kContactPlaneLabel = 1;
inline constexpr std::uint32_t kContactObjectLabel = 10;

struct ContactObject {
  enum class Shape { box, cap } shape = Shape::box;
  Eigen::Vector3d box_size = Eigen::Vector3d::Constant(0.1);  // box: edge lengths x, y, z (m)
  double yaw_deg = 0;                                         // box: about z
  double sphere_radius_m = 0.05;                              // cap: its sphere's radius
  double cap_height_m = 0.05;                                 // cap: height; = radius for a dome
  std::string name;
};

inline ContactObject contact_box(double x, double y, double z, double yaw_deg) {
  ContactObject o;
  o.box_size = {x, y, z};
  o.yaw_deg = yaw_deg;
  o.name = "box " + std::to_string(int(std::lround(x * 100))) + "x" + std::to_string(int(std::lround(y * 100))) + "x" +
           std::to_string(int(std::lround(z * 100))) + " cm";
  return o;
}

// A spherical cap of `height` cut from a sphere of `radius`: its surface meets the
// plane at acos((radius - height) / radius), 90 deg for a dome (height = radius).
inline ContactObject contact_cap(double radius, double height, const std::string& name) {
  ContactObject o;
  o.shape = ContactObject::Shape::cap;
  o.sphere_radius_m = radius;
  o.cap_height_m = height;
  o.name = name;
  return o;
}

struct ContactView {
  double distance_m = 0.9;     // eye to the object's footprint centre
  double elevation_deg = 45;   // above the plane
  double azimuth_deg = -70;    // direction from the object to the eye, from world +x
  double plane_side_m = 0.6;   // the plane: a square centred under the object
  bool organized = true;
  bool noisy = false;
  std::uint64_t seed = 1;      // noise and shuffle
};

struct ContactScene {
  PointCloud cloud;
  Labels truth;  // per point: 0 no return, kContactPlaneLabel, kContactObjectLabel
  Pose camera_from_world;
};

namespace detail {

using synthetic::detail::Hit;
using synthetic::detail::Ray;

inline Hit hit_plane(const Ray& ray, double half_side) {
  Hit hit;
  if (ray.direction.z() >= 0) return hit;
  const double t = -ray.origin.z() / ray.direction.z();
  const Eigen::Vector3d p = ray.origin + t * ray.direction;
  if (std::abs(p.x()) <= half_side && std::abs(p.y()) <= half_side) hit.t = t, hit.normal = Eigen::Vector3d::UnitZ();
  return hit;
}

// The solid cap: the part of the sphere about (0, 0, height - radius) above z = 0.
inline Hit hit_cap(const Ray& ray, double radius, double height) {
  Hit hit;
  const Eigen::Vector3d c(0, 0, height - radius), oc = ray.origin - c;
  const double a = ray.direction.squaredNorm(), b = oc.dot(ray.direction), k = oc.squaredNorm() - radius * radius;
  const double disc = b * b - a * k;
  if (disc < 0) return hit;
  const double t = (-b - std::sqrt(disc)) / a;
  const Eigen::Vector3d p = ray.origin + t * ray.direction;
  if (t > 0 && p.z() >= 0) hit.t = t, hit.normal = (p - c) / radius;
  return hit;
}

inline Hit hit_object(const Ray& world_ray, const ContactObject& o) {
  if (o.shape == ContactObject::Shape::cap) return hit_cap(world_ray, o.sphere_radius_m, o.cap_height_m);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(deg2rad(o.yaw_deg), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Ray local{R.transpose() * world_ray.origin, R.transpose() * world_ray.direction};
  const Eigen::Vector3d half(o.box_size.x() / 2, o.box_size.y() / 2, o.box_size.z());
  Hit hit = synthetic::detail::intersect_box(local, {-half.x(), -half.y(), 0}, half);
  hit.normal = R * hit.normal;
  return hit;
}

// The Kinect v1 measurement of true depth z on a surface hit at `cos2` =
// cos^2(incidence), with the pixel's random numbers as the synthetic scene draws
// them (synthetic::detail::pixel_noise): NaN for no return, else the quantized noisy depth.
inline double measure_depth(double z, double cos2, const synthetic::detail::PixelNoise& noise) {
  namespace k = synthetic::detail;
  const bool returns = cos2 >= k::kCosMaxIncidenceSquared && z >= k::kMinRangeM && z <= k::kMaxRangeM;
  if (!returns || noise.dropout) return kNaN;
  return k::quantize_depth_m(z + k::axial_noise_sigma_m(z) * noise.gaussian);
}

}  // namespace detail

inline ContactScene contact_scene(const ContactObject& object, const ContactView& view) {
  const double el = deg2rad(view.elevation_deg), az = deg2rad(view.azimuth_deg);
  const double height = object.shape == ContactObject::Shape::box ? object.box_size.z() : object.cap_height_m;
  const Eigen::Vector3d target(0, 0, height / 3);
  const Eigen::Vector3d eye =
      target + view.distance_m * Eigen::Vector3d(std::cos(az) * std::cos(el), std::sin(az) * std::cos(el), std::sin(el));
  const Pose pose = look_at(eye, target);
  const PinholeCamera cam;
  const synthetic::detail::NormalDeviates normal;
  const std::uint64_t key = synthetic::detail::frame_key(view.seed, 0);
  ContactScene scene;
  scene.camera_from_world = pose;
  scene.cloud.width = static_cast<std::uint32_t>(cam.width);
  scene.cloud.height = static_cast<std::uint32_t>(cam.height);
  for (int row = 0; row < cam.height; ++row) {
    for (int col = 0; col < cam.width; ++col) {
      const Eigen::Vector3d d_cam((col - cam.cx) / cam.focal_px, (row - cam.cy) / cam.focal_px, 1.0);
      const detail::Ray ray{eye, pose.R.transpose() * d_cam};  // t = depth along the optical axis
      const detail::Hit on_plane = detail::hit_plane(ray, view.plane_side_m / 2);
      const detail::Hit on_object = detail::hit_object(ray, object);
      const bool object_first = on_object.t < on_plane.t;
      const detail::Hit& hit = object_first ? on_object : on_plane;
      double z = hit.t;
      if (z < synthetic::detail::kNoHit && view.noisy) {
        const double c = ray.direction.normalized().dot(hit.normal);
        const std::uint64_t pixel = std::uint64_t(row) * std::uint64_t(cam.width) + std::uint64_t(col);
        z = detail::measure_depth(z, c * c, synthetic::detail::pixel_noise(key, pixel, normal));
      }
      const bool seen = z < synthetic::detail::kNoHit && std::isfinite(z);
      scene.cloud.points.push_back(seen ? Eigen::Vector3f((z * d_cam).cast<float>()) : Eigen::Vector3f::Constant(kNaN));
      scene.truth.push_back(!seen ? 0 : object_first ? kContactObjectLabel : kContactPlaneLabel);
    }
  }
  if (view.organized) return scene;
  std::vector<std::size_t> finite;
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    if (scene.truth[i] != 0) finite.push_back(i);
  }
  std::shuffle(finite.begin(), finite.end(), std::mt19937_64(view.seed));
  ContactScene out;
  out.camera_from_world = pose;
  for (const std::size_t i : finite) out.cloud.points.push_back(scene.cloud.points[i]), out.truth.push_back(scene.truth[i]);
  out.cloud.width = static_cast<std::uint32_t>(finite.size());
  out.cloud.height = 1;
  return out;
}

// The battery: boxes from 5 cm wide to 3x taller than wide, domes, and
// upside-down bowls whose rim meets the plane at 60 and 45 deg.
inline std::vector<ContactObject> contact_objects() {
  return {contact_box(0.05, 0.05, 0.05, 20),     contact_box(0.05, 0.05, 0.15, 20),
          contact_box(0.06, 0.15, 0.07, 30),     contact_box(0.10, 0.10, 0.10, 35),
          contact_box(0.08, 0.08, 0.24, 10),     contact_box(0.20, 0.12, 0.05, 15),
          contact_cap(0.05, 0.05, "dome r 5 cm"), contact_cap(0.08, 0.08, "dome r 8 cm"),
          contact_cap(0.10, 0.05, "bowl r 10 cm, rim 60 deg"),
          contact_cap(0.12, 0.12 * (1 - std::cos(deg2rad(45.0))), "bowl r 12 cm, rim 45 deg")};
}

}  // namespace lccp::test
