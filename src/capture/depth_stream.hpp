#pragma once
// One OpenNI2 device and its depth stream (internal to the capture sources).
#include <atomic>
#include <optional>
#include <string>

#include <OpenNI.h>

#include "lccp/capture/openni_sources.hpp"
#include "lccp/frame.hpp"

namespace lccp::detail {

class DepthStream : private openni::OpenNI::DeviceDisconnectedListener {
 public:
  DepthStream() = default;
  ~DepthStream() override;
  DepthStream(const DepthStream&) = delete;
  DepthStream& operator=(const DepthStream&) = delete;

  // Opens `uri`; on failure throws lccp::Error "<failure>: <OpenNI2's reason>".
  void open_device(const std::string& uri, const std::string& failure);
  // Creates the depth stream; throws if the device has none.
  void open_depth_stream();
  // A live device: the given URI or the first one, the mode nearest options.mode.
  void open_live(const LiveOptions& options);
  void start();

  // The next frame (Frame::index = the sensor's frame index), or nullopt after
  // `timeout_ms` without one, on `stop`, or once the device is lost.
  std::optional<Frame> wait_and_read(int timeout_ms, const std::atomic<bool>& stop);

  bool lost() const { return lost_.load(); }
  const std::string& uri() const { return uri_; }
  DepthMode mode() const;
  openni::Device& device() { return device_; }
  openni::VideoStream& stream() { return stream_; }

 private:
  void onDeviceDisconnected(const openni::DeviceInfo* info) override;
  Frame to_frame(const openni::VideoFrameRef& frame) const;

  openni::Device device_;
  openni::VideoStream stream_;
  std::string uri_;
  bool listening_ = false;
  bool started_ = false;
  std::atomic<bool> lost_{false};
};

}  // namespace lccp::detail
