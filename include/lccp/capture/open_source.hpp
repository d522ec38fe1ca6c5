#pragma once
// SOURCE (as on the command line) -> a FrameSource: an .oni recording, a
// device URI, or point cloud files; the one way every face of the library
// opens a source and limits it to N frames or S seconds.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lccp/frame_source.hpp"

namespace lccp {

enum class SourceKind {
  recording,    // one .oni file (every frame in order, or paced by its timestamps: realtime) or one
                // .bag file (lccp/capture/rosbag.hpp: every message of one topic in bag order)
  device,       // one OpenNI2 device URI (anything with "://", e.g. virtual://synthetic): live
  cloud_files,  // .pcd / .ply files and folders of them, in order
};

struct SourceLimits {
  std::optional<std::uint64_t> max_frames;  // stop after this many frames (>= 1)
  std::optional<double> max_seconds;        // stop this long after the first frame was asked for (> 0)
};

struct SourceOptions {
  SourceLimits limits;
  bool realtime = false;  // .oni recordings: pace by timestamps (a device always is)
};

// What the arguments name. Throws lccp::Error (one line) for no argument, a
// URI or .oni file given with anything else, or a file that is none of .oni,
// .pcd, .ply.
SourceKind source_kind(const std::vector<std::string>& specs);

// "recording", "device" or "cloud files".
const char* to_string(SourceKind kind);

// Opens the source the arguments name. Throws lccp::Error (one line, naming
// the argument) for a missing path, a folder without clouds, an unreadable
// recording, a device that does not answer, or --realtime with anything but an
// .oni recording. A .bag is read with open_rosbag's default topic.
std::unique_ptr<FrameSource> open_source(const std::vector<std::string>& specs, const SourceOptions& options = {});

// `source` ending after limits.max_frames frames or limits.max_seconds seconds
// (whichever comes first), its frame_count() capped to match. Throws
// lccp::Error for max_frames 0 or max_seconds <= 0.
std::unique_ptr<FrameSource> limit_source(std::unique_ptr<FrameSource> source, const SourceLimits& limits);

}  // namespace lccp
