#pragma once
// Point cloud files (PCD, PLY) as a stream of frames.
#include <filesystem>
#include <memory>
#include <vector>

#include "lccp/frame_source.hpp"

namespace lccp {

// The given files in order; a directory stands for its .pcd and .ply files
// sorted by name. Each file is read when its frame is pulled (a bad file throws
// lccp::Error naming it). Frame::name is the file's stem. Throws lccp::Error
// for a missing path or a directory without clouds.
std::unique_ptr<FrameSource> open_cloud_files(const std::vector<std::filesystem::path>& paths);

}  // namespace lccp
