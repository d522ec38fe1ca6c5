#include "lccp/capture/openni_sources.hpp"

#include <algorithm>
#include <condition_variable>
#include <cmath>
#include <cstring>
#include <mutex>

#include <OpenNI.h>
#include <spdlog/spdlog.h>

#include "depth_stream.hpp"
#include "oni_reader.hpp"
#include "lccp/capture/openni_session.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

// Sleeps until `deadline`; a stop request wakes it at once (false).
bool sleep_until(Clock::time_point deadline, std::stop_token stop) {
  std::mutex mutex;
  std::condition_variable_any woken;
  std::unique_lock lock(mutex);
  woken.wait_until(lock, stop, deadline, [] { return false; });
  return !stop.stop_requested();
}

class RecordingSource final : public FrameSource {
 public:
  RecordingSource(const std::filesystem::path& path, const ReplayOptions& options)
      : reader_(checked_recording_path(path)), options_(options) {}

  std::optional<Frame> next(std::stop_token stop) override {
    if (delivered_ >= reader_.frame_count() || stop.stop_requested()) return std::nullopt;
    Frame frame = reader_.read(delivered_++);
    if (options_.realtime && !pace(frame, stop)) return std::nullopt;
    frame.captured = Clock::now();
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override { return reader_.frame_count(); }
  bool is_live() const override { return options_.realtime; }

 private:
  static const std::filesystem::path& checked_recording_path(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::exists(path, error)) throw Error("cannot open " + path.string() + ": no such file");
    if (!std::filesystem::is_regular_file(path, error)) throw Error(path.string() + " is not a file");
    if (path.extension() != ".oni") throw Error(path.string() + " is not an .oni recording (expected the .oni suffix)");
    return path;
  }

  // Waits until the frame is due by the recording's clock (a live sensor's pace).
  bool pace(const Frame& frame, std::stop_token stop) {
    if (!first_timestamp_us_) {
      first_timestamp_us_ = frame.timestamp_us;
      replay_start_ = Clock::now();
    }
    const auto offset = std::chrono::microseconds(frame.timestamp_us - std::min(frame.timestamp_us, *first_timestamp_us_));
    return sleep_until(replay_start_ + offset, std::move(stop));
  }

  detail::OniReader reader_;
  ReplayOptions options_;
  std::uint64_t delivered_ = 0;
  std::optional<std::uint64_t> first_timestamp_us_;
  Clock::time_point replay_start_{};
};

class DeviceSource final : public FrameSource {
 public:
  explicit DeviceSource(const LiveOptions& options) : options_(options) { stream_.open_live(options_); }

  // The stream starts when the first frame is asked for: a sensor's frames
  // from before the pipeline was ready (its warm-up) would be lost uncounted.
  std::optional<Frame> next(std::stop_token stop) override {
    if (!started_) {
      stream_.start();
      started_ = true;
    }
    const int timeout_ms = delivered_ == 0 ? std::max(options_.stall_timeout_ms, options_.first_frame_timeout_ms)
                                           : options_.stall_timeout_ms;
    std::optional<Frame> frame = stream_.wait_and_read(timeout_ms, stop);
    if (!frame) {
      if (stop.stop_requested()) return std::nullopt;
      const std::string after = " after " + std::to_string(delivered_) + " frames";
      if (stream_.lost()) throw Error("device " + stream_.uri() + " disconnected" + after);
      throw Error("device " + stream_.uri() + " stopped sending frames" + after + " (no frame for " +
                  std::to_string(timeout_ms) + " ms)");
    }
    frame->captured = Clock::now();
    ++delivered_;
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override { return std::nullopt; }
  bool is_live() const override { return true; }

 private:
  LiveOptions options_;
  detail::DepthStream stream_;
  bool started_ = false;
  std::uint64_t delivered_ = 0;
};

}  // namespace

std::unique_ptr<FrameSource> open_recording(const std::filesystem::path& path, const ReplayOptions& options) {
  return std::make_unique<RecordingSource>(path, options);
}

std::unique_ptr<FrameSource> open_device(const LiveOptions& options) {
  return std::make_unique<DeviceSource>(options);
}

std::vector<DeviceDescription> list_devices() {
  initialize_openni();
  openni::Array<openni::DeviceInfo> devices;
  openni::OpenNI::enumerateDevices(&devices);
  std::vector<DeviceDescription> out;
  for (int i = 0; i < devices.getSize(); ++i) {
    DeviceDescription description{devices[i].getUri(), devices[i].getVendor(), devices[i].getName(), {}};
    openni::Device device;
    if (device.open(devices[i].getUri()) == openni::STATUS_OK) {
      if (const openni::SensorInfo* depth = device.getSensorInfo(openni::SENSOR_DEPTH)) {
        for (const detail::OfferedMode& offered : detail::depth_modes(*depth)) {
          description.depth_modes.push_back(offered.mode);
        }
      }
      device.close();
    }
    out.push_back(std::move(description));
  }
  return out;
}

std::size_t nearest_depth_mode(const std::vector<DepthMode>& offered, const DepthMode& wanted) {
  if (offered.empty()) throw Error("the depth sensor offers no video mode");
  const auto cost = [&](const DepthMode& mode) {
    const double wanted_pixels = double(wanted.width) * wanted.height;
    const double pixel_difference = std::abs(double(mode.width) * mode.height - wanted_pixels) / wanted_pixels;
    const double rate_difference = std::abs(double(mode.fps - wanted.fps)) / wanted.fps;
    return std::pair{pixel_difference, rate_difference};
  };
  std::size_t best = 0;
  for (std::size_t i = 1; i < offered.size(); ++i) {
    if (cost(offered[i]) < cost(offered[best])) best = i;
  }
  return best;
}

}  // namespace lccp
