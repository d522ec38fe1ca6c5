#pragma once
// The .oni record layout, read in one place: by the structural check a replay makes
// when it opens a recording (oni_check.cpp, whose frame positions our reader then
// uses) and by `lccp record`, which counts the frames openni::Recorder has written
// and cuts a finished file (recorder.cpp).
//
// From OpenNI2's public source (Source/Drivers/OniFile/DataRecords.h, PlayerNode.cpp;
// Source/Core/OniRecorder.cpp, OniDataRecords.cpp):
//   file header (24 bytes): "NI10", version {u8 major, u8 minor, u16 maintenance,
//     u32 build}, u64 global max timestamp, u32 max node id;
//   then records, each a 28-byte header: u32 magic "NIR\0", u32 type, u32 node id,
//     u32 fields size (header included), u32 payload size, u64 undo record position;
//     then the record's fields, then its payload; the last record is End (0x0B).
// All integers little-endian.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace lccp::detail::oni {

inline constexpr std::size_t kFileHeaderBytes = 24;    // RecordingHeader (DataRecords.h)
inline constexpr std::size_t kRecordHeaderBytes = 28;  // Record::Header, 64-bit undo position (format 1.0.1.0)
inline constexpr std::uint32_t kRecordMagic = 0x0052494E;  // "NIR\0" (Record::MAGIC)
inline constexpr std::size_t kSeekEntryBytes = 20;     // DataIndexEntry: u64 timestamp, u32 configuration, u64 position
// The record header's fields after the magic, at these offsets from its start.
inline constexpr std::size_t kRecordTypeAt = 4;
inline constexpr std::size_t kRecordNodeAt = 8;
inline constexpr std::size_t kRecordFieldsSizeAt = 12;
inline constexpr std::size_t kRecordPayloadSizeAt = 16;
inline constexpr std::size_t kRecordUndoAt = 20;

enum RecordType : std::uint32_t {  // DataRecords.h
  kNodeAddedV1004 = 0x02,
  kIntProperty = 0x03,
  kRealProperty = 0x04,
  kStringProperty = 0x05,
  kGeneralProperty = 0x06,
  kNodeRemoved = 0x07,
  kNodeDataBegin = 0x08,
  kNodeStateReady = 0x09,
  kNewData = 0x0A,
  kEnd = 0x0B,
  kNodeAddedV1005 = 0x0C,
  kNodeAdded = 0x0D,
  kSeekTable = 0x0E,
};

// NodeAdded fields (NodeAddedRecord, DataRecords.cpp): the node name (u32 size, NUL
// included, then the bytes), then these, at offsets from the end of the name.
inline constexpr std::size_t kNodeAddedNodeTypeAt = 0;        // u32 node type
inline constexpr std::size_t kNodeAddedCodecAt = 4;           // u32 codec id
inline constexpr std::size_t kNodeAddedFramesAt = 8;          // u32 number of frames
inline constexpr std::size_t kNodeAddedMinTimestampAt = 12;   // u64
inline constexpr std::size_t kNodeAddedMaxTimestampAt = 20;   // u64
inline constexpr std::size_t kNodeAddedSeekTableAt = 28;      // u64 position of the SeekTable record
inline constexpr std::size_t kNodeAddedBytesAfterName = 36;

// Little-endian reads; the caller keeps `at` + 4 (or 8) inside `bytes`.
std::uint32_t read_u32(std::span<const std::uint8_t> bytes, std::uint64_t at);
std::uint64_t read_u64(std::span<const std::uint8_t> bytes, std::uint64_t at);

struct RecordHeader {
  std::uint64_t offset = 0;
  std::uint32_t type = 0;
  std::uint32_t node = 0;
  std::uint32_t fields_size = 0;  // header included
  std::uint32_t payload_size = 0;
  std::uint64_t undo = 0;
  std::span<const std::uint8_t> fields;   // after the 28-byte header (set for a record that parsed)
  std::span<const std::uint8_t> payload;

  std::uint64_t fields_end() const { return offset + fields_size; }  // offset of the payload
  std::uint64_t end() const { return fields_end() + payload_size; }  // offset of the next record
};

// Why a walk over the records stopped.
enum class WalkStop {
  end_record,        // at the End record (the last one in `records`)
  end_of_bytes,      // no bytes left where a record should start
  truncated_header,  // fewer than 28 bytes left for a record header
  no_magic,          // a record header without "NIR\0"
  short_fields,      // a fields size below the 28-byte header
  past_end,          // a record running past the end of the bytes
};

struct RecordWalk {
  std::vector<RecordHeader> records;  // those that parsed, in file order, End included
  WalkStop stop = WalkStop::end_of_bytes;
  // The record that did not parse (not for end_record): its offset, and its header
  // fields when its magic was read (no_magic and later), but no fields or payload.
  RecordHeader failed;
};

// The record headers of an .oni file in `bytes`, from the first record (after the
// file header, which is not checked here) up to End, or up to the first one that does
// not parse or is cut short (a recording still being written ends in a partial one).
// Reads only inside `bytes`.
RecordWalk walk_records(std::span<const std::uint8_t> bytes);

}  // namespace lccp::detail::oni
