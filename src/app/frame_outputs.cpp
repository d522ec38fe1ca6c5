#include "frame_outputs.hpp"

#include <algorithm>
#include <cstdio>

#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"
#include "lccp/io/cloud_io.hpp"

namespace lccp::app {
namespace {

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

}  // namespace

void FrameOutputOptions::add_to(CLI::App& command) {
  command.add_option("-o,--output-dir", directory, "folder for per-frame outputs and summary.json (created if missing)");
  command.add_option("--save", save, "per-frame outputs: pcd (labelled cloud), png (label image), or both")
      ->delimiter(',')
      ->check(CLI::IsMember({"pcd", "png"}))
      ->capture_default_str();
}

bool FrameOutputOptions::pcd() const { return contains(save, "pcd"); }
bool FrameOutputOptions::png() const { return contains(save, "png"); }

std::string frame_output_stem(const Frame& frame) {
  if (!frame.name.empty()) return frame.name;
  char stem[64];
  std::snprintf(stem, sizeof stem, "frame_%06llu_%010lluus", static_cast<unsigned long long>(frame.index),
                static_cast<unsigned long long>(frame.timestamp_us));
  return stem;
}

FrameWriter::FrameWriter(const FrameOutputOptions& options) : options_(options), directory_(options.directory) {
  if (directory_.empty()) return;
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (!std::filesystem::is_directory(directory_)) throw Error("cannot create output folder " + directory_.string());
}

void FrameWriter::write(const FrameResult& result) {
  if (directory_.empty()) return;
  const PointCloud& cloud = result.frame.cloud;
  const Labels no_labels(cloud.size(), 0);
  const Labels& labels = result.segmentation.labels.size() == cloud.size() ? result.segmentation.labels : no_labels;
  const std::string stem = (directory_ / frame_output_stem(result.frame)).string();
  std::vector<FileBytes> files;
  if (options_.pcd()) files.push_back({stem + ".pcd", encode_labelled_pcd(cloud, labels)});
  if (options_.png() && cloud.organized()) files.push_back({stem + ".png", encode_label_png(cloud, labels)});
  write_files_together(files);  // a frame's outputs appear together or not at all
  ++frames_written_;
}

}  // namespace lccp::app
