#pragma once
// Where frames come from: an OpenNI2 device, an .oni recording, cloud files,
// or anything else that produces Frames (lccp/capture/open_source.hpp opens
// the built-in ones).
#include <cstdint>
#include <optional>
#include <stop_token>

#include "lccp/frame.hpp"

namespace lccp {

class FrameSource {
 public:
  virtual ~FrameSource() = default;

  // The next frame, blocking until it arrives; nullopt at the end of the
  // stream, or soon after a stop is requested on `stop`. Throws lccp::Error
  // when the source fails (e.g. the device disappeared). Called from one
  // thread at a time.
  virtual std::optional<Frame> next(std::stop_token stop) = 0;

  // Frames the source will deliver, if known (recordings, file lists).
  virtual std::optional<std::uint64_t> frame_count() const = 0;

  // True for sources that run on their own clock (a live sensor, --realtime
  // replay): frames not taken in time are lost, so the pipeline drops the oldest.
  virtual bool is_live() const = 0;

  // True if the frames are one scene over time (a sensor, a recording), so a
  // segment keeps its id from frame to frame; false for unrelated clouds (a
  // batch of files), where each frame gets ids 1..K of its own.
  virtual bool is_stream() const { return true; }
};

}  // namespace lccp
