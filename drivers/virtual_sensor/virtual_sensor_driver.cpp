// An OpenNI2 driver (OpenNI2 Driver API, Include/Driver/OniDriverAPI.h) exposing a virtual Kinect-class depth sensor, so that
// live capture, recording and device loss can be run and tested without hardware.
// Devices: virtual://synthetic (announced at start-up) and any virtual://... URI a
// client opens (virtual_uri.hpp). One depth sensor per device, free-running like a
// real one: frame k of a started stream is due k / fps seconds after start, carries
// frameIndex = k and timestamp = k * 1e6 / fps microseconds (at 30 fps exactly
// synthetic::timestamp_us_of_frame(k)), and frame numbers are skipped when rendering
// falls more than a frame behind.
// With frames=N the device delivers N frames, then, when frame N would be due,
// reports itself disconnected (OpenNI::addDeviceDisconnectedListener, called on the
// frame thread) and its stream goes silent: waitForAnyStream times out.
// Clients must stop their streams before OpenNI::shutdown(): shutdown holds OpenNI2's
// global lock while it stops them, a frame being raised waits for that lock, and stop()
// waits for the frame thread (measured: with a recorder attached, 4 hangs in 30 runs).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stop_token>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#define XN_NEW(type, ...) new type(__VA_ARGS__)
#define XN_DELETE(p) delete (p)
#include <OniDriverAPI.h>

#include "depth_sources.hpp"
#include "virtual_uri.hpp"

namespace lccp::virtual_sensor {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kDeviceName = "LCCP Virtual Sensor";
constexpr const char* kVendor = "LCCP Stream";
constexpr int kLogError = 3;  // XN_LOG_ERROR

using ErrorLog = std::function<void(const std::string&)>;

OniVideoMode to_oni(const DepthMode& mode) {
  OniVideoMode oni{};
  oni.pixelFormat = ONI_PIXEL_FORMAT_DEPTH_1_MM;
  oni.resolutionX = static_cast<int>(mode.width);
  oni.resolutionY = static_cast<int>(mode.height);
  oni.fps = mode.fps;
  return oni;
}

// Copies a property value out, as OpenNI2 expects: the caller's size must fit it.
template <typename T>
OniStatus put(void* data, int* size, const T& value) {
  if (data == nullptr || size == nullptr || *size < static_cast<int>(sizeof(T))) return ONI_STATUS_BAD_PARAMETER;
  std::memcpy(data, &value, sizeof(T));
  *size = static_cast<int>(sizeof(T));
  return ONI_STATUS_OK;
}

template <typename T>
std::optional<T> take(const void* data, int size) {
  if (data == nullptr || size != static_cast<int>(sizeof(T))) return std::nullopt;
  T value;
  std::memcpy(&value, data, sizeof(T));
  return value;
}

// What a device and its stream share about the device's life: with frames=N it
// disappears once N frames were delivered, and says so once.
class DeviceLife {
 public:
  DeviceLife(std::optional<std::uint64_t> frame_limit, std::function<void()> announce_lost)
      : frame_limit_(frame_limit), announce_lost_(std::move(announce_lost)) {}

  bool lost() const { return lost_; }
  bool used_up() const { return frame_limit_ && delivered_ >= *frame_limit_; }
  void count_frame() { ++delivered_; }

  // Marks the device lost and tells OpenNI2, the first time only.
  void disappear() {
    lost_ = true;
    std::call_once(announced_, announce_lost_);
  }

 private:
  const std::optional<std::uint64_t> frame_limit_;
  std::atomic<std::uint64_t> delivered_{0};
  std::atomic<bool> lost_{false};
  std::once_flag announced_;
  std::function<void()> announce_lost_;
};

class DepthStream final : public oni::driver::StreamBase {
 public:
  DepthStream(std::shared_ptr<const DepthSource> source, std::shared_ptr<DeviceLife> life, ErrorLog log_error)
      : source_(std::move(source)),
        life_(std::move(life)),
        log_error_(std::move(log_error)),
        mode_(source_->modes().front()) {}

  ~DepthStream() override { stop(); }

  OniStatus start() override {
    std::lock_guard lock(mutex_);
    if (worker_.joinable()) return ONI_STATUS_OK;
    if (life_->lost()) return ONI_STATUS_ERROR;
    worker_ = std::jthread([this, mode = mode_](std::stop_token stop) { run(std::move(stop), mode); });
    return ONI_STATUS_OK;
  }

  // Joins the frame thread, unless called from it (a device-lost listener that
  // stops the stream): then the thread is let go, and touches nothing of the stream.
  void stop() override {
    std::jthread worker;
    {
      std::lock_guard lock(mutex_);
      worker = std::move(worker_);
    }
    if (!worker.joinable()) return;
    worker.request_stop();
    if (worker.get_id() == std::this_thread::get_id()) {
      worker.detach();
    } else {
      worker.join();
    }
  }

  int getRequiredFrameSize() override {
    std::lock_guard lock(mutex_);
    return static_cast<int>(mode_.width * mode_.height * sizeof(std::uint16_t));
  }

  OniBool isPropertySupported(int id) override {
    switch (id) {
      case ONI_STREAM_PROPERTY_VIDEO_MODE:
      case ONI_STREAM_PROPERTY_CROPPING:
      case ONI_STREAM_PROPERTY_HORIZONTAL_FOV:
      case ONI_STREAM_PROPERTY_VERTICAL_FOV:
      case ONI_STREAM_PROPERTY_MAX_VALUE:
      case ONI_STREAM_PROPERTY_MIN_VALUE:
      case ONI_STREAM_PROPERTY_STRIDE:
      case ONI_STREAM_PROPERTY_MIRRORING: return TRUE;
      default: return FALSE;
    }
  }

  OniStatus getProperty(int id, void* data, int* size) override {
    std::lock_guard lock(mutex_);
    switch (id) {
      case ONI_STREAM_PROPERTY_VIDEO_MODE: return put(data, size, to_oni(mode_));
      case ONI_STREAM_PROPERTY_CROPPING: {
        // No cropping: the whole image. openni::Recorder asks every stream for it
        // (Source/Core/OniRecorder.cpp) and fails the recording without it.
        OniCropping cropping{};
        cropping.enabled = FALSE;
        cropping.width = static_cast<int>(mode_.width);
        cropping.height = static_cast<int>(mode_.height);
        return put(data, size, cropping);
      }
      case ONI_STREAM_PROPERTY_HORIZONTAL_FOV: return put(data, size, source_->field_of_view().horizontal_rad);
      case ONI_STREAM_PROPERTY_VERTICAL_FOV: return put(data, size, source_->field_of_view().vertical_rad);
      case ONI_STREAM_PROPERTY_MAX_VALUE: return put(data, size, int{kMaxDepthMm});
      case ONI_STREAM_PROPERTY_MIN_VALUE: return put(data, size, int{0});
      case ONI_STREAM_PROPERTY_STRIDE: return put(data, size, static_cast<int>(mode_.width * sizeof(std::uint16_t)));
      case ONI_STREAM_PROPERTY_MIRRORING: return put(data, size, OniBool{FALSE});
      default: return ONI_STATUS_NOT_SUPPORTED;
    }
  }

  OniStatus setProperty(int id, const void* data, int size) override {
    std::lock_guard lock(mutex_);
    switch (id) {
      case ONI_STREAM_PROPERTY_VIDEO_MODE: {
        const auto requested = take<OniVideoMode>(data, size);
        if (!requested) return ONI_STATUS_BAD_PARAMETER;
        const auto& modes = source_->modes();
        const auto match = std::find_if(modes.begin(), modes.end(), [&](const DepthMode& mode) {
          const OniVideoMode oni = to_oni(mode);
          return oni.pixelFormat == requested->pixelFormat && oni.resolutionX == requested->resolutionX &&
                 oni.resolutionY == requested->resolutionY && oni.fps == requested->fps;
        });
        if (match == modes.end()) return ONI_STATUS_NOT_SUPPORTED;
        if (*match == mode_) return ONI_STATUS_OK;
        if (worker_.joinable()) return ONI_STATUS_OUT_OF_FLOW;  // the frame size is fixed while streaming
        mode_ = *match;
        return ONI_STATUS_OK;
      }
      case ONI_STREAM_PROPERTY_CROPPING: {
        const auto cropping = take<OniCropping>(data, size);
        if (!cropping) return ONI_STATUS_BAD_PARAMETER;
        return cropping->enabled ? ONI_STATUS_NOT_SUPPORTED : ONI_STATUS_OK;
      }
      case ONI_STREAM_PROPERTY_MIRRORING: {
        const auto mirroring = take<OniBool>(data, size);
        if (!mirroring) return ONI_STATUS_BAD_PARAMETER;
        return *mirroring ? ONI_STATUS_NOT_SUPPORTED : ONI_STATUS_OK;
      }
      default: return ONI_STATUS_NOT_SUPPORTED;
    }
  }

 private:
  // The frame thread: sleeps until frame k is due, renders it into a frame from
  // OpenNI2's pool and raises it; stops when asked or when the device disappears.
  void run(std::stop_token stop, DepthMode mode) {
    const std::shared_ptr<DeviceLife> life = life_;  // the stream may be gone after disappear()
    const std::chrono::duration<double> period(1.0 / mode.fps);
    const Clock::time_point start = Clock::now();
    std::mutex sleep_mutex;
    std::condition_variable_any sleeper;
    bool render_failed_before = false;

    for (std::uint64_t k = 0;; ++k) {
      const auto due = start + std::chrono::duration_cast<Clock::duration>(period * static_cast<double>(k));
      {
        std::unique_lock lock(sleep_mutex);
        sleeper.wait_until(lock, stop, due, [] { return false; });
      }
      if (stop.stop_requested()) return;
      if (life->used_up()) {
        life->disappear();
        return;
      }
      // Like a real sensor, stay on the clock: skip the frames whose time has passed.
      const auto behind = static_cast<std::uint64_t>(std::floor((Clock::now() - start) / period));
      k = std::max(k, behind);

      OniFrame* frame = getServices().acquireFrame();
      if (frame == nullptr) continue;
      const std::uint64_t timestamp_us = std::llround(static_cast<double>(k) * 1e6 / mode.fps);
      try {
        auto* pixels = static_cast<std::uint16_t*>(frame->data);
        source_->render(k, timestamp_us, mode, std::span<std::uint16_t>(pixels, std::size_t{mode.width} * mode.height));
      } catch (const std::exception& e) {
        if (!render_failed_before) {  // one report per stream start, not one per frame
          log_error_(std::string("virtual sensor: frame ") + std::to_string(k) + " not rendered: " + e.what());
          render_failed_before = true;
        }
        getServices().releaseFrame(frame);
        continue;
      }
      frame->dataSize = static_cast<int>(std::size_t{mode.width} * mode.height * sizeof(std::uint16_t));
      frame->sensorType = ONI_SENSOR_DEPTH;
      frame->timestamp = timestamp_us;
      frame->frameIndex = static_cast<int>(k);
      frame->width = static_cast<int>(mode.width);
      frame->height = static_cast<int>(mode.height);
      frame->videoMode = to_oni(mode);
      frame->croppingEnabled = FALSE;
      frame->cropOriginX = 0;
      frame->cropOriginY = 0;
      frame->stride = static_cast<int>(mode.width * sizeof(std::uint16_t));
      raiseNewFrame(frame);
      getServices().releaseFrame(frame);
      life->count_frame();
    }
  }

  const std::shared_ptr<const DepthSource> source_;
  const std::shared_ptr<DeviceLife> life_;
  const ErrorLog log_error_;
  std::mutex mutex_;  // guards mode_ and worker_: OpenNI2 calls properties from any thread
  DepthMode mode_;
  std::jthread worker_;
};

class VirtualDevice final : public oni::driver::DeviceBase {
 public:
  VirtualDevice(std::shared_ptr<const DepthSource> source, std::shared_ptr<DeviceLife> life, ErrorLog log_error)
      : source_(std::move(source)), life_(std::move(life)), log_error_(std::move(log_error)) {
    for (const DepthMode& mode : source_->modes()) video_modes_.push_back(to_oni(mode));
    sensor_.sensorType = ONI_SENSOR_DEPTH;
    sensor_.numSupportedVideoModes = static_cast<int>(video_modes_.size());
    sensor_.pSupportedVideoModes = video_modes_.data();
  }

  // OpenNI2 destroys streams before closing their device. A client that closes the
  // device first still has the stream's handle and may stop it later, so a stream left
  // here is stopped but kept.
  ~VirtualDevice() override {
    std::lock_guard lock(mutex_);
    for (DepthStream* stream : streams_) stream->stop();
  }

  OniStatus getSensorInfoList(OniSensorInfo** sensors, int* count) override {
    *sensors = &sensor_;
    *count = 1;
    return ONI_STATUS_OK;
  }

  oni::driver::StreamBase* createStream(OniSensorType type) override {
    if (type != ONI_SENSOR_DEPTH) return nullptr;
    std::lock_guard lock(mutex_);
    return streams_.emplace_back(new DepthStream(source_, life_, log_error_));
  }

  void destroyStream(oni::driver::StreamBase* stream) override {
    {
      std::lock_guard lock(mutex_);
      std::erase(streams_, stream);
    }
    delete stream;
  }

  OniBool isPropertySupported(int id) override { return id == ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION; }

  OniStatus getProperty(int id, void* data, int* size) override {
    if (id == ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION) return put(data, size, ONI_IMAGE_REGISTRATION_OFF);
    return ONI_STATUS_NOT_SUPPORTED;
  }

  OniStatus setProperty(int id, const void* data, int size) override {
    if (id != ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION) return ONI_STATUS_NOT_SUPPORTED;
    const auto mode = take<OniImageRegistrationMode>(data, size);
    if (!mode) return ONI_STATUS_BAD_PARAMETER;
    return *mode == ONI_IMAGE_REGISTRATION_OFF ? ONI_STATUS_OK : ONI_STATUS_NOT_SUPPORTED;
  }

 private:
  const std::shared_ptr<const DepthSource> source_;
  const std::shared_ptr<DeviceLife> life_;
  const ErrorLog log_error_;
  std::vector<OniVideoMode> video_modes_;
  OniSensorInfo sensor_{};
  std::mutex mutex_;
  std::vector<DepthStream*> streams_;
};

class VirtualSensorDriver final : public oni::driver::DriverBase {
 public:
  explicit VirtualSensorDriver(OniDriverServices* services) : DriverBase(services) {}

  OniStatus initialize(oni::driver::DeviceConnectedCallback connected,
                       oni::driver::DeviceDisconnectedCallback disconnected,
                       oni::driver::DeviceStateChangedCallback state_changed, void* cookie) override {
    const OniStatus status = DriverBase::initialize(connected, disconnected, state_changed, cookie);
    if (status == ONI_STATUS_OK) announce(std::string(kSyntheticUri));
    return status;
  }

  // Any virtual://... URI that parses becomes a device; OpenNI2 asks every driver.
  OniStatus tryDevice(const char* uri) override {
    if (uri == nullptr || !is_virtual_uri(uri)) return ONI_STATUS_ERROR;
    try {
      parse_virtual_uri(uri);
      if (std::strlen(uri) >= ONI_MAX_STR) {
        report("virtual sensor URI is longer than OpenNI2's " + std::to_string(ONI_MAX_STR - 1) + " characters");
        return ONI_STATUS_ERROR;
      }
      announce(uri);
      return ONI_STATUS_OK;
    } catch (const std::exception& e) {
      report(e.what());
      return ONI_STATUS_ERROR;
    }
  }

  oni::driver::DeviceBase* deviceOpen(const char* uri, const char* /*mode*/) override {
    try {
      const VirtualUri parsed = parse_virtual_uri(uri);
      const OniDeviceInfo info = device_info(uri);
      auto life = std::make_shared<DeviceLife>(parsed.frame_limit, [this, info] { deviceDisconnected(&info); });
      return new VirtualDevice(make_source(parsed), std::move(life),
                               [this](const std::string& message) { log(message); });
    } catch (const std::exception& e) {
      report(std::string("cannot open ") + uri + ": " + e.what());
      return nullptr;
    }
  }

  void deviceClose(oni::driver::DeviceBase* device) override { delete device; }

  void shutdown() override {}

 private:
  static OniDeviceInfo device_info(const std::string& uri) {
    OniDeviceInfo info{};
    std::snprintf(info.uri, sizeof(info.uri), "%s", uri.c_str());
    std::snprintf(info.vendor, sizeof(info.vendor), "%s", kVendor);
    std::snprintf(info.name, sizeof(info.name), "%s", kDeviceName);
    return info;
  }

  // Tells OpenNI2 about a device, once per URI.
  void announce(const std::string& uri) {
    {
      std::lock_guard lock(mutex_);
      if (!announced_.insert(uri).second) return;
    }
    const OniDeviceInfo info = device_info(uri);
    deviceConnected(&info);
  }

  // Frame-thread failures: OpenNI2's log, and stderr, since nobody reads that log.
  void log(const std::string& message) {
    getServices().log(kLogError, __FILE__, __LINE__, "LccpVirtualSensor", message.c_str());
    std::fprintf(stderr, "%s\n", message.c_str());
  }

  // Adds to OpenNI2's extended error (OpenNI::getExtendedError()).
  void report(const std::string& message) { getServices().errorLoggerAppend("%s", message.c_str()); }

  std::mutex mutex_;
  std::set<std::string> announced_;
};

}  // namespace
}  // namespace lccp::virtual_sensor

ONI_EXPORT_DRIVER(lccp::virtual_sensor::VirtualSensorDriver)
