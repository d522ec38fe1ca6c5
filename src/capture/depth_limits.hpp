#pragma once
// The limits on a depth image that every way in checks: a live OpenNI2 frame
// (depth_stream.cpp) and a recording's stream (oni_check.cpp).
namespace lccp::detail {

// The largest depth image accepted, per side.
inline constexpr int kMaxDepthSide = 4096;

}  // namespace lccp::detail
