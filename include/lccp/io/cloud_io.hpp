#pragma once
// Reading clouds (PCD, PLY) and writing labelled outputs (PCD, PNG). The
// readers are our own (no PCL): every size in a file is checked against the
// file's length and against ReadLimits before anything is allocated.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "lccp/cloud.hpp"

namespace lccp {

struct LabelledCloud {
  PointCloud cloud;
  std::optional<Labels> labels;  // the file's `label` field, if it has one
};

// Upper bounds a file must respect to be read at all; larger files are
// rejected with lccp::Error before their data is decoded.
struct ReadLimits {
  // Points in one cloud (PCD POINTS, PLY vertex count), checked before any
  // point is decoded. The default, 50 million, is 160 Kinect frames of
  // 640x480; the decoded cloud then takes 1 to 1.6 GB (20 to 32 bytes a
  // point: position, colour, label, normal).
  std::uint64_t max_points = 50'000'000;
  // Bytes of one file, checked by read_cloud before it reads the file.
  std::uint64_t max_file_bytes = std::uint64_t{4} << 30;  // 4 GiB
};

// Reads a regular .pcd (DATA ascii, binary or binary_compressed) or .ply
// (ascii, binary_little_endian, binary_big_endian) file; the extension picks
// the format. Fields are found by name: x y z required; rgb or rgba (PLY also
// red/green/blue), normal_x/y/z (PLY also nx/ny/nz) and label optional, in any
// order. Throws lccp::Error with one line "PATH: problem" (missing, a
// directory or other non-regular file, too large, not a point cloud,
// inconsistent header, truncated or corrupt data, no x/y/z fields).
LabelledCloud read_cloud(const std::filesystem::path& path, const ReadLimits& limits = {});

// The parsers behind read_cloud, on bytes in memory (for fuzzing and tests).
// `name` is the file name used in error messages. Same checks and errors.
LabelledCloud parse_pcd(std::span<const std::uint8_t> bytes, std::string_view name, const ReadLimits& limits = {});
LabelledCloud parse_ply(std::span<const std::uint8_t> bytes, std::string_view name, const ReadLimits& limits = {});

// A binary PCD of x y z [rgb] label (the header PCL's PCDWriter::writeBinary
// writes for these fields), organized layout kept. Throws lccp::Error if the
// labels, colours or width x height do not match the points, or there are none.
std::vector<std::uint8_t> encode_labelled_pcd(const PointCloud& cloud, const Labels& labels);

// A width x height 8-bit RGB PNG: label_color per label, black for label 0.
// Throws lccp::Error for an unorganized cloud or mismatched labels.
std::vector<std::uint8_t> encode_label_png(const PointCloud& cloud, const Labels& labels);

// encode_labelled_pcd / encode_label_png written with write_file_atomically
// (lccp/io/atomic_file.hpp): the file appears only when complete. Errors
// name the path.
void write_labelled_pcd(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels);
void write_label_png(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels);

// The colour of a label in label images: black for 0, otherwise a fixed,
// well-spread colour per label.
std::array<std::uint8_t, 3> label_color(std::uint32_t label);

}  // namespace lccp
