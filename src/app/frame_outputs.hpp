#pragma once
// Per-frame outputs of a stream run: labelled PCD / PLY, colour label PNG and
// per-segment geometry (JSON) in a folder.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "lccp/io/atomic_file.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/pipeline/pipeline.hpp"

namespace lccp::app {

struct FrameOutputOptions {
  std::string directory;                 // empty: no per-frame outputs
  std::vector<std::string> save{"png"};  // any of pcd, ply, png, segments
  bool overlay = false;                  // label images over the shaded depth image
  std::string pcd_data = "binary_compressed";
  CLI::Option* save_option = nullptr;    // to tell a given --save from the default

  // -o, --save, --overlay, --pcd-data; `default_save` is --save's default.
  void add_to(CLI::App& command, std::vector<std::string> default_save = {"png"});
  // Throws UsageError for --save without -o (the outputs would go nowhere).
  void check() const;
  bool saves(const std::string& kind) const;
  PcdEncoding pcd_encoding() const;
  LabelImageStyle image_style() const;
};

// --save's help: the kinds, and that the default applies with -o only.
std::string save_help(const std::vector<std::string>& default_save);

// Output name of a frame: frame_<index>_<timestamp>us, or the source file's stem.
std::string frame_output_stem(const Frame& frame);

// Where one frame's outputs go; an empty path (or no cloud path) is not written.
struct FramePaths {
  std::string png;                  // label image
  std::string segments;             // per-segment geometry (JSON)
  std::vector<std::string> clouds;  // labelled clouds, each .pcd or .ply by its extension
};

// The one list of a frame's output files, in the order write_files_together
// names them: image, segments, then the labelled clouds, so a frame whose
// cloud exists has all its outputs. Throws lccp::Error for a cloud path that
// is neither .pcd nor .ply.
std::vector<FileBytes> frame_files(const PointCloud& cloud, const SceneSegmentation& scene, std::uint64_t index,
                                   std::uint64_t timestamp_us, const FramePaths& paths,
                                   const FrameOutputOptions& options);

// Writes the selected outputs of each finished frame into the folder (created
// if missing); a frame's files appear together. A frame that failed leaves no
// file (its error is reported, stream_run.cpp). Throws lccp::Error when two
// frames would get the same name (two input files of one stem).
class FrameWriter {
 public:
  explicit FrameWriter(const FrameOutputOptions& options);
  void write(const FrameResult& result);

 private:
  FramePaths paths(const FrameResult& result, const std::string& stem) const;

  FrameOutputOptions options_;
  std::filesystem::path directory_;
  std::set<std::string> input_stems_;  // names taken from input files
};

}  // namespace lccp::app
