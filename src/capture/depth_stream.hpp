#pragma once
// One OpenNI2 device and its depth stream (internal to the capture sources).
#include <atomic>
#include <cstdint>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include <OpenNI.h>

#include "lccp/capture/openni_sources.hpp"
#include "depth_limits.hpp"
#include "lccp/frame.hpp"

namespace lccp::detail {

// What an openni::VideoFrameRef says about its pixels, and the stream's declared mode.
struct DepthFrameLayout {
  int pixel_format = 0;  // openni::PixelFormat
  int width = 0;
  int height = 0;
  int stride_bytes = 0;
  int data_bytes = 0;    // getDataSize()
  bool has_data = false; // getData() != nullptr
  int mode_width = 0;    // the stream's video mode
  int mode_height = 0;
};

// Why the frame's pixels cannot be read as width x height 2-byte depth values in
// 1 mm or 100 um units within its data (one line), or nullopt if they can.
std::optional<std::string> depth_frame_problem(const DepthFrameLayout& frame);

// The millimetre depth modes a sensor offers, each with its index in
// getSupportedVideoModes() (to set it).
struct OfferedMode {
  DepthMode mode;
  int index = 0;
};
std::vector<OfferedMode> depth_modes(const openni::SensorInfo& sensor);

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
  // OpenNI2's waitForAnyStream cannot be woken early, so the wait is cut into
  // 100 ms slices and `stop` is seen within one slice.
  std::optional<Frame> wait_and_read(int timeout_ms, std::stop_token stop);

  bool lost() const { return lost_.load(); }
  const std::string& uri() const { return uri_; }
  DepthMode mode() const;
  openni::Device& device() { return device_; }
  openni::VideoStream& stream() { return stream_; }

 private:
  void onDeviceDisconnected(const openni::DeviceInfo* info) override;
  // Throws lccp::Error "<uri>: frame <number>: ..." for a frame depth_frame_problem refuses.
  Frame to_frame(const openni::VideoFrameRef& frame, std::uint64_t number) const;

  openni::Device device_;
  openni::VideoStream stream_;
  std::string uri_;
  bool listening_ = false;
  bool started_ = false;
  std::atomic<bool> lost_{false};
  std::uint64_t frames_read_ = 0;
};

}  // namespace lccp::detail
