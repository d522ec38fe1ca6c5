#pragma once
// Objects resting on a plane, where they meet the support and each other, ray
// cast by a Kinect-class camera (640 x 480, fx = fy = 525 px) looking down at
// them. Organized, or unorganized (the same finite points, shuffled);
// noise-free, or with the Kinect v1 depth model of src/synthetic/kinect_model.hpp
// (axial noise, disparity quantization, no return beyond 80 deg incidence,
// random dropouts; the projector's shadow is left out). Ground truth in mOSD's
// convention: 1 the plane, 10, 20, ... the objects (n * 10 + k for part k of
// object n, as mOSD labels a mug's handle).
// World frame: z up, the plane z = 0.
//
// One object (ContactObject: a box, a dome or an upside-down bowl, standing at
// the origin) is the layout of one solid (contact_layout); scenes of several
// objects (contact_clutter.hpp) are layouts of several solids. Both take the
// one ray-casting path of contact_scene(layout, view).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ostream>
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

// One rigid solid, in its own frame, placed in the world by p -> rotation p + position.
struct ContactSolid {
  enum class Shape {
    box,       // [lo, hi]
    cap,       // the part above z = 0 of the sphere of radius_m about (0, 0, height_m - radius_m)
    cylinder,  // radius_m about the z axis, from z = 0 to height_m
    cup,       // that cylinder minus the open-topped cavity of inner_radius_m above z = bottom_m
    tube,      // radius_m around centre_line (ray_cast.hpp's intersect_tube)
  } shape = Shape::box;
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  double radius_m = 0, height_m = 0, inner_radius_m = 0, bottom_m = 0;
  std::vector<Eigen::Vector3d> centre_line;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::uint32_t label = kContactObjectLabel;
};

// What the camera sees: the solids on the plane, and the point it looks at (the
// plane is a square centred under it).
struct ContactLayout {
  std::string name;
  std::vector<ContactSolid> solids;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
};

// GoogleTest prints a parameter through these: by name, not as bytes.
inline void PrintTo(const ContactObject& object, std::ostream* os) { *os << object.name; }
inline void PrintTo(const ContactLayout& layout, std::ostream* os) { *os << layout.name; }

// One object at the origin, labelled kContactObjectLabel; the camera looks at a
// third of its height above its footprint centre.
inline ContactLayout contact_layout(const ContactObject& object) {
  ContactSolid solid;
  double height = object.cap_height_m;
  if (object.shape == ContactObject::Shape::box) {
    height = object.box_size.z();
    solid.lo = {-object.box_size.x() / 2, -object.box_size.y() / 2, 0};
    solid.hi = {object.box_size.x() / 2, object.box_size.y() / 2, height};
    solid.rotation = Eigen::AngleAxisd(deg2rad(object.yaw_deg), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  } else {
    solid.shape = ContactSolid::Shape::cap;
    solid.radius_m = object.sphere_radius_m;
    solid.height_m = object.cap_height_m;
  }
  return {object.name, {solid}, Eigen::Vector3d(0, 0, height / 3)};
}

struct ContactView {
  double distance_m = 0.9;     // eye to the layout's target
  double elevation_deg = 45;   // above the plane
  double azimuth_deg = -70;    // direction from the target to the eye, from world +x
  double plane_side_m = 0.6;   // the plane: a square centred under the target
  bool organized = true;
  bool noisy = false;
  std::uint64_t seed = 1;      // noise and shuffle
};

// The eight views every contact case is checked from: elevation 45 and 30 deg,
// organized and unorganized, noise-free and with the Kinect noise model.
inline std::vector<ContactView> contact_views() {
  std::vector<ContactView> views;
  for (const double elevation : {45.0, 30.0}) {
    for (const bool organized : {true, false}) {
      for (const bool noisy : {false, true}) {
        ContactView view;
        view.elevation_deg = elevation, view.organized = organized, view.noisy = noisy;
        views.push_back(view);
      }
    }
  }
  return views;
}

inline std::string describe(const ContactView& view) {
  return "elevation " + std::to_string(int(std::lround(view.elevation_deg))) +
         (view.organized ? " organized" : " unorganized") + (view.noisy ? " kinect noise" : " noise-free");
}

struct ContactScene {
  PointCloud cloud;
  Labels truth;  // per point: 0 no return, kContactPlaneLabel, or the label of the solid seen
  Pose camera_from_world;
};

// The scene of a layout seen from a view: one ray per pixel (contact_scenes.cpp,
// compiled at the build type's optimization, not the test files' -O1: it casts
// 307 200 rays a scene, which the sanitizer builds slowed most at -O1).
ContactScene contact_scene(const ContactLayout& layout, const ContactView& view);

inline ContactScene contact_scene(const ContactObject& object, const ContactView& view) {
  return contact_scene(contact_layout(object), view);
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
