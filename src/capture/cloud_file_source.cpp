#include <algorithm>

#include "lccp/capture/cloud_files.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"

namespace lccp {
namespace {

bool is_cloud_file(const std::filesystem::path& path) {
  return path.extension() == ".pcd" || path.extension() == ".ply";
}

std::vector<std::filesystem::path> expand(const std::vector<std::filesystem::path>& paths) {
  std::vector<std::filesystem::path> files;
  for (const auto& path : paths) {
    std::error_code error;
    if (!std::filesystem::exists(path, error)) throw Error("cannot open " + path.string() + ": no such file");
    if (!std::filesystem::is_directory(path, error)) {
      files.push_back(path);
      continue;
    }
    std::vector<std::filesystem::path> in_directory;
    for (const auto& entry : std::filesystem::directory_iterator(path)) {
      if (entry.is_regular_file() && is_cloud_file(entry.path())) in_directory.push_back(entry.path());
    }
    if (in_directory.empty()) throw Error("directory " + path.string() + " holds no .pcd or .ply file");
    std::sort(in_directory.begin(), in_directory.end());
    files.insert(files.end(), in_directory.begin(), in_directory.end());
  }
  if (files.empty()) throw Error("no point cloud files given");
  return files;
}

class CloudFileSource final : public FrameSource {
 public:
  explicit CloudFileSource(std::vector<std::filesystem::path> files) : files_(std::move(files)) {}

  std::optional<Frame> next(std::stop_token stop) override {
    if (stop.stop_requested() || next_ >= files_.size()) return std::nullopt;
    Frame frame;
    frame.index = next_;
    frame.name = files_[next_].stem().string();
    frame.file = files_[next_].string();
    frame.cloud = read_cloud(files_[next_]).cloud;
    frame.captured = Clock::now();
    ++next_;
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override { return files_.size(); }
  bool is_live() const override { return false; }
  bool is_stream() const override { return false; }  // unrelated clouds: ids 1..K each

 private:
  std::vector<std::filesystem::path> files_;
  std::size_t next_ = 0;
};

}  // namespace

std::unique_ptr<FrameSource> open_cloud_files(const std::vector<std::filesystem::path>& paths) {
  return std::make_unique<CloudFileSource>(expand(paths));
}

}  // namespace lccp
