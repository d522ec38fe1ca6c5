#pragma once
// Reading clouds (PCD, PLY through PCL io) and writing labelled outputs.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>

#include "lccp/cloud.hpp"

namespace lccp {

struct LabelledCloud {
  PointCloud cloud;
  std::optional<Labels> labels;  // the file's `label` field, if it has one
};

// Reads .pcd (ascii, binary, binary_compressed) or .ply. Fields are found by
// name: x y z required; rgb or rgba, normal_x/y/z and label optional, in any
// order. Throws lccp::Error with one line naming the file and the problem
// (missing, unreadable, not a point cloud, truncated, no x/y/z fields).
LabelledCloud read_cloud(const std::filesystem::path& path);

// Writes x y z [rgb] label as a binary PCD, organized layout kept. The file
// appears only when complete (written beside it, then renamed).
void write_labelled_pcd(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels);

// Writes a width x height RGB PNG: a distinct colour per label, black for label 0.
// Throws lccp::Error for an unorganized cloud. Appears only when complete.
void write_label_png(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels);

// The colour of a label in label images: black for 0, otherwise a fixed,
// well-spread colour per label.
std::array<std::uint8_t, 3> label_color(std::uint32_t label);

}  // namespace lccp
