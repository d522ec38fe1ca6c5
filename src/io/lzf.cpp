// LZF decompression. The stream is a sequence of runs (format described in
// PCL's io/src/lzf.cpp, from Marc Lehmann's liblzf):
//   000LLLLL <L+1 bytes>          literal run of L+1 = 1..32 bytes
//   LLLooooo oooooooo             back reference of L+2 = 3..8 bytes
//   111ooooo LLLLLLLL oooooooo    back reference of L+9 = 9..264 bytes
// with o+1 = 1..8192 the distance back from the current output position.
#include "lzf.hpp"

#include <cstddef>
#include <cstring>

namespace lccp::io_detail {

const char* lzf_decompress(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) {
  std::size_t ip = 0;
  std::size_t op = 0;
  while (ip < in.size()) {
    const std::size_t control = in[ip++];
    if (control < 32) {
      const std::size_t length = control + 1;
      if (length > in.size() - ip) return "literal run past the end of the compressed data";
      if (length > out.size() - op) return "literal run past the declared raw size";
      std::memcpy(out.data() + op, in.data() + ip, length);
      ip += length;
      op += length;
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7) {
      if (ip >= in.size()) return "back reference cut off";
      length += in[ip++];
    }
    if (ip >= in.size()) return "back reference cut off";
    const std::size_t distance = ((control & 0x1f) << 8) + in[ip++] + 1;
    length += 2;
    if (distance > op) return "back reference before the start of the data";
    if (length > out.size() - op) return "back reference past the declared raw size";
    if (distance >= length) {  // disjoint: one copy
      std::memcpy(out.data() + op, out.data() + op - distance, length);
      op += length;
    } else {  // overlapping, a repeating pattern: byte by byte, in order
      for (std::size_t k = 0; k < length; ++k, ++op) out[op] = out[op - distance];
    }
  }
  return op == out.size() ? nullptr : "stream ends before the declared raw size";
}

}  // namespace lccp::io_detail
