#include "depth_stream.hpp"

#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <thread>

#include <spdlog/spdlog.h>

#include "depth_units.hpp"
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

// 0 is "unknown" (back_project refuses it per frame); NaN, negative or >= pi is garbage.
bool is_field_of_view(float radians) { return radians >= 0.0f && radians < std::numbers::pi_v<float>; }

}  // namespace

std::optional<std::string> depth_frame_problem(const DepthFrameLayout& f) {
  if (!is_depth_format(static_cast<openni::PixelFormat>(f.pixel_format))) {
    return "pixel format " + std::to_string(f.pixel_format) + " is not depth in 1 mm or 100 um";
  }
  const std::string size = std::to_string(f.width) + "x" + std::to_string(f.height);
  if (f.width <= 0 || f.height <= 0 || f.width > kMaxDepthSide || f.height > kMaxDepthSide) {
    return "size " + size + " outside 1.." + std::to_string(kMaxDepthSide) + " a side";
  }
  if (f.width != f.mode_width || f.height != f.mode_height) {
    return "size " + size + " differs from the stream's mode " + std::to_string(f.mode_width) + "x" +
           std::to_string(f.mode_height);
  }
  const std::int64_t row_bytes = std::int64_t{f.width} * 2;
  if (f.stride_bytes < row_bytes) {
    return "row stride " + std::to_string(f.stride_bytes) + " bytes is shorter than a row of " + std::to_string(row_bytes);
  }
  const std::int64_t needed = std::int64_t{f.stride_bytes} * (f.height - 1) + row_bytes;
  if (!f.has_data || f.data_bytes < needed) {
    return "holds " + std::to_string(f.has_data ? f.data_bytes : 0) + " bytes, " + size + " depth needs " +
           std::to_string(needed);
  }
  return std::nullopt;
}

DepthStream::~DepthStream() {
  if (started_) stream_.stop();
  // OpenNI2's file player thread walks its stream list without a lock, and
  // destroying a stream deletes it from that list without one (PlayerDevice::
  // MainLoop and destroyStream, Source/Drivers/OniFile/PlayerDevice.cpp): seen
  // as a SIGSEGV in libOniFile about once in 20 closes on a loaded machine.
  // A stopped stream sends that thread into 10 ms sleeps between walks; give
  // it two of them to get there before the stream goes.
  if (started_ && device_.isValid() && device_.isFile()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (stream_.isValid()) stream_.destroy();
  if (device_.isValid()) device_.close();
  if (listening_) openni::OpenNI::removeDeviceDisconnectedListener(this);
}

namespace {

// Why OpenNI2 could not open `uri`, without restating it: its extended error is
// the driver's reason, if any (ours: "virtual sensor URI 'URI': reason"), then
// "DeviceOpen: Couldn't open device 'URI'", and the caller's message names the
// URI already.
std::string open_failure_reason(const std::string& uri) {
  std::string reason = openni_error();
  const std::string generic = "DeviceOpen: Couldn't open device '" + uri + "'";
  if (const auto at = reason.find(generic); at != std::string::npos) reason.erase(at, generic.size());
  const std::string restated = "'" + uri + "': ";
  if (const auto at = reason.find(restated); at != std::string::npos) reason.erase(0, at + restated.size());
  const auto last = reason.find_last_not_of(' ');
  if (last == std::string::npos) return "no device answers at that URI (lccp devices lists them)";
  return reason.substr(0, last + 1);
}

}  // namespace

void DepthStream::open_device(const std::string& uri, const std::string& failure) {
  initialize_openni();
  if (device_.open(uri.c_str()) != openni::STATUS_OK) throw Error(failure + ": " + open_failure_reason(uri));
  uri_ = device_.getDeviceInfo().getUri();
  listening_ = openni::OpenNI::addDeviceDisconnectedListener(this) == openni::STATUS_OK;
}

void DepthStream::open_depth_stream() {
  if (!device_.hasSensor(openni::SENSOR_DEPTH)) throw Error(uri_ + " has no depth stream");
  if (stream_.create(device_, openni::SENSOR_DEPTH) != openni::STATUS_OK) {
    throw Error("cannot open the depth stream of " + uri_ + ": " + openni_error());
  }
}

std::vector<OfferedMode> depth_modes(const openni::SensorInfo& sensor) {
  const openni::Array<openni::VideoMode>& offered = sensor.getSupportedVideoModes();
  std::vector<OfferedMode> modes;
  for (int i = 0; i < offered.getSize(); ++i) {
    if (!is_depth_format(offered[i].getPixelFormat())) continue;
    modes.push_back({{offered[i].getResolutionX(), offered[i].getResolutionY(), offered[i].getFps()}, i});
  }
  return modes;
}

void DepthStream::open_live(const LiveOptions& options) {
  const std::string uri = options.uri.empty() ? first_sensor_uri() : options.uri;
  open_device(uri, "cannot open device " + uri);
  open_depth_stream();
  const std::vector<OfferedMode> modes = depth_modes(stream_.getSensorInfo());
  if (modes.empty()) throw Error(uri_ + " offers no millimetre depth mode");
  std::vector<DepthMode> choices;
  for (const OfferedMode& offered : modes) choices.push_back(offered.mode);
  const OfferedMode& chosen = modes[nearest_depth_mode(choices, options.mode)];
  const openni::VideoMode& video_mode = stream_.getSensorInfo().getSupportedVideoModes()[chosen.index];
  if (stream_.setVideoMode(video_mode) != openni::STATUS_OK) {
    throw Error("cannot set depth mode " + mode_text(chosen.mode) + " on " + uri_ + ": " + openni_error());
  }
  if (chosen.mode == options.mode) {
    spdlog::info("{}: depth {}", uri_, mode_text(chosen.mode));
  } else {
    spdlog::info("{}: depth {} (nearest offered to {})", uri_, mode_text(chosen.mode), mode_text(options.mode));
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

std::optional<Frame> DepthStream::wait_and_read(int timeout_ms, std::stop_token stop) {
  openni::VideoStream* streams[] = {&stream_};
  for (int waited = 0; waited < timeout_ms && !stop.stop_requested() && !lost_.load(); waited += kWaitSliceMs) {
    int ready = -1;
    if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, kWaitSliceMs) != openni::STATUS_OK) continue;
    openni::VideoFrameRef frame;
    if (stream_.readFrame(&frame) != openni::STATUS_OK || !frame.isValid()) continue;
    return to_frame(frame, frames_read_++);
  }
  return std::nullopt;
}

// Every size and format is checked before a byte is read: OpenNI2 hands on what
// the device or file declares (PlayerStream::OnNewDataCallback caps the data at
// the required frame size but keeps the declared width and height).
Frame DepthStream::to_frame(const openni::VideoFrameRef& frame, std::uint64_t number) const {
  auto& stream = const_cast<openni::VideoStream&>(stream_);
  const openni::VideoMode mode = stream.getVideoMode();
  DepthFrameLayout layout;
  layout.pixel_format = frame.getVideoMode().getPixelFormat();
  layout.width = frame.getWidth();
  layout.height = frame.getHeight();
  layout.stride_bytes = frame.getStrideInBytes();
  layout.data_bytes = frame.getDataSize();
  layout.has_data = frame.getData() != nullptr;
  layout.mode_width = mode.getResolutionX();
  layout.mode_height = mode.getResolutionY();
  const std::string where = uri_ + ": frame " + std::to_string(number) + ": ";
  if (const auto problem = depth_frame_problem(layout)) throw Error(where + *problem);
  DepthImage image;
  image.width = static_cast<std::uint32_t>(layout.width);
  image.height = static_cast<std::uint32_t>(layout.height);
  image.horizontal_fov_rad = stream.getHorizontalFieldOfView();
  image.vertical_fov_rad = stream.getVerticalFieldOfView();
  if (!is_field_of_view(image.horizontal_fov_rad) || !is_field_of_view(image.vertical_fov_rad)) {
    throw Error(where + "field of view outside [0, pi)");
  }
  image.depth_mm.resize(std::size_t{image.width} * image.height);
  const auto* bytes = static_cast<const std::uint8_t*>(frame.getData());
  const std::size_t row_bytes = image.width * sizeof(std::uint16_t);
  for (std::uint32_t row = 0; row < image.height; ++row) {
    std::memcpy(&image.depth_mm[std::size_t{row} * image.width], bytes + std::size_t{row} * layout.stride_bytes, row_bytes);
  }
  to_millimetres(image.depth_mm, layout.pixel_format);
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

namespace lccp {

std::string first_sensor_uri() {
  initialize_openni();
  openni::Array<openni::DeviceInfo> devices;
  openni::OpenNI::enumerateDevices(&devices);
  for (int i = 0; i < devices.getSize(); ++i) {
    const std::string uri = devices[i].getUri();
    if (uri.rfind("virtual://", 0) != 0) return uri;
  }
  throw Error("no OpenNI2 depth sensor found (lccp devices lists what OpenNI2 sees; --uri virtual://synthetic "
              "streams the built-in virtual sensor)");
}

}  // namespace lccp
