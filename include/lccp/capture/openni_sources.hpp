#pragma once
// Frame sources for OpenNI2: live devices through OpenNI2, and .oni recordings
// (OpenNI2's file format) through our own reader.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "lccp/frame_source.hpp"

namespace lccp {

struct ReplayOptions {
  bool realtime = false;                   // pace frames by the recording's timestamps
};

// Every depth frame of an .oni recording (as OpenNI2's Recorder writes them: one
// depth stream, 16zT or uncompressed), in order, none dropped. The whole file is
// checked when it is opened, then each frame is read and decoded by next() on
// the caller's thread; OpenNI2's file player is not used (src/capture/oni_reader.hpp
// says why). Frame::index counts from 0. Throws lccp::Error naming the file when
// it is missing, not an .oni recording, damaged anywhere, or has no depth stream;
// next() throws when the file was cut or changed after it was opened.
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
  std::string uri;                         // empty: the first real OpenNI2 device (never the virtual sensor)
  DepthMode mode;                          // wanted; the nearest offered is used and logged
  int stall_timeout_ms = 2000;             // no frame for this long: the device is lost
  int first_frame_timeout_ms = 20000;      // the wait for the first frame, if longer: a device
                                           // may take a while to start (over 2 s for the virtual
                                           // sensor under a sanitizer on a loaded machine)
};

// A live OpenNI2 depth stream. Frame::index is the sensor's frame index, so
// frames the sensor produced but we never read show up as gaps. Throws
// lccp::Error when no device answers the URI (or, without a URI, no sensor is
// attached) or it has no depth sensor; next() throws when the device
// disappears mid-stream.
std::unique_ptr<FrameSource> open_device(const LiveOptions& options);

// The URI of the first device OpenNI2 reports that is not the virtual sensor
// (what open_device uses without a URI). Throws lccp::Error, saying how to use
// the virtual sensor, when no such device is attached.
std::string first_sensor_uri();

// One OpenNI2 device as enumerateDevices reports it, with its depth modes.
struct DeviceDescription {
  std::string uri;
  std::string vendor;
  std::string name;
  std::vector<DepthMode> depth_modes;  // millimetre depth modes of its depth sensor (empty: none)
};

// Every device OpenNI2's drivers report (real sensors and the virtual sensor's
// default URI), in OpenNI2's order.
std::vector<DeviceDescription> list_devices();

struct RecordStats {
  std::uint64_t frames = 0;
  DepthMode mode;
};

// Records `frames` depth frames of a device with openni::Recorder (fewer if
// a stop is requested first: what was recorded is kept). The file appears only when
// complete; stats.frames is the count the file holds. Throws lccp::Error like
// open_device, and when the device is lost (no file is left behind then).
RecordStats record_device(const LiveOptions& options, const std::filesystem::path& output, std::uint64_t frames,
                          std::stop_token stop = {});

}  // namespace lccp
