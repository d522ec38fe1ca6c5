#include "oni_16zt.hpp"

namespace lccp::detail {
namespace {

std::string str(std::uint64_t value) { return std::to_string(value); }

// The 16zT stream after its table (XnStreamUncompressDepth16ZWithEmbTable): each
// output pixel is table[index]; bytes below 0xE0 carry two 4-bit steps (index -=
// nibble - 6; a low nibble 0xD ends the byte, 0xF means a long step follows); 0xFF
// means a long step follows; 0xE0 + n repeats the last pixel 2n times. A long step
// is one byte b >= 0x80 (index -= b - 192) or two bytes (index = b << 8 | next).
class Decoder16zT {
 public:
  Decoder16zT(std::span<const std::uint8_t> in, std::span<std::uint16_t> out) : in_(in), out_(out) {}

  std::optional<std::string> run() {
    if (in_.size() < 2) return "16zT data shorter than its table size";
    const std::size_t table_size = std::size_t(in_[0]) | std::size_t(in_[1]) << 8;
    if (in_.size() < 2 + 2 * table_size + 2) return "16zT table of " + str(table_size) + " entries runs past the data";
    table_ = in_.subspan(2, 2 * table_size);
    at_ = 2 + 2 * table_size;
    index_ = read16();
    if (!emit(1)) return problem_;
    while (at_ < in_.size()) {
      if (!step()) return problem_;
    }
    if (written_ != out_.size()) return "16zT data decodes to " + str(written_) + " of " + str(out_.size()) + " pixels";
    return std::nullopt;
  }

 private:
  std::uint16_t read16() {
    const std::uint16_t value = static_cast<std::uint16_t>(in_[at_] | in_[at_ + 1] << 8);
    at_ += 2;
    return value;
  }
  bool fail(std::string text) {
    problem_ = std::move(text);
    return false;
  }
  // The failures, out of line: emit runs once or twice per pixel.
  [[gnu::noinline]] bool index_past_table() { return fail("16zT index " + str(index_) + " past its table"); }
  [[gnu::noinline]] bool too_many_pixels() { return fail("16zT data decodes to more than " + str(out_.size()) + " pixels"); }
  bool emit(std::size_t count) {
    if (2 * std::size_t{index_} >= table_.size()) [[unlikely]] return index_past_table();
    if (count > out_.size() - written_) [[unlikely]] return too_many_pixels();
    const auto value = static_cast<std::uint16_t>(table_[2 * index_] | table_[2 * index_ + 1] << 8);
    std::uint16_t* out = out_.data() + written_;
    written_ += count;
    for (std::size_t i = 0; i < count; ++i) out[i] = value;
    return true;
  }
  void add(int delta) { index_ = static_cast<std::uint16_t>(index_ - delta); }  // u16 arithmetic, as the player's

  bool long_step() {
    if (at_ >= in_.size()) return fail("16zT data ends inside a step");
    const std::uint8_t b = in_[at_++];
    if (b & 0x80) {
      add(int(b) - 192);
    } else {
      if (at_ >= in_.size()) return fail("16zT data ends inside a step");
      index_ = static_cast<std::uint16_t>(b << 8 | in_[at_++]);
    }
    return emit(1);
  }

  bool step() {
    const std::uint8_t c = in_[at_++];
    if (c == 0xFF) return long_step();
    if (c >= 0xE0) return emit(2 * std::size_t(c - 0xE0));
    add(int(c >> 4) - 6);
    if (!emit(1)) return false;
    const int low = c & 0x0F;
    if (low == 0x0F) return long_step();
    if (low == 0x0D) return true;
    add(low - 6);
    return emit(1);
  }

  std::span<const std::uint8_t> in_;
  std::span<std::uint16_t> out_;
  std::span<const std::uint8_t> table_;
  std::size_t at_ = 0;
  std::size_t written_ = 0;
  std::uint16_t index_ = 0;
  std::string problem_;
};

}  // namespace

bool is_16zt(std::uint32_t codec) { return codec == kCodec16zT; }

std::optional<std::string> decode_16zt(std::span<const std::uint8_t> in, std::span<std::uint16_t> out) {
  return Decoder16zT(in, out).run();
}

}  // namespace lccp::detail
