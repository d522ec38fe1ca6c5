#pragma once
// Where frames come from: an OpenNI2 device, an .oni recording, or cloud files.
#include <cstdint>
#include <optional>

#include "lccp/frame.hpp"

namespace lccp {

class FrameSource {
 public:
  virtual ~FrameSource() = default;

  // The next frame, blocking until it arrives; nullopt at the end of the stream
  // or after request_stop(). Throws lccp::Error when the source fails (e.g. the
  // device disappeared). Called from one thread at a time.
  virtual std::optional<Frame> next() = 0;

  // Frames the source will deliver, if known (recordings, file lists).
  virtual std::optional<std::uint64_t> frame_count() const = 0;

  // True for sources that run on their own clock (a live sensor, --realtime
  // replay): frames not taken in time are lost, so the pipeline drops the oldest.
  virtual bool is_live() const = 0;

  // Makes a blocked or later next() return nullopt soon. Safe from any thread;
  // only sets an atomic flag, so also safe from a signal handler.
  virtual void request_stop() = 0;
};

}  // namespace lccp
