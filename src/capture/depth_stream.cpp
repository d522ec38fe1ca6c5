#include "depth_stream.hpp"

#include <cstring>

#include <spdlog/spdlog.h>

#include "lccp/capture/openni_session.hpp"
#include "lccp/error.hpp"

namespace lccp::detail {
namespace {

constexpr int kWaitSliceMs = 100;

std::string mode_text(const DepthMode& mode) {
  return std::to_string(mode.width) + "x" + std::to_string(mode.height) + " @ " + std::to_string(mode.fps) + " Hz";
}

bool is_depth_format(openni::PixelFormat format) {
  return format == openni::PIXEL_FORMAT_DEPTH_1_MM || format == openni::PIXEL_FORMAT_DEPTH_100_UM;
}

}  // namespace

DepthStream::~DepthStream() {
  if (started_) stream_.stop();
  if (stream_.isValid()) stream_.destroy();
  if (device_.isValid()) device_.close();
  if (listening_) openni::OpenNI::removeDeviceDisconnectedListener(this);
}

void DepthStream::open_device(const std::string& uri, const std::string& failure) {
  initialize_openni();
  if (device_.open(uri.c_str()) != openni::STATUS_OK) throw Error(failure + ": " + openni_error());
  uri_ = device_.getDeviceInfo().getUri();
  listening_ = openni::OpenNI::addDeviceDisconnectedListener(this) == openni::STATUS_OK;
}

void DepthStream::open_depth_stream() {
  if (!device_.hasSensor(openni::SENSOR_DEPTH)) throw Error(uri_ + " has no depth stream");
  if (stream_.create(device_, openni::SENSOR_DEPTH) != openni::STATUS_OK) {
    throw Error("cannot open the depth stream of " + uri_ + ": " + openni_error());
  }
}

void DepthStream::open_live(const LiveOptions& options) {
  initialize_openni();
  std::string uri = options.uri;
  if (uri.empty()) {
    openni::Array<openni::DeviceInfo> devices;
    openni::OpenNI::enumerateDevices(&devices);
    if (devices.getSize() == 0) throw Error("no OpenNI2 device found (none attached; give one with --uri)");
    // A real sensor before our virtual one (drivers load in file-name order).
    uri = devices[0].getUri();
    for (int i = devices.getSize() - 1; i >= 0; --i) {
      if (std::string(devices[i].getUri()).rfind("virtual://", 0) != 0) uri = devices[i].getUri();
    }
  }
  open_device(uri, "cannot open device " + uri);
  open_depth_stream();

  const openni::Array<openni::VideoMode>& offered = stream_.getSensorInfo().getSupportedVideoModes();
  std::vector<DepthMode> modes;
  std::vector<int> mode_index;
  for (int i = 0; i < offered.getSize(); ++i) {
    if (!is_depth_format(offered[i].getPixelFormat())) continue;
    modes.push_back({offered[i].getResolutionX(), offered[i].getResolutionY(), offered[i].getFps()});
    mode_index.push_back(i);
  }
  if (modes.empty()) throw Error(uri_ + " offers no millimetre depth mode");
  const std::size_t chosen = nearest_depth_mode(modes, options.mode);
  if (stream_.setVideoMode(offered[mode_index[chosen]]) != openni::STATUS_OK) {
    throw Error("cannot set depth mode " + mode_text(modes[chosen]) + " on " + uri_ + ": " + openni_error());
  }
  if (modes[chosen] == options.mode) {
    spdlog::info("{}: depth {}", uri_, mode_text(modes[chosen]));
  } else {
    spdlog::info("{}: depth {} (nearest offered to {})", uri_, mode_text(modes[chosen]), mode_text(options.mode));
  }
}

void DepthStream::start() {
  if (stream_.start() != openni::STATUS_OK) throw Error("cannot start the depth stream of " + uri_ + ": " + openni_error());
  started_ = true;
}

DepthMode DepthStream::mode() const {
  const openni::VideoMode mode = const_cast<openni::VideoStream&>(stream_).getVideoMode();
  return {mode.getResolutionX(), mode.getResolutionY(), mode.getFps()};
}

std::optional<Frame> DepthStream::wait_and_read(int timeout_ms, const std::atomic<bool>& stop) {
  openni::VideoStream* streams[] = {&stream_};
  for (int waited = 0; waited < timeout_ms && !stop.load() && !lost_.load(); waited += kWaitSliceMs) {
    int ready = -1;
    if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, kWaitSliceMs) != openni::STATUS_OK) continue;
    openni::VideoFrameRef frame;
    if (stream_.readFrame(&frame) != openni::STATUS_OK || !frame.isValid()) continue;
    return to_frame(frame);
  }
  return std::nullopt;
}

Frame DepthStream::to_frame(const openni::VideoFrameRef& frame) const {
  const auto& stream = const_cast<openni::VideoStream&>(stream_);
  DepthImage image;
  image.width = static_cast<std::uint32_t>(frame.getWidth());
  image.height = static_cast<std::uint32_t>(frame.getHeight());
  image.horizontal_fov_rad = stream.getHorizontalFieldOfView();
  image.vertical_fov_rad = stream.getVerticalFieldOfView();
  image.depth_mm.resize(std::size_t{image.width} * image.height);
  const auto* bytes = static_cast<const std::uint8_t*>(frame.getData());
  const std::size_t row_bytes = image.width * sizeof(std::uint16_t);
  for (std::uint32_t row = 0; row < image.height; ++row) {
    std::memcpy(&image.depth_mm[std::size_t{row} * image.width], bytes + std::size_t{row} * frame.getStrideInBytes(), row_bytes);
  }
  if (frame.getVideoMode().getPixelFormat() == openni::PIXEL_FORMAT_DEPTH_100_UM) {
    for (std::uint16_t& d : image.depth_mm) d = static_cast<std::uint16_t>((d + 5) / 10);
  } else if (frame.getVideoMode().getPixelFormat() != openni::PIXEL_FORMAT_DEPTH_1_MM) {
    throw Error(uri_ + " sends depth in an unsupported pixel format");
  }
  Frame out;
  out.index = static_cast<std::uint64_t>(frame.getFrameIndex());
  out.timestamp_us = frame.getTimestamp();
  out.depth = std::move(image);
  return out;
}

void DepthStream::onDeviceDisconnected(const openni::DeviceInfo* info) {
  if (info != nullptr && uri_ == info->getUri()) lost_.store(true);
}

}  // namespace lccp::detail
