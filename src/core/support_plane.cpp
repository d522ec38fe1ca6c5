// Stage 0: the support plane by RANSAC (Fischler and Bolles, "Random sample
// consensus: a paradigm for model fitting with applications to image analysis and
// automated cartography", Comm. ACM 24(6):381-395, 1981): planes through random
// triples of points, the one with the most points within distance_m wins, then a
// least-squares refit over its inliers.
//
// Deterministic for any thread count: hypothesis i draws its triple from a
// counter-based generator keyed by (seed, i); hypotheses are scored on a fixed
// subsample of the finite points, evenly strided over the cloud, and compared
// serially (most inliers, then smallest i); sums over points run in fixed blocks
// of kBlock points that are added in block order.
//
// Cost: the scoring touches kScoreSamples points per hypothesis, the cloud is
// read twice (the least-squares round and the marking), so a VGA frame takes
// about a millisecond.
#include "lccp/core/support_plane.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "parallel.hpp"
#include "plane_fit.hpp"
#include "robust_sigma.hpp"

namespace lccp {
namespace {

using detail::Moments;

constexpr std::size_t kBlock = 4096;         // points per block of every sum over points
constexpr std::size_t kScoreSamples = 4096;  // finite points that score the hypotheses
constexpr std::uint32_t kDrawsPerHypothesis = 16;  // triples tried before a hypothesis gives up

// What makes a plane acceptable: the inlier band, the smallest triangle height of a
// sample, and the up direction (zero: any) with the cosine of the largest tilt.
struct Criteria {
  float distance = 0;
  float min_height = 0;
  Eigen::Vector3f up = Eigen::Vector3f::Zero();
  float min_cos = 0;

  bool within_tilt(const Eigen::Vector3f& normal) const {
    return up.isZero() || std::abs(normal.dot(up)) >= min_cos;
  }
};

Criteria criteria_of(const SupportPlaneConfig& config) {
  Criteria c;
  c.distance = config.distance_m;
  c.min_height = 2.0f * config.distance_m;
  const Eigen::Vector3f up(config.up_x, config.up_y, config.up_z);
  if (!up.isZero()) c.up = up.normalized();
  c.min_cos = static_cast<float>(std::cos(config.max_tilt_deg * std::numbers::pi / 180.0));
  return c;
}

// The scoring subsample, structure of arrays so that the scoring loop vectorizes.
struct Samples {
  std::vector<float> x, y, z;
  std::size_t size() const { return x.size(); }
  Eigen::Vector3f operator[](std::size_t j) const { return {x[j], y[j], z[j]}; }
};

// is_finite(p), cheaper: x * 0 is NaN exactly when x is NaN or infinite.
bool finite_point(const Eigen::Vector3f& p) { return p.x() * 0.0f + p.y() * 0.0f + p.z() * 0.0f == 0.0f; }

// How far from the plane a point at depth z may lie and be on it: distance_m,
// or (noise_sigmas > 0) k s z^2 between half a depth step, q z^2 / 2, and
// distance_m (SupportPlaneConfig::noise_sigmas). z below the sensor's nearest
// range counts as that range.
struct Band {
  float max_m = 0;
  float sigmas_per_m2 = 0;     // k s; 0: the band is max_m everywhere
  float half_step_per_m2 = 0;  // q / 2
  float min_z = 0;

  bool fixed() const { return sigmas_per_m2 == 0.0f; }
  float at(float z) const {
    const float z2 = std::max(z, min_z) * std::max(z, min_z);
    return std::min(max_m, std::max(half_step_per_m2, sigmas_per_m2) * z2);
  }
};

// The points that take part: finite and not skipped.
struct Candidates {
  const CloudView& cloud;
  const std::vector<std::uint8_t>& skip;

  bool kept(std::size_t i) const { return skip.empty() || !skip[i]; }
  bool counts(std::size_t i) const { return finite_point(cloud.points[i]) && kept(i); }
  // Whether point i takes part and lies within distance of the plane (a NaN or infinite point does not).
  bool on(const Plane& plane, float distance, std::size_t i) const {
    return std::abs(plane.distance(cloud.points[i])) <= distance && kept(i);
  }
  bool on(const Plane& plane, const Band& band, std::size_t i) const {
    const Eigen::Vector3f& p = cloud.points[i];
    return std::abs(plane.distance(p)) <= (band.fixed() ? band.max_m : band.at(p.z())) && kept(i);
  }
};

std::size_t block_count(std::size_t n) { return (n + kBlock - 1) / kBlock; }

// Calls body(b, begin, end) for every fixed block b = [begin, end) of [0, n), in parallel.
template <typename Body>
void for_each_block(std::size_t n, Body&& body) {
  detail::parallel_for_each_index(block_count(n),
                                  [&](std::size_t b) { body(b, b * kBlock, std::min(n, (b + 1) * kBlock)); });
}

// The scoring samples: the cloud's index range cut into kScoreSamples equal
// intervals (fewer for a small cloud), the first point of each that takes part,
// in order; an interval without one gives none. No pass over the whole cloud is
// needed, at the price of fewer samples when most of it is NaN or skipped (10%
// left: about 400).
Samples score_samples(const Candidates& candidates) {
  const CloudView& cloud = candidates.cloud;
  const std::size_t n = std::min(cloud.size(), kScoreSamples);
  std::vector<std::size_t> chosen(n, cloud.size());
  detail::parallel_for_each_index(n, [&](std::size_t k) {
    const std::size_t end = (k + 1) * cloud.size() / n;
    for (std::size_t i = k * cloud.size() / n; i < end; ++i) {
      if (candidates.counts(i)) {
        chosen[k] = i;
        break;
      }
    }
  });
  Samples s;
  for (const std::size_t i : chosen) {
    if (i == cloud.size()) continue;
    s.x.push_back(cloud.points[i].x()), s.y.push_back(cloud.points[i].y()), s.z.push_back(cloud.points[i].z());
  }
  return s;
}

// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014): the k-th output of the stream keyed by (seed, i).
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

std::uint64_t draw(std::uint32_t seed, std::uint32_t i, std::uint64_t k) {
  return splitmix64(splitmix64((std::uint64_t{seed} << 32) | i) + k * 0x9E3779B97F4A7C15ull);
}

// An index in [0, n) from the high 32 bits of a draw (Lemire's multiply-shift).
std::size_t index_below(std::uint64_t random, std::size_t n) { return ((random >> 32) * n) >> 32; }

// The plane through a, b and c; empty when the triangle's height over its longest
// side is below min_height: collinear points, or two of them too close together
// (a side shorter than min_height bounds that height too).
std::optional<Plane> plane_through(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                                   float min_height) {
  const Eigen::Vector3f cross = (b - a).cross(c - a);
  const float longest = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
  if (!(longest > 0.0f) || !(cross.squaredNorm() >= min_height * min_height * longest)) return std::nullopt;
  const Eigen::Vector3f normal = cross.normalized();
  return Plane{normal, -normal.dot(a)};
}

// Hypothesis i: the first of its triples that spans an acceptable plane.
std::optional<Plane> hypothesis(const Samples& s, const Criteria& c, std::uint32_t seed, std::uint32_t i) {
  for (std::uint32_t k = 0; k < kDrawsPerHypothesis; ++k) {
    const std::size_t a = index_below(draw(seed, i, 3 * k), s.size());
    const std::size_t b = index_below(draw(seed, i, 3 * k + 1), s.size());
    const std::size_t d = index_below(draw(seed, i, 3 * k + 2), s.size());
    const auto plane = plane_through(s[a], s[b], s[d], c.min_height);
    if (plane && c.within_tilt(plane->normal)) return plane;
  }
  return std::nullopt;
}

std::uint32_t score(const Plane& p, const Samples& s, float distance) {
  const float nx = p.normal.x(), ny = p.normal.y(), nz = p.normal.z(), d = p.d;
  std::uint32_t count = 0;
  for (std::size_t j = 0; j < s.size(); ++j) count += std::abs(nx * s.x[j] + ny * s.y[j] + nz * s.z[j] + d) <= distance;
  return count;
}

// All hypotheses scored in parallel, compared serially: most inliers, then smallest i.
std::optional<Plane> best_hypothesis(const Samples& s, const Criteria& c, const SupportPlaneConfig& config) {
  std::vector<std::optional<Plane>> planes(config.iterations);
  std::vector<std::uint32_t> scores(config.iterations, 0);
  detail::parallel_for_each_index(planes.size(), [&](std::size_t i) {
    planes[i] = hypothesis(s, c, config.seed, static_cast<std::uint32_t>(i));
    if (planes[i]) scores[i] = score(*planes[i], s, c.distance);
  });
  std::optional<Plane> best;
  std::uint32_t best_score = 0;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    if (planes[i] && scores[i] > best_score) best = planes[i], best_score = scores[i];
  }
  return best;
}

// Sums of the moments of points in double, one scalar per moment (a Moments
// vector built per point costs several times more).
struct MomentSums {
  double n = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;

  void add(const Eigen::Vector3f& p) {
    const double x = p.x(), y = p.y(), z = p.z();
    n += 1, sx += x, sy += y, sz += z;
    sxx += x * x, sxy += x * y, sxz += x * z, syy += y * y, syz += y * z, szz += z * z;
  }
  Moments moments() const {
    Moments m;
    m << n, sx, sy, sz, sxx, sxy, sxz, syy, syz, szz;
    return m;
  }
};

// Moments of the samples within distance of the plane.
Moments sample_moments(const Samples& s, const Plane& plane, float distance) {
  MomentSums sums;
  for (std::size_t j = 0; j < s.size(); ++j) {
    if (std::abs(plane.distance(s[j])) <= distance) sums.add(s[j]);
  }
  return sums.moments();
}

// Moments of all the points within distance of the plane that take part: per
// fixed block in parallel, added in block order.
Moments inlier_moments(const Candidates& candidates, const Plane& plane, float distance) {
  const CloudView& cloud = candidates.cloud;
  std::vector<Moments> blocks(block_count(cloud.size()), Moments::Zero());
  for_each_block(cloud.size(), [&](std::size_t b, std::size_t begin, std::size_t end) {
    MomentSums sums;
    for (std::size_t i = begin; i < end; ++i) {
      if (candidates.on(plane, distance, i)) sums.add(cloud.points[i]);
    }
    blocks[b] = sums.moments();
  });
  Moments sum = Moments::Zero();
  for (const Moments& m : blocks) sum += m;
  return sum;
}

// Least-squares plane of the points: through their mean, normal along the least
// eigenvector of their covariance; empty for fewer than 3 points or a degenerate set.
std::optional<Plane> fit_plane(const Moments& m) {
  const auto normal = m(0) >= 3.0 ? detail::least_eigenvector(detail::covariance_of(m)) : std::nullopt;
  if (!normal) return std::nullopt;
  const Eigen::Vector3d mean = m.segment<3>(1) / m(0);
  return Plane{normal->cast<float>(), static_cast<float>(-normal->dot(mean))};
}

// The least-squares plane of the inliers, or the previous plane if that fit is
// degenerate or leaves the tilt cone.
Plane refit(const Moments& inliers, const Plane& previous, const Criteria& c) {
  const auto fit = fit_plane(inliers);
  return fit && c.within_tilt(fit->normal) ? *fit : previous;
}

// Two least-squares rounds (fit, re-collect the inliers): the first over the
// scoring samples, cheap, corrects the tilt of the three-point hypothesis, so that
// the second collects the whole cloud's inliers around a nearly final plane.
Plane refined(const Candidates& candidates, const Samples& s, const Plane& hypothesis, const Criteria& c) {
  const Plane coarse = refit(sample_moments(s, hypothesis, c.distance), hypothesis, c);
  return refit(inlier_moments(candidates, coarse, c.distance), coarse, c);
}

// Normal toward the sensor at the origin (d > 0); a plane through it along up.
Plane oriented(const Plane& p, const Eigen::Vector3f& up) {
  if (p.d < 0.0f || (p.d == 0.0f && p.normal.dot(up) < 0.0f)) return Plane{-p.normal, -p.d};
  return p;
}

// The plane's noise from the scoring samples within distance_m of it: its
// robust sigma in metres, and the band (the sigma of |r| / z^2 times k).
struct Noise {
  float sigma_m = 0;
  Band band;
};

Noise plane_noise(const Samples& s, const Plane& plane, const SupportPlaneConfig& config, const SensorConfig& sensor) {
  std::vector<float> distances, per_m2;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const float r = std::abs(plane.distance(s[j]));
    if (r > config.distance_m) continue;
    const float z = std::max(s.z[j], sensor.min_range_m);
    distances.push_back(r), per_m2.push_back(r / (z * z));
  }
  Noise noise;
  noise.sigma_m = detail::robust_sigma(distances);
  noise.band = {config.distance_m, config.noise_sigmas * detail::robust_sigma(per_m2), 0.5f * sensor.step_per_m2(),
                sensor.min_range_m};
  if (config.noise_sigmas == 0.0f) noise.band.sigmas_per_m2 = 0.0f;
  return noise;
}

// The support's points, and the count of points that take part (for the inlier share).
struct Marking {
  SupportPlane support;
  std::uint64_t finite = 0;
};

Marking marked(const Candidates& candidates, const Plane& plane, const Band& band) {
  const std::size_t n = candidates.cloud.size();
  Marking m{SupportPlane{plane, std::vector<std::uint8_t>(n, 0), 0, 0.0f}, 0};
  std::vector<std::uint64_t> inliers(block_count(n), 0), finite(inliers.size(), 0);
  for_each_block(n, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::uint8_t* on_plane = m.support.on_plane.data();  // a raw pointer: the byte stores would reload it every point
    std::uint64_t on_count = 0, finite_count = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const bool on = candidates.on(plane, band, i);
      on_plane[i] = on;
      on_count += on;
      finite_count += candidates.counts(i);
    }
    inliers[b] = on_count, finite[b] = finite_count;
  });
  for (std::size_t b = 0; b < inliers.size(); ++b) m.support.inliers += inliers[b], m.finite += finite[b];
  return m;
}

}  // namespace

std::optional<SupportPlane> find_support_plane(const CloudView& cloud, const SupportPlaneConfig& config,
                                               const std::vector<std::uint8_t>& skip, const SensorConfig& sensor) {
  if (!(config.distance_m > 0.0f)) return std::nullopt;
  const Criteria criteria = criteria_of(config);
  const Candidates candidates{cloud, skip};
  const Samples samples = score_samples(candidates);
  if (samples.size() < 3) return std::nullopt;
  const auto best = best_hypothesis(samples, criteria, config);
  if (!best) return std::nullopt;
  const Plane plane = oriented(refined(candidates, samples, *best, criteria), criteria.up);
  const Noise noise = plane_noise(samples, plane, config, sensor);
  Marking m = marked(candidates, plane, noise.band);
  m.support.noise_m = noise.sigma_m;
  const double least = static_cast<double>(config.min_inlier_share) * static_cast<double>(m.finite);
  if (static_cast<double>(m.support.inliers) < least) return std::nullopt;
  return std::move(m.support);
}

}  // namespace lccp
