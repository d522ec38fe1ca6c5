#pragma once
// How a Kinect v1 turns the true depth of a surface into a measurement: axial
// noise, disparity quantization and the reasons for a missing return. The
// random numbers are counter-based: a pure function of (seed, frame, pixel).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace lccp::synthetic::detail {

inline constexpr double kMinRangeM = 0.4;
inline constexpr double kMaxRangeM = 4.0;
// A surface seen at more than 80 deg from its normal returns nothing:
// (ray . normal)^2 < cos^2(80 deg) |ray|^2.
inline constexpr double kCosMaxIncidenceSquared = 0.030153689607045803;  // cos(80 deg)^2
inline constexpr double kDropoutProbability = 0.005;
// The IR projector sits this far along the optical +x axis from the IR camera;
// surfaces it cannot see return nothing (its shadow, left of near objects).
inline constexpr double kProjectorOffsetM = 0.075;

// Disparity as the Kinect measures it: f b / z in steps of 1/8 pixel.
inline constexpr double kDisparityFocalPx = 580.0;
inline constexpr double kDisparityBaselineM = 0.075;
inline constexpr double kDisparityStepPx = 1.0 / 8.0;
// Disparity in steps times depth (metres): steps = this / z.
inline constexpr double kDisparityStepsTimesDepth = kDisparityFocalPx * kDisparityBaselineM / kDisparityStepPx;

// Standard deviation of the axial noise at depth z for surfaces facing the
// sensor (Nguyen, Izadi, Lovell 2012, "Modeling Kinect sensor noise").
inline double axial_noise_sigma_m(double z_m) { return 0.0012 + 0.0019 * (z_m - 0.4) * (z_m - 0.4); }

// Rounds a positive number to the nearest integer (ties up), without a libm call.
inline double round_positive(double x) { return static_cast<double>(static_cast<std::int64_t>(x + 0.5)); }

// Depth after quantizing 1/z to whole disparity steps.
inline double quantize_depth_m(double z_m) {
  return kDisparityStepsTimesDepth / round_positive(kDisparityStepsTimesDepth / z_m);
}

// The depth difference between neighbouring disparity steps at depth z.
inline double quantization_step_m(double z_m) { return z_m * z_m / kDisparityStepsTimesDepth; }

// Steele et al.'s SplitMix64: a bijective 64-bit mix, the output of step x of its generator.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// The per-frame key every pixel's random numbers derive from.
inline std::uint64_t frame_key(std::uint64_t noise_seed, std::uint64_t frame_index) {
  return splitmix64(splitmix64(noise_seed) ^ splitmix64(frame_index));
}

// The standard normal quantile: Acklam's rational approximation (relative
// error below 1.2e-9), whose central branch (95 % of draws) has no logarithm.
inline double standard_normal_quantile(double p) {
  constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                          1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                          6.680131188771972e+01, -1.328068155288572e+01};
  constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                          -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                          3.754408661907416e+00};
  constexpr double kLow = 0.02425;
  if (p >= kLow && p <= 1 - kLow) {
    const double q = p - 0.5;
    const double r = q * q;
    return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
           (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  }
  const double q = std::sqrt(-2 * std::log(p < kLow ? p : 1 - p));
  const double tail = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
                      ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  return p < kLow ? tail : -tail;
}

// Standard normal deviates from 52 uniform bits by the inverse CDF, tabulated:
// linear interpolation between the quantiles at k / 2048 (error below 0.03
// sigma, in the second and second-to-last bins; far less elsewhere); the two
// outer bins (0.1 % of draws) evaluate the quantile itself, so the tails reach
// 8.2 sigma. Costs a multiply-add where the rational approximation costs a
// division and a mispredicted branch (5 % of draws take the logarithm).
class NormalDeviates {
 public:
  NormalDeviates() {
    for (std::size_t k = 1; k < kBins; ++k) quantiles_[k] = standard_normal_quantile(static_cast<double>(k) / kBins);
  }

  double operator()(std::uint64_t bits52) const {
    const std::uint64_t bin = bits52 >> (52 - kBinBits);
    if (bin == 0 || bin == kBins - 1) return standard_normal_quantile((static_cast<double>(bits52) + 0.5) * 0x1p-52);
    const double within = static_cast<double>(bits52 & ((std::uint64_t{1} << (52 - kBinBits)) - 1)) * 0x1p-41;
    return quantiles_[bin] + within * (quantiles_[bin + 1] - quantiles_[bin]);
  }

 private:
  static constexpr std::uint64_t kBinBits = 11;
  static constexpr std::uint64_t kBins = std::uint64_t{1} << kBinBits;
  static_assert(52 - kBinBits == 41);
  std::array<double, kBins + 1> quantiles_{};
};

struct PixelNoise {
  double gaussian = 0;   // standard normal
  bool dropout = false;  // with kDropoutProbability
};

// One pixel's random numbers from the pixel-th step of a SplitMix64 stream
// started at the frame key: the low 12 bits decide the dropout (20 / 4096 =
// 0.49 %), the 52 above them the normal deviate.
inline PixelNoise pixel_noise(std::uint64_t frame_key, std::uint64_t pixel, const NormalDeviates& normal) {
  constexpr std::uint64_t kDropoutBits = 12;
  constexpr auto kDropoutBelow = static_cast<std::uint64_t>(kDropoutProbability * (1u << kDropoutBits) + 0.5);
  const std::uint64_t bits = splitmix64(frame_key + pixel * 0x9E3779B97F4A7C15ull);
  PixelNoise noise;
  noise.dropout = (bits & ((1u << kDropoutBits) - 1)) < kDropoutBelow;
  noise.gaussian = normal(bits >> kDropoutBits);
  return noise;
}

}  // namespace lccp::synthetic::detail
