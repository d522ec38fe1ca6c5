#pragma once
// LZF decompression for PCD `binary_compressed` data (internal to src/io).
#include <cstdint>
#include <span>

namespace lccp::io_detail {

// The most bytes one compressed byte can stand for: a 3-byte back reference
// copies at most 7 + 255 + 2 = 264 bytes (the LZF format as described in
// PCL's io/src/lzf.cpp), so raw size <= 88 x compressed size.
inline constexpr std::uint64_t kLzfMaxRatio = 88;

// Decompresses `in` into exactly `out.size()` bytes. Returns nullptr on
// success, otherwise a short description of what is wrong with the stream.
// Every read and write is bounds-checked; nothing outside `out` is touched.
const char* lzf_decompress(std::span<const std::uint8_t> in, std::span<std::uint8_t> out);

}  // namespace lccp::io_detail
