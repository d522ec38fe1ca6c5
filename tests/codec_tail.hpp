#pragma once
// Comparing replayed depth with the depth that was recorded, for tests.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace lccp::test {

// Pixels of a replayed frame that differ from the depth that was recorded, except
// those OpenNI2's 16zT codec is known to change. Its encoder
// (XnStreamCompressDepth16ZWithEmbTable, OpenNI2 Source/Core/XnStreamCompression.cpp)
// ends a frame by writing a pending single step before a pending run of unchanged
// pixel pairs (at most 14 pairs), so the decoder gives that run the last pixel's value:
// up to 28 pixels before the last one may come back equal to the last pixel.
inline std::size_t differing_pixels_but_codec_tail(const std::vector<std::uint16_t>& replayed,
                                            const std::vector<std::uint16_t>& recorded) {
  constexpr std::size_t kCodecTail = 2 * 14 + 1;
  if (replayed.size() != recorded.size() || replayed.empty()) return std::max(replayed.size(), recorded.size());
  std::size_t count = 0;
  for (std::size_t i = 0; i < replayed.size(); ++i) {
    const bool codec_tail = i + kCodecTail >= replayed.size() && i + 1 < replayed.size() &&
                            replayed[i] == replayed.back();
    count += replayed[i] != recorded[i] && !codec_tail;
  }
  return count;
}

}  // namespace lccp::test
