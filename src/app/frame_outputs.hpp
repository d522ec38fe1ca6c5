#pragma once
// Per-frame outputs of a stream run: labelled PCD and/or colour label PNG in a folder.
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "lccp/pipeline/pipeline.hpp"

namespace lccp::app {

struct FrameOutputOptions {
  std::string directory;          // empty: no per-frame outputs
  std::vector<std::string> save{"png"};  // any of pcd, png

  void add_to(CLI::App& command);
  bool pcd() const;
  bool png() const;
};

// Output name of a frame: frame_<index>_<timestamp>us, or the source file's stem.
std::string frame_output_stem(const Frame& frame);

// Writes the selected outputs of each finished frame into the directory
// (created if missing). A frame without labels (it failed) is written with label 0.
class FrameWriter {
 public:
  explicit FrameWriter(const FrameOutputOptions& options);
  void write(const FrameResult& result);
  std::uint64_t frames_written() const { return frames_written_; }

 private:
  FrameOutputOptions options_;
  std::filesystem::path directory_;
  std::uint64_t frames_written_ = 0;
};

}  // namespace lccp::app
