#include "ray_cast.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace lccp::synthetic::detail {
namespace {

// Where a ray is inside a convex solid: entry and exit with their outward normals.
struct Span {
  double t_in = -kNoHit;
  double t_out = kNoHit;
  Eigen::Vector3d normal_in = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_out = Eigen::Vector3d::Zero();
};

// The span of the upright cylinder of `radius` about the z axis between z_lo and z_hi.
std::optional<Span> cylinder_span(const Ray& ray, double radius, double z_lo, double z_hi) {
  const Eigen::Vector3d& o = ray.origin;
  const Eigen::Vector3d& d = ray.direction;
  Span span;
  // Side: |o_xy + t d_xy| = radius.
  const double a = d.x() * d.x() + d.y() * d.y();
  const double b = o.x() * d.x() + o.y() * d.y();
  const double c = o.x() * o.x() + o.y() * o.y() - radius * radius;
  double side_in = -kNoHit, side_out = kNoHit;
  if (a > 0) {
    const double discriminant = b * b - a * c;
    if (discriminant <= 0) return std::nullopt;
    const double root = std::sqrt(discriminant);
    side_in = (-b - root) / a;
    side_out = (-b + root) / a;
  } else if (c > 0) {
    return std::nullopt;  // vertical ray outside the cylinder
  }
  // Caps: the slab z_lo <= z <= z_hi.
  double cap_in = -kNoHit, cap_out = kNoHit, cap_in_normal = 0, cap_out_normal = 0;
  if (d.z() != 0) {
    const double t_lo = (z_lo - o.z()) / d.z();
    const double t_hi = (z_hi - o.z()) / d.z();
    if (d.z() > 0) {
      cap_in = t_lo, cap_in_normal = -1, cap_out = t_hi, cap_out_normal = 1;
    } else {
      cap_in = t_hi, cap_in_normal = 1, cap_out = t_lo, cap_out_normal = -1;
    }
  } else if (o.z() < z_lo || o.z() > z_hi) {
    return std::nullopt;
  }
  const auto radial = [&](double t) {
    const Eigen::Vector3d p = o + t * d;
    return Eigen::Vector3d(p.x() / radius, p.y() / radius, 0);
  };
  if (side_in > cap_in) {
    span.t_in = side_in;
    span.normal_in = radial(side_in);
  } else {
    span.t_in = cap_in;
    span.normal_in = Eigen::Vector3d(0, 0, cap_in_normal);
  }
  if (side_out < cap_out) {
    span.t_out = side_out;
    span.normal_out = radial(side_out);
  } else {
    span.t_out = cap_out;
    span.normal_out = Eigen::Vector3d(0, 0, cap_out_normal);
  }
  if (!(span.t_in < span.t_out)) return std::nullopt;
  return span;
}

// First hit (along a unit direction u) of the capsule of `radius` around the
// segment a-b: the side, else the sphere at the end the ray comes nearest.
// Inigo Quilez's capsule intersection.
double capsule_distance(const Eigen::Vector3d& o, const Eigen::Vector3d& u, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b, double radius) {
  const Eigen::Vector3d ba = b - a;
  const Eigen::Vector3d oa = o - a;
  const double baba = ba.dot(ba);
  const double bard = ba.dot(u);
  const double baoa = ba.dot(oa);
  const double rdoa = u.dot(oa);
  const double oaoa = oa.dot(oa);
  const double qa = baba - bard * bard;
  const double qb = baba * rdoa - baoa * bard;
  const double qc = baba * oaoa - baoa * baoa - radius * radius * baba;
  double h = qb * qb - qa * qc;
  if (h < 0) return kNoHit;  // misses the infinite cylinder, so the ends too
  double y = bard > 0 ? -1.0 : baba + 1.0;  // along the axis: the end it comes from first
  if (qa > 1e-12 * baba) {
    const double t = (-qb - std::sqrt(h)) / qa;
    y = baoa + t * bard;
    if (y > 0 && y < baba) return t;  // the side, between the ends
  }
  const Eigen::Vector3d oc = y <= 0 ? oa : Eigen::Vector3d(o - b);
  const double sb = u.dot(oc);
  const double sc = oc.dot(oc) - radius * radius;
  h = sb * sb - sc;
  if (h <= 0) return kNoHit;
  return -sb - std::sqrt(h);
}

}  // namespace

Hit intersect_box(const Ray& ray, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  // Slab test; a zero direction component gives infinite inverse, so a slab
  // the ray runs inside never limits it and one it runs outside rejects it.
  const Eigen::Vector3d inverse = ray.direction.cwiseInverse();
  double t_in = -kNoHit, t_out = kNoHit;
  int axis_in = 0;
  double sign_in = 0;
  for (int i = 0; i < 3; ++i) {
    const bool forward = inverse[i] >= 0;
    const double t0 = ((forward ? lo[i] : hi[i]) - ray.origin[i]) * inverse[i];
    const double t1 = ((forward ? hi[i] : lo[i]) - ray.origin[i]) * inverse[i];
    if (t0 > t_in) {
      t_in = t0;
      axis_in = i;
      sign_in = forward ? -1 : 1;  // the entry face's outward normal
    }
    t_out = std::min(t_out, t1);
  }
  if (!(t_in < t_out) || t_in <= 0) return {};
  Hit hit;
  hit.t = t_in;
  hit.normal[axis_in] = sign_in;
  return hit;
}

Hit intersect_cylinder(const Ray& ray, double radius, double height) {
  const std::optional<Span> span = cylinder_span(ray, radius, 0, height);
  if (!span || span->t_in <= 0) return {};
  return Hit{span->t_in, span->normal_in};
}

Hit intersect_cup(const Ray& ray, double outer_radius, double inner_radius, double height, double bottom) {
  // Outer solid minus cavity: the first point of the outer span outside the
  // cavity. The cavity reaches above the rim, so the top is open.
  const std::optional<Span> outer = cylinder_span(ray, outer_radius, 0, height);
  if (!outer || outer->t_in <= 0) return {};
  const std::optional<Span> cavity = cylinder_span(ray, inner_radius, bottom, height + 1.0);
  if (!cavity || outer->t_in < cavity->t_in || outer->t_in > cavity->t_out) return Hit{outer->t_in, outer->normal_in};
  if (cavity->t_out < outer->t_out) return Hit{cavity->t_out, -cavity->normal_out};  // inner wall or bottom
  return {};
}

Hit intersect_tube(const Ray& ray, std::span<const Eigen::Vector3d> centre_line, double radius) {
  const double length = ray.direction.norm();
  const Eigen::Vector3d u = ray.direction / length;
  double best = kNoHit;
  std::size_t best_segment = 0;
  for (std::size_t k = 0; k + 1 < centre_line.size(); ++k) {
    const double distance = capsule_distance(ray.origin, u, centre_line[k], centre_line[k + 1], radius);
    if (distance > 0 && distance < best) {
      best = distance;
      best_segment = k;
    }
  }
  if (best == kNoHit) return {};
  // Normal: from the nearest point of the segment's axis to the hit.
  const Eigen::Vector3d p = ray.origin + best * u;
  const Eigen::Vector3d& a = centre_line[best_segment];
  const Eigen::Vector3d ba = centre_line[best_segment + 1] - a;
  const double s = std::clamp((p - a).dot(ba) / ba.dot(ba), 0.0, 1.0);
  return Hit{best / length, (p - (a + s * ba)).normalized()};
}

}  // namespace lccp::synthetic::detail
