// The ray casting of contact_scenes.hpp: a scene of a layout seen from a view.
#include "contact_scenes.hpp"

namespace lccp::test {
namespace {

using synthetic::detail::Hit;
using synthetic::detail::Ray;

Hit hit_plane(const Ray& ray, const Eigen::Vector2d& centre, double half_side) {
  Hit hit;
  if (ray.direction.z() >= 0) return hit;
  const double t = -ray.origin.z() / ray.direction.z();
  const Eigen::Vector3d p = ray.origin + t * ray.direction;
  if ((p.head<2>() - centre).cwiseAbs().maxCoeff() <= half_side) hit.t = t, hit.normal = Eigen::Vector3d::UnitZ();
  return hit;
}

// The solid cap: the part of the sphere about (0, 0, height - radius) above z = 0.
Hit hit_cap(const Ray& ray, double radius, double height) {
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

// The first hit of a world ray with a solid: the ray in the solid's frame (a
// rotation keeps the ray parameter, the depth), the normal back in the world's.
Hit hit_solid(const Ray& world_ray, const ContactSolid& s) {
  namespace k = synthetic::detail;
  const Ray ray{s.rotation.transpose() * (world_ray.origin - s.position), s.rotation.transpose() * world_ray.direction};
  Hit hit;
  switch (s.shape) {
    case ContactSolid::Shape::box: hit = k::intersect_box(ray, s.lo, s.hi); break;
    case ContactSolid::Shape::cap: hit = hit_cap(ray, s.radius_m, s.height_m); break;
    case ContactSolid::Shape::cylinder: hit = k::intersect_cylinder(ray, s.radius_m, s.height_m); break;
    case ContactSolid::Shape::cup:
      hit = k::intersect_cup(ray, s.radius_m, s.inner_radius_m, s.height_m, s.bottom_m);
      break;
    case ContactSolid::Shape::tube: hit = k::intersect_tube(ray, s.centre_line, s.radius_m); break;
  }
  hit.normal = s.rotation * hit.normal;
  return hit;
}

// The nearest hit of a ray with the plane and the solids, and its label (0: none).
struct LabelledHit {
  Hit hit;
  std::uint32_t label = 0;
};

LabelledHit first_hit(const Ray& ray, const ContactLayout& layout, double plane_side_m) {
  LabelledHit first{hit_plane(ray, layout.target.head<2>(), plane_side_m / 2), kContactPlaneLabel};
  for (const ContactSolid& solid : layout.solids) {
    const Hit hit = hit_solid(ray, solid);
    if (hit.t < first.hit.t) first = {hit, solid.label};
  }
  if (!(first.hit.t < synthetic::detail::kNoHit)) first.label = 0;
  return first;
}

// The Kinect v1 measurement of true depth z on a surface hit at `cos2` =
// cos^2(incidence), with the pixel's random numbers as the synthetic scene draws
// them (synthetic::detail::pixel_noise): NaN for no return, else the quantized noisy depth.
double measure_depth(double z, double cos2, const synthetic::detail::PixelNoise& noise) {
  namespace k = synthetic::detail;
  const bool returns = cos2 >= k::kCosMaxIncidenceSquared && z >= k::kMinRangeM && z <= k::kMaxRangeM;
  if (!returns || noise.dropout) return kNaN;
  return k::quantize_depth_m(z + k::axial_noise_sigma_m(z) * noise.gaussian);
}

// The finite points of an organized scene, shuffled: an unorganized cloud.
ContactScene shuffled(const ContactScene& scene, std::uint64_t seed) {
  std::vector<std::size_t> finite;
  for (std::size_t i = 0; i < scene.truth.size(); ++i) {
    if (scene.truth[i] != 0) finite.push_back(i);
  }
  std::shuffle(finite.begin(), finite.end(), std::mt19937_64(seed));
  ContactScene out;
  out.camera_from_world = scene.camera_from_world;
  for (const std::size_t i : finite) {
    out.cloud.points.push_back(scene.cloud.points[i]);
    out.truth.push_back(scene.truth[i]);
  }
  out.cloud.width = static_cast<std::uint32_t>(finite.size());
  out.cloud.height = 1;
  return out;
}

}  // namespace

ContactScene contact_scene(const ContactLayout& layout, const ContactView& view) {
  const double el = deg2rad(view.elevation_deg), az = deg2rad(view.azimuth_deg);
  const Eigen::Vector3d toward_eye(std::cos(az) * std::cos(el), std::sin(az) * std::cos(el), std::sin(el));
  const Eigen::Vector3d eye = layout.target + view.distance_m * toward_eye;
  const Pose pose = look_at(eye, layout.target);
  const PinholeCamera cam;
  const synthetic::detail::NormalDeviates normal;
  const std::uint64_t key = synthetic::detail::frame_key(view.seed, 0);
  ContactScene scene;
  scene.camera_from_world = pose;
  scene.cloud.width = static_cast<std::uint32_t>(cam.width);
  scene.cloud.height = static_cast<std::uint32_t>(cam.height);
  scene.cloud.points.reserve(std::size_t(cam.width) * std::size_t(cam.height));
  scene.truth.reserve(scene.cloud.points.capacity());
  for (int row = 0; row < cam.height; ++row) {
    for (int col = 0; col < cam.width; ++col) {
      const Eigen::Vector3d d_cam((col - cam.cx) / cam.focal_px, (row - cam.cy) / cam.focal_px, 1.0);
      const Ray ray{eye, pose.R.transpose() * d_cam};  // t = depth along the optical axis
      const LabelledHit first = first_hit(ray, layout, view.plane_side_m);
      double z = first.hit.t;
      if (first.label != 0 && view.noisy) {
        const double c = ray.direction.normalized().dot(first.hit.normal);
        const std::uint64_t pixel = std::uint64_t(row) * std::uint64_t(cam.width) + std::uint64_t(col);
        z = measure_depth(z, c * c, synthetic::detail::pixel_noise(key, pixel, normal));
      }
      const bool seen = first.label != 0 && std::isfinite(z);
      scene.cloud.points.push_back(seen ? Eigen::Vector3f((z * d_cam).cast<float>()) : Eigen::Vector3f::Constant(kNaN));
      scene.truth.push_back(seen ? first.label : 0);
    }
  }
  return view.organized ? scene : shuffled(scene, view.seed);
}

}  // namespace lccp::test
