// The .oni record walk shared by the recording check and the recorder (oni_format.hpp).
#include "oni_format.hpp"

#include <optional>

namespace lccp::detail::oni {
namespace {

std::uint64_t read_le(std::span<const std::uint8_t> bytes, std::uint64_t at, int size) {
  std::uint64_t value = 0;
  for (int i = size - 1; i >= 0; --i) value = value << 8 | bytes[at + i];
  return value;
}

// The record header at `at` into `r`; returns why it does not parse, or nothing
// (then its fields and payload are set too).
std::optional<WalkStop> read_header(std::span<const std::uint8_t> bytes, std::uint64_t at, RecordHeader& r) {
  r.offset = at;
  if (at >= bytes.size()) return WalkStop::end_of_bytes;
  if (bytes.size() - at < kRecordHeaderBytes) return WalkStop::truncated_header;
  if (read_u32(bytes, at) != kRecordMagic) return WalkStop::no_magic;
  r.type = read_u32(bytes, at + kRecordTypeAt);
  r.node = read_u32(bytes, at + kRecordNodeAt);
  r.fields_size = read_u32(bytes, at + kRecordFieldsSizeAt);
  r.payload_size = read_u32(bytes, at + kRecordPayloadSizeAt);
  r.undo = read_u64(bytes, at + kRecordUndoAt);
  if (r.fields_size < kRecordHeaderBytes) return WalkStop::short_fields;
  if (std::uint64_t{r.fields_size} + r.payload_size > bytes.size() - at) return WalkStop::past_end;
  r.fields = bytes.subspan(at + kRecordHeaderBytes, r.fields_size - kRecordHeaderBytes);
  r.payload = bytes.subspan(at + r.fields_size, r.payload_size);
  return std::nullopt;
}

}  // namespace

std::uint32_t read_u32(std::span<const std::uint8_t> bytes, std::uint64_t at) {
  return static_cast<std::uint32_t>(read_le(bytes, at, 4));
}

std::uint64_t read_u64(std::span<const std::uint8_t> bytes, std::uint64_t at) { return read_le(bytes, at, 8); }

RecordWalk walk_records(std::span<const std::uint8_t> bytes) {
  RecordWalk walk;
  for (std::uint64_t at = kFileHeaderBytes;;) {
    RecordHeader r;
    if (const auto stop = read_header(bytes, at, r)) {
      walk.stop = *stop;
      walk.failed = r;
      return walk;
    }
    walk.records.push_back(r);
    if (r.type == kEnd) {
      walk.stop = WalkStop::end_record;
      return walk;
    }
    at = r.end();
  }
}

}  // namespace lccp::detail::oni
