#pragma once
// Our own structural check of an .oni recording, made when a replay opens it
// (oni_reader.hpp). It accepts what OpenNI2's file driver (libOniFile) reads
// safely: that driver trusts every size and index in the file, so a corrupt
// recording can make it corrupt its heap or spin.
// The record layout, from OpenNI2's public source, is in oni_format.hpp.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "depth_limits.hpp"

namespace lccp::detail {

// What we accept, besides a well-formed file: one depth stream (OpenNI2's
// Recorder writes exactly this for a depth-only recording), 16zT-compressed or
// uncompressed, in 1 mm or 100 um units, at most kMaxDepthSide pixels a side
// (depth_limits.hpp), and a frame that fits OpenNI2's player buffer (PlayerNode::DATA_MAX_SIZE,
// 1600 x 1200 x 3 bytes).
inline constexpr std::uint64_t kOniPlayerDataMaxBytes = 1600ull * 1200 * 3;

// Where one depth frame's NewData record lies in the file.
struct OniFrameRecord {
  std::uint64_t record_offset = 0;
  std::uint64_t payload_offset = 0;  // the frame's pixels, 16zT or uncompressed
  std::uint32_t payload_size = 0;
  std::uint64_t timestamp_us = 0;    // the sensor's timestamp, as OpenNI2's player hands it on
};

struct OniRecordingFacts {
  std::uint32_t frames = 0;
  int width = 0;
  int height = 0;
  int pixel_format = 0;     // openni::PixelFormat: 100 (1 mm) or 101 (100 um)
  std::uint32_t codec = 0;  // XnCodecID: '16zT' or 'NONE' as a little-endian u32
  float horizontal_fov_rad = 0;  // the xnFOV property; 0 (unknown) without one, as OpenNI2 reports it
  float vertical_fov_rad = 0;
  std::vector<OniFrameRecord> frame_records;  // `frames` of them, in file order
};

// Walks every record of the recording in `bytes` and decodes every depth frame
// with a bounded decoder. Returns what it found, or throws lccp::Error with one
// line "NAME: ..." naming the first inconsistency (and its byte offset). Reads
// only inside `bytes`; time and memory are linear in its size (fuzzing entry point).
OniRecordingFacts check_oni_recording(std::span<const std::uint8_t> bytes, std::string_view name);

// The same for a file, mapped read-only. Throws lccp::Error naming the path.
OniRecordingFacts check_oni_file(const std::filesystem::path& path);

}  // namespace lccp::detail
