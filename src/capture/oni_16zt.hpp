#pragma once
// The 16zT depth codec of OpenNI's .oni recordings (XnStreamCompression.cpp,
// XnStreamUncompressDepth16ZWithEmbTable, and XnCodecIDs.h in OpenNI2's public
// source, Source/Drivers/OniFile/): decoding with every index and length bounded.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace lccp::detail {

constexpr std::uint32_t codec_id(char c1, char c2, char c3, char c4) {  // XN_CODEC_ID, XnCodecIDs.h
  return std::uint32_t(std::uint8_t(c4)) << 24 | std::uint32_t(std::uint8_t(c3)) << 16 |
         std::uint32_t(std::uint8_t(c2)) << 8 | std::uint8_t(c1);
}
inline constexpr std::uint32_t kCodec16zT = codec_id('1', '6', 'z', 'T');
inline constexpr std::uint32_t kCodecNone = codec_id('N', 'O', 'N', 'E');

// Whether `codec` (a stream's XnCodecID) is 16zT; otherwise frames are uncompressed.
bool is_16zt(std::uint32_t codec);

// Decodes one 16zT frame into exactly `out.size()` pixels. Returns nullopt on
// success, or what is wrong: a read past the input, a table index past the
// table, too many or too few pixels.
std::optional<std::string> decode_16zt(std::span<const std::uint8_t> in, std::span<std::uint16_t> out);

}  // namespace lccp::detail
