#pragma once
// LZF compression and decompression for PCD `binary_compressed` data
// (internal to src/io).
#include <cstdint>
#include <span>
#include <vector>

namespace lccp::io_detail {

// The most bytes one compressed byte can stand for: a 3-byte back reference
// copies at most 7 + 255 + 2 = 264 bytes (the LZF format as described in
// PCL's io/src/lzf.cpp), so raw size <= 88 x compressed size.
inline constexpr std::uint64_t kLzfMaxRatio = 88;

// Decompresses `in` into exactly `out.size()` bytes. Returns nullptr on
// success, otherwise a short description of what is wrong with the stream.
// Every read and write is bounds-checked; nothing outside `out` is touched.
const char* lzf_decompress(std::span<const std::uint8_t> in, std::span<std::uint8_t> out);

// An LZF stream that lzf_decompress (and liblzf's lzf_decompress, which PCL's
// PCDReader uses) expands back to `in`. Never fails: data without repeats
// grows by one byte per 32 (in.size() + ceil(in.size() / 32) at most).
std::vector<std::uint8_t> lzf_compress(std::span<const std::uint8_t> in);

}  // namespace lccp::io_detail
