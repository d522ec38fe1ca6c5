#pragma once
// The two depth units OpenNI2 delivers and recordings hold (openni::PixelFormat,
// OniCTypes.h), and the conversion to the millimetres of DepthImage.
#include <cstdint>
#include <span>

namespace lccp::detail {

inline constexpr int kDepth1mm = 100;    // ONI_PIXEL_FORMAT_DEPTH_1_MM
inline constexpr int kDepth100um = 101;  // ONI_PIXEL_FORMAT_DEPTH_100_UM

// Pixels in `pixel_format` units to whole millimetres, rounded to nearest, in place.
inline void to_millimetres(std::span<std::uint16_t> depth, int pixel_format) {
  if (pixel_format != kDepth100um) return;
  for (std::uint16_t& d : depth) d = static_cast<std::uint16_t>((d + 5) / 10);
}

}  // namespace lccp::detail
