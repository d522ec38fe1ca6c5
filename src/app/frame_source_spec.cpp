#include "frame_source_spec.hpp"

#include <algorithm>
#include <filesystem>

#include "lccp/capture/cloud_files.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/error.hpp"

namespace lccp::app {
namespace {

namespace fs = std::filesystem;

bool is_uri(const std::string& spec) { return spec.find("://") != std::string::npos; }
bool has_extension(const std::string& spec, const char* extension) { return fs::path(spec).extension() == extension; }

// A source of files that stops after N frames or S seconds; the recording and
// device sources stop after N frames themselves.
class LimitedSource final : public FrameSource {
 public:
  LimitedSource(std::unique_ptr<FrameSource> source, std::optional<std::uint64_t> max_frames,
                std::optional<double> max_seconds)
      : source_(std::move(source)), max_frames_(max_frames), max_seconds_(max_seconds) {}

  std::optional<Frame> next() override {
    if (!started_) started_ = Clock::now();
    if (max_frames_ && delivered_ >= *max_frames_) return std::nullopt;
    if (max_seconds_ && std::chrono::duration<double>(Clock::now() - *started_).count() >= *max_seconds_) {
      return std::nullopt;
    }
    std::optional<Frame> frame = source_->next();
    if (frame) ++delivered_;
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override {
    const std::optional<std::uint64_t> count = source_->frame_count();
    if (!max_frames_) return count;
    return count ? std::min(*count, *max_frames_) : *max_frames_;
  }
  bool is_live() const override { return source_->is_live(); }
  void request_stop() override { source_->request_stop(); }

 private:
  std::unique_ptr<FrameSource> source_;
  std::optional<std::uint64_t> max_frames_;
  std::optional<double> max_seconds_;
  std::optional<Clock::time_point> started_;
  std::uint64_t delivered_ = 0;
};

// Several sources are all cloud files or folders: a URI or a recording stands alone.
void check_alone(const std::vector<std::string>& specs) {
  for (const std::string& spec : specs) {
    if (is_uri(spec)) throw Error("a device URI (" + spec + ") must be the only source");
    if (has_extension(spec, ".oni")) throw Error("an .oni recording (" + spec + ") must be the only source");
  }
}

}  // namespace

SourceKind source_kind(const std::vector<std::string>& specs) {
  if (specs.empty()) throw Error("no source given (an .oni file, a device URI, or .pcd/.ply files or folders)");
  if (specs.size() > 1) {
    check_alone(specs);
  } else if (is_uri(specs.front())) {
    return SourceKind::device;
  } else if (has_extension(specs.front(), ".oni")) {
    return SourceKind::recording;
  }
  for (const std::string& spec : specs) {
    std::error_code error;
    if (!fs::exists(spec, error)) throw Error("cannot open " + spec + ": no such file");
    if (!fs::is_directory(spec, error) && !has_extension(spec, ".pcd") && !has_extension(spec, ".ply")) {
      throw Error(spec + " is not a source: expected an .oni recording, a .pcd or .ply cloud, a folder of clouds or a "
                         "device URI");
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

std::unique_ptr<FrameSource> open_frame_source(const std::vector<std::string>& specs, const SourceOptions& options) {
  const SourceKind kind = source_kind(specs);
  if (kind == SourceKind::device) {
    LiveOptions live;
    live.uri = specs.front();
    live.max_frames = options.max_frames;
    live.max_seconds = options.max_seconds;
    return open_device(live);
  }
  if (kind == SourceKind::recording) {
    ReplayOptions replay;
    replay.realtime = options.realtime;
    replay.max_frames = options.max_frames;
    std::unique_ptr<FrameSource> recording = open_recording(specs.front(), replay);
    if (!options.max_seconds) return recording;
    return std::make_unique<LimitedSource>(std::move(recording), std::nullopt, options.max_seconds);
  }
  if (options.realtime) throw Error("--realtime needs an .oni recording: cloud files have no timestamps");
  const std::vector<fs::path> paths(specs.begin(), specs.end());
  return std::make_unique<LimitedSource>(open_cloud_files(paths), options.max_frames, options.max_seconds);
}

}  // namespace lccp::app
