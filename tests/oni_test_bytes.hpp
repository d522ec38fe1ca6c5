#pragma once
// Byte-level access to .oni recordings for tests that craft damaged ones: the
// records of a file and its header fields, by the layout in src/capture/oni_check.hpp
// (OpenNI2's Source/Drivers/OniFile/DataRecords.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace lccp::test {

inline const std::filesystem::path kRecordingsDir = std::filesystem::path(LCCP_CONFIG_DIR).parent_path() / "recordings";

inline constexpr std::size_t kOniFileHeaderBytes = 24;
inline constexpr std::size_t kOniRecordHeaderBytes = 28;

enum OniRecordType : std::uint32_t {
  kOniIntProperty = 0x03,
  kOniGeneralProperty = 0x06,
  kOniNodeRemoved = 0x07,
  kOniNodeDataBegin = 0x08,
  kOniNodeStateReady = 0x09,
  kOniNewData = 0x0A,
  kOniEnd = 0x0B,
  kOniNodeAdded = 0x0D,
  kOniSeekTable = 0x0E,
};

inline std::uint32_t get_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, sizeof value);  // little-endian host, as the file
  return value;
}
inline std::uint64_t get_u64(const std::string& bytes, std::size_t at) {
  std::uint64_t value = 0;
  std::memcpy(&value, bytes.data() + at, sizeof value);
  return value;
}
inline void put_u32(std::string& bytes, std::size_t at, std::uint32_t value) { std::memcpy(bytes.data() + at, &value, sizeof value); }
inline void put_u64(std::string& bytes, std::size_t at, std::uint64_t value) { std::memcpy(bytes.data() + at, &value, sizeof value); }

struct OniRecord {
  std::size_t offset = 0;
  std::uint32_t type = 0;
  std::uint32_t node = 0;
  std::uint32_t fields_size = 0;  // the 28-byte header included
  std::uint32_t payload_size = 0;
  std::string property;           // property records: the name
  std::size_t property_data = 0;  // property records: offset of the value
};

// The records of a well-formed recording, up to and including End.
inline std::vector<OniRecord> oni_records(const std::string& bytes) {
  std::vector<OniRecord> records;
  std::size_t at = kOniFileHeaderBytes;
  while (at + kOniRecordHeaderBytes <= bytes.size()) {
    OniRecord r;
    r.offset = at;
    r.type = get_u32(bytes, at + 4);
    r.node = get_u32(bytes, at + 8);
    r.fields_size = get_u32(bytes, at + 12);
    r.payload_size = get_u32(bytes, at + 16);
    if (r.type >= 0x03 && r.type <= 0x06) {
      const std::uint32_t name_size = get_u32(bytes, at + 28);
      r.property = std::string(bytes.data() + at + 32, name_size - 1);
      r.property_data = at + 32 + name_size + 4;
    }
    records.push_back(r);
    if (r.type == kOniEnd) break;
    at += std::size_t{r.fields_size} + r.payload_size;
  }
  return records;
}

// The record of a property by name; fails the test if there is none.
inline OniRecord oni_property(const std::string& bytes, const std::string& name) {
  for (const OniRecord& r : oni_records(bytes)) {
    if (r.property == name) return r;
  }
  ADD_FAILURE() << "no property " << name;
  return {};
}

// The records of one type, in file order.
inline std::vector<OniRecord> oni_records_of(const std::string& bytes, std::uint32_t type) {
  std::vector<OniRecord> found;
  for (const OniRecord& r : oni_records(bytes)) {
    if (r.type == type) found.push_back(r);
  }
  return found;
}

// `extra` appended to a record's payload (its payload size grown to match); the
// records after it move, so only checks up to this record still agree.
inline void append_to_payload(std::string& bytes, const OniRecord& r, const std::string& extra) {
  bytes.insert(r.offset + r.fields_size + r.payload_size, extra);
  put_u32(bytes, r.offset + 16, r.payload_size + static_cast<std::uint32_t>(extra.size()));
}

}  // namespace lccp::test
