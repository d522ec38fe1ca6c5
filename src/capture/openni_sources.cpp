#include "lccp/capture/openni_sources.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <thread>

#include <OpenNI.h>
#include <spdlog/spdlog.h>

#include "depth_stream.hpp"
#include "oni_check.hpp"
#include "lccp/capture/openni_session.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

using Millis = std::chrono::milliseconds;

// Sleeps until `deadline` in short slices, returning early (false) on stop.
bool sleep_until(Clock::time_point deadline, const std::atomic<bool>& stop) {
  while (Clock::now() < deadline) {
    if (stop.load()) return false;
    std::this_thread::sleep_for(std::min<Clock::duration>(deadline - Clock::now(), Millis(20)));
  }
  return !stop.load();
}

class RecordingSource final : public FrameSource {
 public:
  RecordingSource(const std::filesystem::path& path, const ReplayOptions& options)
      : path_(path), options_(options) {
    check_recording_path(path);
    // OpenNI2's file driver trusts the file's sizes and indices: ours are checked
    // first, every record and every frame (oni_check.cpp says why this, not a child process).
    const detail::OniRecordingFacts facts = detail::check_oni_file(path);
    initialize_openni();
    try {
      stream_.open_device(path.string(), "");
    } catch (const Error&) {  // OpenNI2 says only "Couldn't open device"
      throw Error("cannot open " + path.string() + ": not a readable .oni recording (truncated or corrupt?)");
    }
    openni::PlaybackControl* playback = stream_.device().getPlaybackControl();
    if (playback == nullptr) throw Error(path.string() + " is not an .oni recording");
    playback->setRepeatEnabled(false);
    playback->setSpeed(-1.0f);  // manual: each frame released on request, none dropped (GUIDE 4)
    stream_.open_depth_stream();
    total_ = static_cast<std::uint64_t>(std::max(0, playback->getNumberOfFrames(stream_.stream())));
    if (total_ != facts.frames) {
      throw Error(path.string() + ": OpenNI2 counts " + std::to_string(total_) + " depth frames where the file holds " +
                  std::to_string(facts.frames));
    }
    if (options_.max_frames) total_ = std::min(total_, *options_.max_frames);
    stream_.start();
  }

  std::optional<Frame> next() override {
    if (delivered_ >= total_) return std::nullopt;
    std::optional<Frame> frame = stream_.wait_and_read(options_.stall_timeout_ms, stop_);
    if (!frame) {
      if (stop_.load()) return std::nullopt;
      throw Error("recording " + path_.string() + " ended after " + std::to_string(delivered_) + " of " +
                  std::to_string(total_) + " frames (truncated or corrupt?)");
    }
    frame->index = delivered_++;
    if (options_.realtime && !pace(*frame)) return std::nullopt;
    frame->captured = Clock::now();
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override { return total_; }
  bool is_live() const override { return options_.realtime; }
  void request_stop() override { stop_.store(true); }

 private:
  static void check_recording_path(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::exists(path, error)) throw Error("cannot open " + path.string() + ": no such file");
    if (!std::filesystem::is_regular_file(path, error)) throw Error(path.string() + " is not a file");
    if (path.extension() != ".oni") throw Error(path.string() + " is not an .oni recording (expected the .oni suffix)");
  }

  // Waits until the frame is due by the recording's clock (a live sensor's pace).
  bool pace(const Frame& frame) {
    if (!first_timestamp_us_) {
      first_timestamp_us_ = frame.timestamp_us;
      replay_start_ = Clock::now();
    }
    const auto offset = std::chrono::microseconds(frame.timestamp_us - std::min(frame.timestamp_us, *first_timestamp_us_));
    return sleep_until(replay_start_ + offset, stop_);
  }

  std::filesystem::path path_;
  ReplayOptions options_;
  detail::DepthStream stream_;
  std::uint64_t total_ = 0;
  std::uint64_t delivered_ = 0;
  std::optional<std::uint64_t> first_timestamp_us_;
  Clock::time_point replay_start_{};
  std::atomic<bool> stop_{false};
};

class DeviceSource final : public FrameSource {
 public:
  explicit DeviceSource(const LiveOptions& options) : options_(options) {
    stream_.open_live(options_);
    stream_.start();
    started_ = Clock::now();
  }

  std::optional<Frame> next() override {
    if (options_.max_frames && delivered_ >= *options_.max_frames) return std::nullopt;
    if (options_.max_seconds &&
        std::chrono::duration<double>(Clock::now() - started_).count() >= *options_.max_seconds) {
      return std::nullopt;
    }
    const int timeout_ms = delivered_ == 0 ? std::max(options_.stall_timeout_ms, options_.first_frame_timeout_ms)
                                           : options_.stall_timeout_ms;
    std::optional<Frame> frame = stream_.wait_and_read(timeout_ms, stop_);
    if (!frame) {
      if (stop_.load()) return std::nullopt;
      const std::string after = " after " + std::to_string(delivered_) + " frames";
      if (stream_.lost()) throw Error("device " + stream_.uri() + " disconnected" + after);
      throw Error("device " + stream_.uri() + " stopped sending frames" + after + " (no frame for " +
                  std::to_string(timeout_ms) + " ms)");
    }
    frame->captured = Clock::now();
    ++delivered_;
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override { return options_.max_frames; }
  bool is_live() const override { return true; }
  void request_stop() override { stop_.store(true); }

 private:
  LiveOptions options_;
  detail::DepthStream stream_;
  Clock::time_point started_{};
  std::uint64_t delivered_ = 0;
  std::atomic<bool> stop_{false};
};

}  // namespace

std::unique_ptr<FrameSource> open_recording(const std::filesystem::path& path, const ReplayOptions& options) {
  return std::make_unique<RecordingSource>(path, options);
}

std::unique_ptr<FrameSource> open_device(const LiveOptions& options) {
  return std::make_unique<DeviceSource>(options);
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
