#pragma once
// Reading clouds (PCD, PLY) and writing labelled outputs (PCD, PLY, PNG). The
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
  std::optional<Labels> labels;   // the file's `label` field, if it has one
  std::optional<Labels> objects;  // its `object` field (a two-level result's objects), if it has one
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

// How a labelled PCD stores its points (PCD v0.7 DATA kinds, as PCL's
// PCDWriter writes them): `binary` one point after another (writeBinary),
// `binary_compressed` one LZF-compressed array per field (writeBinaryCompressed).
enum class PcdEncoding { binary, binary_compressed };

// A PCD of x y z [rgb] label [object] (float metres; rgb the float holding
// 0xFFRRGGBB, as PCL's PointXYZRGB; uint32 label and object), organized
// layout kept, with the header PCL's PCDWriter writes for these fields.
// `label` is the finest level (a part's id with two levels), so tools that
// read PCL's `label` field see the segments; `object`, written when `objects`
// is given (SceneSegmentation::objects: the id of each point's object), is one
// more uint32 field (PCD v0.7 allows any field name). The files the tool
// writes are binary_compressed (encode_labelled_cloud's default, --pcd-data);
// this function defaults to `binary`. Throws lccp::Error if the labels, objects,
// colours or width x height do not match the points, or there are none, or
// (binary_compressed) the data exceeds PCL's limit of 2863311530 bytes (its
// two uint32 sizes must hold 3/2 of it).
std::vector<std::uint8_t> encode_labelled_pcd(const PointCloud& cloud, const Labels& labels,
                                              PcdEncoding encoding = PcdEncoding::binary,
                                              const Labels* objects = nullptr);

// A binary_little_endian 1.0 PLY: one `vertex` element of x y z (float,
// metres; NaN points written as NaN, so there is a vertex per point), red
// green blue (uchar, if the cloud has colours), label (uint) and, with
// `objects`, object (uint: the id of each point's object), then PCL's
// PLYWriter `face` (empty) and `camera` elements, whose viewportx/viewporty
// keep width and height. Throws lccp::Error as encode_labelled_pcd, or if
// width or height exceed 2^31 - 1 (the camera's int fields).
std::vector<std::uint8_t> encode_labelled_ply(const PointCloud& cloud, const Labels& labels,
                                              const Labels* objects = nullptr);

// encode_labelled_pcd or encode_labelled_ply by the extension of
// `path_for_extension` (.pcd or .ply, any case); `encoding` applies to PCD.
// Throws lccp::Error with one line "PATH: problem": "unknown output format
// 'EXT' (use .pcd or .ply)" for any other extension, or an encoder's error.
std::vector<std::uint8_t> encode_labelled_cloud(const std::filesystem::path& path_for_extension,
                                                const PointCloud& cloud, const Labels& labels,
                                                PcdEncoding encoding = PcdEncoding::binary_compressed,
                                                const Labels* objects = nullptr);

// What a label image shows. labels: label_color per point (black for label
// 0). overlay: the scene as a grey rendering of its surface (Lambert shading
// with the light at the camera, normals from neighbouring pixels' points;
// src/io/label_image.cpp), each labelled point's pixel blended half and half
// with its colour; label-0 points grey, NaN points black.
enum class LabelImageStyle { labels, overlay };

// A width x height 8-bit RGB PNG of the labels, one pixel per point. With
// `objects` (per point the id of its object, as SceneSegmentation::objects)
// each point is coloured part_color(object, label): an object's parts have
// hues of their own near its hue; without it each point is label_color(label).
// Throws lccp::Error for an unorganized cloud or mismatched labels or objects.
std::vector<std::uint8_t> encode_label_png(const PointCloud& cloud, const Labels& labels,
                                           LabelImageStyle style = LabelImageStyle::labels,
                                           const Labels* objects = nullptr);

// The colours of a label image in the `labels` style, one RGB per label in
// point order (the pixels encode_label_png writes): label_color, or with
// `objects` part_color. Throws lccp::Error if objects and labels differ in number.
std::vector<std::array<std::uint8_t, 3>> label_rgb(const Labels& labels, const Labels* objects = nullptr);

// The encoders above written with write_file_atomically
// (lccp/io/atomic_file.hpp): the file appears only when complete. Errors
// name the path.
void write_labelled_pcd(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels,
                        PcdEncoding encoding = PcdEncoding::binary, const Labels* objects = nullptr);
void write_labelled_ply(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels,
                        const Labels* objects = nullptr);
void write_labelled_cloud(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels,
                          PcdEncoding encoding = PcdEncoding::binary_compressed, const Labels* objects = nullptr);
void write_label_png(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels,
                     LabelImageStyle style = LabelImageStyle::labels, const Labels* objects = nullptr);

// The colour of a label in label images: black for 0, otherwise a fixed,
// well-spread colour per label.
std::array<std::uint8_t, 3> label_color(std::uint32_t label);

// The colour of part `part` of object `object` in label images with objects:
// a hue of its own within 60 deg of the object's hue (label_color(object)'s),
// consecutive part ids 46 deg or more apart, one of three lightness levels,
// never black or white (src/io/label_image.cpp argues the choice). Black for
// part 0; label_color(part) where the
// part is no object's (object 0) or is the object itself (the support plane,
// whose part and object ids are the same).
std::array<std::uint8_t, 3> part_color(std::uint32_t object, std::uint32_t part);

}  // namespace lccp
