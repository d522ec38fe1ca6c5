#include "frame_outputs.hpp"

#include <algorithm>
#include <cstdio>

#include "commands.hpp"
#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"
#include "lccp/io/segments_json.hpp"

namespace lccp::app {

std::string save_help(const std::vector<std::string>& default_save) {
  std::string defaults;
  for (const std::string& kind : default_save) defaults += (defaults.empty() ? "" : ",") + kind;
  // No "=png" after the option: without -o nothing is written, whatever the default.
  return "per-frame outputs in the -o folder (with -o, default " + defaults +
         "): pcd, ply (labelled clouds), png (label image), segments (per-segment geometry, JSON)";
}

void FrameOutputOptions::add_to(CLI::App& command, std::vector<std::string> default_save) {
  save = std::move(default_save);
  command.add_option("-o,--output-dir", directory, "folder for per-frame outputs and summary.json (created if missing)");
  save_option = command.add_option("--save", save, save_help(save))
                    ->delimiter(',')
                    ->check(CLI::IsMember({"pcd", "ply", "png", "segments"}));
  command.add_flag("--overlay", overlay, "label images over the shaded depth image, so the scene shows");
  command.add_option("--pcd-data", pcd_data, "PCD encoding: binary_compressed or binary")
      ->check(CLI::IsMember({"binary_compressed", "binary"}))
      ->capture_default_str();
}

void FrameOutputOptions::check() const {
  if (directory.empty() && save_option != nullptr && save_option->count() > 0) {
    throw UsageError("--save needs -o DIR, the folder the per-frame outputs go to");
  }
}

bool FrameOutputOptions::saves(const std::string& kind) const {
  return std::find(save.begin(), save.end(), kind) != save.end();
}

PcdEncoding FrameOutputOptions::pcd_encoding() const {
  return pcd_data == "binary" ? PcdEncoding::binary : PcdEncoding::binary_compressed;
}

LabelImageStyle FrameOutputOptions::image_style() const {
  return overlay ? LabelImageStyle::overlay : LabelImageStyle::labels;
}

std::string frame_output_stem(const Frame& frame) {
  if (!frame.name.empty()) return frame.name;
  char stem[64];
  std::snprintf(stem, sizeof stem, "frame_%06llu_%010lluus", static_cast<unsigned long long>(frame.index),
                static_cast<unsigned long long>(frame.timestamp_us));
  return stem;
}

FrameWriter::FrameWriter(const FrameOutputOptions& options) : options_(options), directory_(options.directory) {
  if (!directory_.empty()) create_output_folder(directory_);
}

void FrameWriter::write(const FrameResult& result) {
  if (directory_.empty() || !result.error.empty()) return;  // a failed frame has no labels to write
  const std::string name = frame_output_stem(result.frame);
  // Frames named after their input file may share a stem (a.pcd in two folders);
  // frame_<index>_... names are unique by the index.
  if (!result.frame.name.empty() && !input_stems_.insert(name).second) {
    throw Error("two inputs named " + name + ": their outputs would overwrite each other");
  }
  const FramePaths where = paths(result, (directory_ / name).string());
  write_files_together(frame_files(result.frame.cloud, result.segmentation, result.frame.index,
                                   result.frame.timestamp_us, where, options_));
}

FramePaths FrameWriter::paths(const FrameResult& result, const std::string& stem) const {
  FramePaths paths;
  if (options_.saves("png") && result.frame.cloud.organized()) paths.png = stem + ".png";
  if (options_.saves("segments")) paths.segments = stem + ".segments.json";
  for (const char* kind : {"ply", "pcd"}) {
    if (options_.saves(kind)) paths.clouds.push_back(stem + "." + kind);
  }
  return paths;
}

std::vector<FileBytes> frame_files(const PointCloud& cloud, const SceneSegmentation& scene, std::uint64_t index,
                                   std::uint64_t timestamp_us, const FramePaths& paths,
                                   const FrameOutputOptions& options) {
  const Labels* objects = scene.objects.size() == cloud.size() ? &scene.objects : nullptr;
  std::vector<FileBytes> files;
  if (!paths.png.empty()) {
    files.push_back({paths.png, encode_label_png(cloud, scene.labels, options.image_style(), objects)});
  }
  if (!paths.segments.empty()) {
    const std::string json = encode_segments_json(index, timestamp_us, scene);
    files.push_back({paths.segments, std::vector<std::uint8_t>(json.begin(), json.end())});
  }
  for (const std::string& path : paths.clouds) {
    files.push_back({path, encode_labelled_cloud(path, cloud, scene.labels, options.pcd_encoding(), objects)});
  }
  return files;
}

}  // namespace lccp::app
