#include "lccp/capture/open_source.hpp"

#include <algorithm>
#include <filesystem>

#include "lccp/capture/cloud_files.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/capture/rosbag.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

bool is_uri(const std::string& spec) { return spec.find("://") != std::string::npos; }
bool has_extension(const std::string& spec, const char* extension) { return fs::path(spec).extension() == extension; }
bool is_recording(const std::string& spec) { return has_extension(spec, ".oni") || has_extension(spec, ".bag"); }

// A source that ends after N frames or S seconds. A frame that arrives after
// the S seconds is not passed on.
class LimitedSource final : public FrameSource {
 public:
  LimitedSource(std::unique_ptr<FrameSource> source, const SourceLimits& limits)
      : source_(std::move(source)), limits_(limits) {}

  std::optional<Frame> next(std::stop_token stop) override {
    if (!started_) started_ = Clock::now();
    if (limits_.max_frames && delivered_ >= *limits_.max_frames) return std::nullopt;
    if (out_of_time()) return std::nullopt;
    std::optional<Frame> frame = source_->next(std::move(stop));
    if (!frame || out_of_time()) return std::nullopt;
    ++delivered_;
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override {
    const std::optional<std::uint64_t> count = source_->frame_count();
    if (!limits_.max_frames) return count;
    return count ? std::min(*count, *limits_.max_frames) : *limits_.max_frames;
  }
  bool is_live() const override { return source_->is_live(); }
  bool is_stream() const override { return source_->is_stream(); }

 private:
  bool out_of_time() const {
    return limits_.max_seconds &&
           std::chrono::duration<double>(Clock::now() - *started_).count() >= *limits_.max_seconds;
  }

  std::unique_ptr<FrameSource> source_;
  SourceLimits limits_;
  std::optional<Clock::time_point> started_;
  std::uint64_t delivered_ = 0;
};

// Several sources are all cloud files or folders: a URI or a recording stands alone.
void check_alone(const std::vector<std::string>& specs) {
  for (const std::string& spec : specs) {
    if (is_uri(spec)) throw Error("a device URI (" + spec + ") must be the only source");
    if (is_recording(spec)) throw Error("a recording (" + spec + ") must be the only source");
  }
}

}  // namespace

SourceKind source_kind(const std::vector<std::string>& specs) {
  if (specs.empty()) throw Error("no source given (an .oni file, a device URI, or .pcd/.ply files or folders)");
  if (specs.size() > 1) {
    check_alone(specs);
  } else if (is_uri(specs.front())) {
    return SourceKind::device;
  } else if (is_recording(specs.front())) {
    return SourceKind::recording;
  }
  for (const std::string& spec : specs) {
    std::error_code error;
    if (!fs::exists(spec, error)) throw Error("cannot open " + spec + ": no such file");
    if (!fs::is_directory(spec, error) && !has_extension(spec, ".pcd") && !has_extension(spec, ".ply")) {
      throw Error(spec + " is not a source: expected an .oni or .bag recording, a .pcd or .ply cloud, a folder of "
                         "clouds or a device URI");
    }
  }
  return SourceKind::cloud_files;
}

const char* to_string(SourceKind kind) {
  switch (kind) {
    case SourceKind::recording: return "recording";
    case SourceKind::device: return "device";
    case SourceKind::cloud_files: break;
  }
  return "cloud files";
}

std::unique_ptr<FrameSource> limit_source(std::unique_ptr<FrameSource> source, const SourceLimits& limits) {
  if (limits.max_frames && *limits.max_frames == 0) throw Error("--frames must be at least 1");
  if (limits.max_seconds && !(*limits.max_seconds > 0)) throw Error("--seconds must be more than 0");
  if (!limits.max_frames && !limits.max_seconds) return source;
  return std::make_unique<LimitedSource>(std::move(source), limits);
}

std::unique_ptr<FrameSource> open_source(const std::vector<std::string>& specs, const SourceOptions& options) {
  const SourceKind kind = source_kind(specs);
  const bool bag = kind == SourceKind::recording && has_extension(specs.front(), ".bag");
  if (options.realtime && (kind != SourceKind::recording || bag)) {
    throw Error("--realtime needs an .oni recording: a device is always real time, cloud files have no timestamps");
  }
  std::unique_ptr<FrameSource> source;
  if (kind == SourceKind::device) {
    LiveOptions live;
    live.uri = specs.front();
    source = open_device(live);
  } else if (bag) {
    source = open_rosbag(specs.front());
  } else if (kind == SourceKind::recording) {
    ReplayOptions replay;
    replay.realtime = options.realtime;
    source = open_recording(specs.front(), replay);
  } else {
    source = open_cloud_files(std::vector<fs::path>(specs.begin(), specs.end()));
  }
  return limit_source(std::move(source), options.limits);
}

}  // namespace lccp
