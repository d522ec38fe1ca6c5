#pragma once
// Frame sources through OpenNI2: .oni recordings and live devices.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lccp/capture/frame_source.hpp"

namespace lccp {

struct ReplayOptions {
  bool realtime = false;                   // pace frames by the recording's timestamps
  std::optional<std::uint64_t> max_frames; // stop after this many frames
  int stall_timeout_ms = 5000;             // no frame for this long before the end: corrupt file
};

// Every depth frame of an .oni recording, in order, none dropped (OpenNI2's
// manual playback mode); the end of the file is detected by frame count, never
// by blocking (GUIDE 4). Frame::index counts from 0. Throws lccp::Error naming
// the file when it is missing, not an .oni recording, or has no depth stream;
// next() throws when the recording stops short of its frame count.
std::unique_ptr<FrameSource> open_recording(const std::filesystem::path& path, const ReplayOptions& options = {});

struct DepthMode {
  int width = 640;
  int height = 480;
  int fps = 30;
  bool operator==(const DepthMode&) const = default;
};

// The index of the mode nearest `wanted`: the same size and rate if offered,
// else the smallest relative difference in pixel count, then in frame rate.
// Throws lccp::Error for an empty list.
std::size_t nearest_depth_mode(const std::vector<DepthMode>& offered, const DepthMode& wanted);

struct LiveOptions {
  std::string uri;                         // empty: the first OpenNI2 device
  DepthMode mode;                          // wanted; the nearest offered is used and logged
  std::optional<std::uint64_t> max_frames; // stop after this many frames
  std::optional<double> max_seconds;       // stop after this long
  int stall_timeout_ms = 2000;             // no frame for this long: the device is lost
  int first_frame_timeout_ms = 20000;      // the wait for the first frame, if longer: a device
                                           // may take a while to start (over 2 s for the virtual
                                           // sensor under a sanitizer on a loaded machine)
};

// A live OpenNI2 depth stream. Frame::index is the sensor's frame index, so
// frames the sensor produced but we never read show up as gaps. Throws
// lccp::Error when no device answers the URI (or none is attached) or it has
// no depth sensor; next() throws when the device disappears mid-stream.
std::unique_ptr<FrameSource> open_device(const LiveOptions& options);

struct RecordStats {
  std::uint64_t frames = 0;
  DepthMode mode;
};

// Records `frames` depth frames of a device with openni::Recorder (fewer if
// `stop` is set first: what was recorded is kept). The file appears only when
// complete; stats.frames is the count the file holds. Throws lccp::Error like
// open_device, and when the device is lost (no file is left behind then).
RecordStats record_device(const LiveOptions& options, const std::filesystem::path& output, std::uint64_t frames,
                          const std::atomic<bool>& stop);

}  // namespace lccp
