// LZF compression and decompression. The stream is a sequence of runs (format
// described in PCL's io/src/lzf.cpp, from Marc Lehmann's liblzf):
//   000LLLLL <L+1 bytes>          literal run of L+1 = 1..32 bytes
//   LLLooooo oooooooo             back reference of L+2 = 3..8 bytes
//   111ooooo LLLLLLLL oooooooo    back reference of L+9 = 9..264 bytes
// with o+1 = 1..8192 the distance back from the current output position.
#include "lzf.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>

namespace lccp::io_detail {
namespace {

constexpr std::size_t kMaxLiteralRun = 32;
constexpr std::size_t kMinMatch = 3;
constexpr std::size_t kMaxMatch = 264;      // 7 + 255 + 2
constexpr std::size_t kMaxDistance = 8192;  // o + 1, o in 13 bits
constexpr int kHashBits = 16;
constexpr std::size_t kNoPosition = static_cast<std::size_t>(-1);

// Bucket of the 3 bytes at p (Fibonacci hashing of their 24-bit value).
std::size_t hash3(const std::uint8_t* p) {
  const std::uint32_t v = std::uint32_t{p[0]} << 16 | std::uint32_t{p[1]} << 8 | p[2];
  return (v * 2654435769u) >> (32 - kHashBits);
}

// in[from, to) as literal runs of at most 32 bytes.
void put_literals(std::span<const std::uint8_t> in, std::size_t from, std::size_t to, std::vector<std::uint8_t>& out) {
  while (from < to) {
    const std::size_t n = std::min(kMaxLiteralRun, to - from);
    out.push_back(static_cast<std::uint8_t>(n - 1));
    const auto* first = in.data() + from;
    out.insert(out.end(), first, first + n);
    from += n;
  }
}

// A back reference of `length` (3..264) bytes starting `distance` (1..8192) back.
void put_reference(std::size_t length, std::size_t distance, std::vector<std::uint8_t>& out) {
  const std::size_t l = length - 2, o = distance - 1;
  out.push_back(static_cast<std::uint8_t>(std::min<std::size_t>(l, 7) << 5 | o >> 8));
  if (l >= 7) out.push_back(static_cast<std::uint8_t>(l - 7));
  out.push_back(static_cast<std::uint8_t>(o & 0xff));
}

// How many bytes from `pos` repeat those from `ref` (< pos), up to 264. The
// two may overlap: the decoder copies byte by byte, so a run repeats.
std::size_t match_length(std::span<const std::uint8_t> in, std::size_t ref, std::size_t pos) {
  const std::size_t limit = std::min(kMaxMatch, in.size() - pos);
  std::size_t n = 0;
  while (n < limit && in[ref + n] == in[pos + n]) ++n;
  return n;
}

}  // namespace

// Greedy, like liblzf's lzf_compress: at each position the last earlier
// position with the same 3-byte hash is tried; a match of >= 3 bytes within
// 8192 back is taken whole, and the positions it covers are hashed too.
std::vector<std::uint8_t> lzf_compress(std::span<const std::uint8_t> in) {
  std::vector<std::uint8_t> out;
  out.reserve(in.size() + in.size() / kMaxLiteralRun + 1);
  std::vector<std::size_t> last(std::size_t{1} << kHashBits, kNoPosition);
  std::size_t literals = 0;  // first byte not yet written
  std::size_t pos = 0;
  while (pos + kMinMatch <= in.size()) {
    const std::size_t bucket = hash3(&in[pos]);
    const std::size_t ref = last[bucket];
    last[bucket] = pos;
    const std::size_t length = ref != kNoPosition && pos - ref <= kMaxDistance ? match_length(in, ref, pos) : 0;
    if (length < kMinMatch) {
      ++pos;
      continue;
    }
    put_literals(in, literals, pos, out);
    put_reference(length, pos - ref, out);
    for (std::size_t k = pos + 1; k < pos + length && k + kMinMatch <= in.size(); ++k) last[hash3(&in[k])] = k;
    pos += length;
    literals = pos;
  }
  put_literals(in, literals, in.size(), out);
  return out;
}

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
