// Tests for the labelled-cloud writers of lccp/io/cloud_io.hpp: compressed
// PCD (and the LZF compressor behind it), PLY, the choice by extension, the
// object field of two-level outputs, and the label images (overlay, objects).
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../src/io/lzf.hpp"
#include "expect_error.hpp"
#include "test_files.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;
using test::expect_lccp_error;

const fs::path kData = LCCP_TEST_DATA_DIR;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

fs::path scratch_dir() { return test::scratch_dir("lccp_io_writers"); }

Bytes to_bytes(const std::string& text) { return {text.begin(), text.end()}; }
std::string as_text(const Bytes& bytes) { return {bytes.begin(), bytes.end()}; }

template <typename T>
T load(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

// An organized width x height cloud: NaN holes where (i % 7 == 3 or a
// 3-pixel band of rows), the rest a tilted plane; labels 1 + i % 9, 0 for NaN.
PointCloud organized_cloud(std::uint32_t width, std::uint32_t height, bool colors) {
  PointCloud cloud;
  cloud.width = width;
  cloud.height = height;
  for (std::uint32_t i = 0; i < width * height; ++i) {
    const std::uint32_t x = i % width, y = i / width;
    const bool hole = i % 7 == 3 || (y >= height / 2 && y < height / 2 + 3);
    cloud.points.push_back(hole ? Eigen::Vector3f(kNaN, kNaN, kNaN)
                                : Eigen::Vector3f(0.002f * x - 0.6f, 0.002f * y - 0.45f, 1.0f + 0.0005f * x));
    if (colors) cloud.colors.push_back((i * 0x0A1B2Cu + 0x30405u) & 0xFFFFFFu);
  }
  return cloud;
}

Labels labels_for(const PointCloud& cloud) {
  Labels labels;
  for (std::size_t i = 0; i < cloud.size(); ++i) labels.push_back(is_finite(cloud.points[i]) ? 1 + i % 9 : 0);
  return labels;
}

// Object ids for labels_for's parts: parts 1-3 form object 21, 4-6 object 22,
// 8-9 object 23; 7 is the support (object and part 7, as SceneSegmentation
// gives it); 0 for 0.
Labels objects_for(const Labels& labels) {
  Labels objects;
  for (const std::uint32_t label : labels) objects.push_back(label == 0 || label == 7 ? label : 21 + (label - 1) / 3);
  return objects;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_cloud(const LabelledCloud& in, const PointCloud& cloud, const Labels& labels) {
  EXPECT_EQ(in.cloud.width, cloud.width);
  EXPECT_EQ(in.cloud.height, cloud.height);
  ASSERT_EQ(in.cloud.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_TRUE(same_bits(in.cloud.points[i][k], cloud.points[i][k])) << "point " << i << " axis " << k;
  EXPECT_EQ(in.cloud.colors, cloud.colors);
  ASSERT_TRUE(in.labels.has_value());
  EXPECT_EQ(*in.labels, labels);
}

// The byte after "DATA ...\n" (PCD) or "end_header\n" (PLY).
std::size_t data_start(const std::string& bytes, const std::string& last_line) {
  const std::size_t at = bytes.find(last_line);
  EXPECT_NE(at, std::string::npos) << last_line;
  return at == std::string::npos ? bytes.size() : at + last_line.size();
}

// ------------------------------------------------------------------- LZF

Bytes round_trip_lzf(const Bytes& raw) {
  const Bytes packed = io_detail::lzf_compress(raw);
  EXPECT_LE(packed.size(), raw.size() + (raw.size() + 31) / 32);
  Bytes out(raw.size());
  const char* problem = io_detail::lzf_decompress(packed, out);
  EXPECT_EQ(problem, nullptr) << problem;
  return out;
}

TEST(IoWriterLzf, CompressedStreamsExpandToTheirInput) {
  std::mt19937 random(7);
  std::vector<Bytes> inputs = {{}, {1}, {1, 2}, {5, 5, 5}, Bytes(100000, 0), to_bytes("abcabcabcabcabcabcxyz")};
  Bytes noise(70000);
  for (auto& byte : noise) byte = static_cast<std::uint8_t>(random());
  inputs.push_back(noise);
  for (const std::size_t period : {8191, 8192, 8193}) {  // repeats at and just beyond the farthest reach
    Bytes repeat(3 * period);
    for (std::size_t i = 0; i < repeat.size(); ++i) repeat[i] = noise[i % period];
    inputs.push_back(repeat);
  }
  Bytes mixed;  // short and long matches, literals in between
  for (int k = 0; k < 5000; ++k) {
    const std::size_t run = random() % 300;
    mixed.insert(mixed.end(), run, static_cast<std::uint8_t>(random() % 4));
    mixed.push_back(static_cast<std::uint8_t>(random()));
  }
  inputs.push_back(mixed);
  for (const Bytes& raw : inputs) {
    SCOPED_TRACE("input of " + std::to_string(raw.size()) + " bytes");
    EXPECT_EQ(round_trip_lzf(raw), raw);
  }
  EXPECT_LT(io_detail::lzf_compress(Bytes(100000, 0)).size(), 100000u / 80);  // 264-byte references
  Bytes repeat(3 * 8192);
  for (std::size_t i = 0; i < repeat.size(); ++i) repeat[i] = noise[i % 8192];
  EXPECT_LT(io_detail::lzf_compress(repeat).size(), 8192u * 12 / 10);  // the copies 8192 back are found
}

// --------------------------------------------------------- compressed PCD

// The LZF section after a DATA binary_compressed line, expanded.
Bytes expand_compressed(const std::string& bytes, std::size_t data, std::uint32_t expected_raw) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(bytes.data()) + data;
  const auto compressed = load<std::uint32_t>(p), raw = load<std::uint32_t>(p + 4);
  EXPECT_EQ(raw, expected_raw);
  EXPECT_LE(data + 8 + compressed, bytes.size());
  Bytes out(raw);
  const char* problem = io_detail::lzf_decompress({p + 8, compressed}, out);
  EXPECT_EQ(problem, nullptr) << problem;
  return out;
}

TEST(IoWriterPcd, PclCompressedFixtureHasTheLayoutWeWrite) {
  // PCL 1.13's writeBinaryCompressed output (tests/data/formats/README.md):
  // after DATA, two uint32 sizes, then one array per field: 6 x, 6 x 5
  // histogram, 6 y, 6 z, 6 uint16 labels (the `_` padding is not stored).
  const std::string pcl = test::read_bytes(kData / "formats" / "pcl_count5_compressed.pcd");
  const Bytes raw = expand_compressed(pcl, data_start(pcl, "DATA binary_compressed\n"), 6 * (4 + 20 + 4 + 4 + 2));
  ASSERT_EQ(raw.size(), 204u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(load<float>(&raw[4 * i]), 1.5f * i);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(load<float>(&raw[24 + 20 * i + 4 * k]), 100.0f * i + k);
    EXPECT_EQ(load<float>(&raw[144 + 4 * i]), -2.0f * i);
    EXPECT_EQ(load<float>(&raw[168 + 4 * i]), 3.0f + i);
    EXPECT_EQ(load<std::uint16_t>(&raw[192 + 2 * i]), 1000 * i + 7);
  }
}

TEST(IoWriterPcd, CompressedIsBinaryHeaderAndFieldArrays) {
  for (const bool colors : {true, false}) {
    SCOPED_TRACE(colors ? "colours" : "no colours");
    const PointCloud cloud = organized_cloud(5, 4, colors);
    const Labels labels = labels_for(cloud);
    const std::string binary = as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary));
    const std::string compressed = as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary_compressed));
    const std::size_t binary_data = data_start(binary, "DATA binary\n");
    const std::size_t data = data_start(compressed, "DATA binary_compressed\n");
    EXPECT_EQ(compressed.substr(0, data), binary.substr(0, binary_data - 12) + "DATA binary_compressed\n");
    const std::size_t fields = colors ? 5 : 4, n = cloud.size();
    const Bytes raw = expand_compressed(compressed, data, static_cast<std::uint32_t>(4 * fields * n));
    EXPECT_EQ(data + 8 + load<std::uint32_t>(reinterpret_cast<const std::uint8_t*>(compressed.data()) + data),
              compressed.size());  // nothing after the stream
    for (std::size_t i = 0; i < n; ++i)  // field f of point i: binary record i, compressed array f
      for (std::size_t f = 0; f < fields; ++f)
        ASSERT_EQ(std::memcmp(&raw[4 * (f * n + i)], binary.data() + binary_data + 4 * (fields * i + f), 4), 0)
            << "point " << i << " field " << f;
  }
}

TEST(IoWriterPcd, BinaryStaysTheDefault) {
  const PointCloud cloud = organized_cloud(6, 3, true);
  const Labels labels = labels_for(cloud);
  EXPECT_EQ(encode_labelled_pcd(cloud, labels), encode_labelled_pcd(cloud, labels, PcdEncoding::binary));
  const fs::path path = scratch_dir() / "default.pcd";
  write_labelled_pcd(path, cloud, labels);
  EXPECT_EQ(test::read_bytes(path), as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary)));
}

TEST(IoWriterPcd, CompressedRoundTripOf640x480WithNans) {
  for (const bool colors : {true, false}) {
    SCOPED_TRACE(colors ? "colours" : "no colours");
    PointCloud cloud = organized_cloud(640, 480, colors);
    cloud.points[1] = Eigen::Vector3f(-0.0f, std::numeric_limits<float>::infinity(), 1e-40f);  // bits kept
    Labels labels = labels_for(cloud);
    labels[2] = 0xFFFFFFFFu;
    const Bytes bytes = encode_labelled_pcd(cloud, labels, PcdEncoding::binary_compressed);
    expect_same_cloud(parse_pcd(bytes, "mem.pcd"), cloud, labels);
    const fs::path path = scratch_dir() / "frame.pcd";
    write_labelled_pcd(path, cloud, labels, PcdEncoding::binary_compressed);
    expect_same_cloud(read_cloud(path), cloud, labels);
  }
}

// Point i's uint32 in 4-byte field f of a PCD's DATA binary records of `fields` fields.
std::uint32_t binary_field(const std::string& pcd, std::size_t fields, std::size_t i, std::size_t f) {
  const std::size_t data = data_start(pcd, "DATA binary\n");
  return load<std::uint32_t>(reinterpret_cast<const std::uint8_t*>(pcd.data()) + data + 4 * (fields * i + f));
}

TEST(IoWriterPcd, ObjectFieldFollowsLabelInBothEncodings) {
  for (const bool colors : {true, false}) {
    SCOPED_TRACE(colors ? "colours" : "no colours");
    const PointCloud cloud = organized_cloud(9, 7, colors);
    const Labels labels = labels_for(cloud), objects = objects_for(labels);
    const std::size_t fields = colors ? 6 : 5, n = cloud.size();
    const std::string header = colors ? "FIELDS x y z rgb label object\nSIZE 4 4 4 4 4 4\nTYPE F F F F U U\n"
                                        "COUNT 1 1 1 1 1 1\nWIDTH 9\nHEIGHT 7\n"
                                      : "FIELDS x y z label object\nSIZE 4 4 4 4 4\nTYPE F F F U U\n"
                                        "COUNT 1 1 1 1 1\nWIDTH 9\nHEIGHT 7\n";
    const std::string binary = as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary, &objects));
    const std::string compressed =
        as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary_compressed, &objects));
    EXPECT_NE(binary.find("VERSION 0.7\n" + header), std::string::npos) << binary.substr(0, 300);
    EXPECT_NE(compressed.find("VERSION 0.7\n" + header), std::string::npos);
    const std::size_t data = data_start(compressed, "DATA binary_compressed\n");
    const Bytes raw = expand_compressed(compressed, data, static_cast<std::uint32_t>(4 * fields * n));
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(binary_field(binary, fields, i, fields - 2), labels[i]) << "point " << i;
      ASSERT_EQ(binary_field(binary, fields, i, fields - 1), objects[i]) << "point " << i;
      ASSERT_EQ(load<std::uint32_t>(&raw[4 * ((fields - 2) * n + i)]), labels[i]) << "point " << i;
      ASSERT_EQ(load<std::uint32_t>(&raw[4 * ((fields - 1) * n + i)]), objects[i]) << "point " << i;
    }
    EXPECT_EQ(binary.size(), data_start(binary, "DATA binary\n") + 4 * fields * n);
    expect_same_cloud(parse_pcd(to_bytes(binary), "mem.pcd"), cloud, labels);  // `object` is one more field
    expect_same_cloud(parse_pcd(to_bytes(compressed), "mem.pcd"), cloud, labels);
  }
}

TEST(IoWriterPcd, WithoutObjectsTheBytesAreAsBefore) {
  const PointCloud cloud = organized_cloud(6, 4, true);
  const Labels labels = labels_for(cloud), objects = objects_for(labels);
  for (const PcdEncoding encoding : {PcdEncoding::binary, PcdEncoding::binary_compressed}) {
    const Bytes before = encode_labelled_pcd(cloud, labels, encoding);
    EXPECT_EQ(encode_labelled_pcd(cloud, labels, encoding, nullptr), before);
    EXPECT_EQ(as_text(before).find("object"), std::string::npos);
  }
  const Labels short_objects(4, 1);
  expect_lccp_error([&] { encode_labelled_pcd(cloud, labels, PcdEncoding::binary, &short_objects); },
                    {"objects and points differ in number"});
}

TEST(IoWriterPcd, FilesWithObjectsReadBack) {
  const PointCloud cloud = organized_cloud(16, 12, true);
  const Labels labels = labels_for(cloud), objects = objects_for(labels);
  const fs::path dir = scratch_dir();
  write_labelled_pcd(dir / "binary.pcd", cloud, labels, PcdEncoding::binary, &objects);
  write_labelled_pcd(dir / "compressed.pcd", cloud, labels, PcdEncoding::binary_compressed, &objects);
  EXPECT_EQ(test::read_bytes(dir / "binary.pcd"), as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary, &objects)));
  EXPECT_EQ(test::read_bytes(dir / "compressed.pcd"),
            as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary_compressed, &objects)));
  for (const char* name : {"binary.pcd", "compressed.pcd"}) expect_same_cloud(read_cloud(dir / name), cloud, labels);
}

TEST(IoWriterPcd, MosdSceneCompressesBelowSixtyPercent) {
  const LabelledCloud scene = read_cloud(kData / "mosd_test2.pcd");
  ASSERT_TRUE(scene.labels.has_value());
  const Bytes binary = encode_labelled_pcd(scene.cloud, *scene.labels, PcdEncoding::binary);
  const Bytes compressed = encode_labelled_pcd(scene.cloud, *scene.labels, PcdEncoding::binary_compressed);
  const double ratio = static_cast<double>(compressed.size()) / static_cast<double>(binary.size());
  RecordProperty("compressed_bytes", std::to_string(compressed.size()));
  RecordProperty("binary_bytes", std::to_string(binary.size()));
  EXPECT_LT(ratio, 0.6) << compressed.size() << " of " << binary.size() << " bytes";
  expect_same_cloud(parse_pcd(compressed, "mem.pcd"), scene.cloud, *scene.labels);
}

// ------------------------------------------------------------------- PLY

TEST(IoWriterPly, RoundTripKeepsPointsNansColoursLabelsAndShape) {
  for (const bool colors : {true, false}) {
    SCOPED_TRACE(colors ? "colours" : "no colours");
    PointCloud cloud = organized_cloud(7, 5, colors);
    cloud.points[1] = Eigen::Vector3f(-0.0f, std::numeric_limits<float>::infinity(), 1e-40f);
    Labels labels = labels_for(cloud);
    labels[2] = 0xFFFFFFFFu;
    const Bytes bytes = encode_labelled_ply(cloud, labels);
    expect_same_cloud(parse_ply(bytes, "mem.ply"), cloud, labels);
    const std::string text = as_text(bytes);
    const std::string rgb = colors ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "";
    const std::string vertex = "element vertex 35\nproperty float x\nproperty float y\nproperty float z\n" + rgb +
                               "property uint label\nelement face 0\nelement camera 1\n";
    EXPECT_EQ(text.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
    EXPECT_NE(text.find(vertex), std::string::npos) << text.substr(0, 400);
    const std::size_t step = colors ? 19 : 16;
    EXPECT_EQ(text.size(), data_start(text, "end_header\n") + 35 * step + 21 * 4);  // every point, then the camera
  }
}

TEST(IoWriterPly, ObjectPropertyFollowsLabel) {
  for (const bool colors : {true, false}) {
    SCOPED_TRACE(colors ? "colours" : "no colours");
    const PointCloud cloud = organized_cloud(7, 5, colors);
    const Labels labels = labels_for(cloud), objects = objects_for(labels);
    const Bytes bytes = encode_labelled_ply(cloud, labels, &objects);
    const std::string text = as_text(bytes);
    EXPECT_NE(text.find("property uint label\nproperty uint object\nelement face 0\n"), std::string::npos);
    const std::size_t step = colors ? 23 : 20, data = data_start(text, "end_header\n");
    ASSERT_EQ(text.size(), data + 35 * step + 21 * 4);
    for (std::size_t i = 0; i < cloud.size(); ++i) {  // little-endian, as the header says
      const std::uint8_t* record = bytes.data() + data + i * step;
      const std::uint32_t object = record[step - 4] | record[step - 3] << 8 | record[step - 2] << 16 |
                                   std::uint32_t{record[step - 1]} << 24;
      ASSERT_EQ(load<std::uint32_t>(record + step - 8), labels[i]) << "point " << i;
      ASSERT_EQ(object, objects[i]) << "point " << i;
    }
    expect_same_cloud(parse_ply(bytes, "mem.ply"), cloud, labels);
    EXPECT_EQ(encode_labelled_ply(cloud, labels, nullptr), encode_labelled_ply(cloud, labels));
    EXPECT_EQ(as_text(encode_labelled_ply(cloud, labels)).find("object"), std::string::npos);
  }
  const PointCloud cloud = organized_cloud(5, 4, true);
  const Labels labels = labels_for(cloud), objects = objects_for(labels);
  const fs::path path = scratch_dir() / "objects.ply";
  write_labelled_ply(path, cloud, labels, &objects);
  EXPECT_EQ(test::read_bytes(path), as_text(encode_labelled_ply(cloud, labels, &objects)));
  expect_same_cloud(read_cloud(path), cloud, labels);
  const Labels short_objects(4, 1);
  expect_lccp_error([&] { encode_labelled_ply(cloud, labels, &short_objects); },
                    {"objects and points differ in number"});
}

TEST(IoWriterPly, CameraElementIsPlyWritersOwn) {
  // PCL's reader restores width and height from its own camera element; ours
  // declares the same properties in the same order.
  const std::string pcl = test::read_bytes(kData / "formats" / "pcl_normals_binary.ply");
  const std::size_t from = pcl.find("element face 0\n"), to = data_start(pcl, "end_header\n");
  ASSERT_NE(from, std::string::npos);
  const PointCloud cloud = organized_cloud(4, 3, true);
  const std::string ours = as_text(encode_labelled_ply(cloud, labels_for(cloud)));
  const std::size_t our_end = data_start(ours, "end_header\n");
  EXPECT_EQ(ours.substr(0, our_end).substr(ours.find("element face 0\n")), pcl.substr(from, to - from));
  // The camera record: 17 floats (position, identity axes, five zeros), viewport 4 x 3, two zeros.
  const auto* camera = reinterpret_cast<const std::uint8_t*>(ours.data()) + ours.size() - 84;
  const auto* theirs = reinterpret_cast<const std::uint8_t*>(pcl.data()) + pcl.size() - 84;
  EXPECT_EQ(load<std::int32_t>(camera + 68), 4);
  EXPECT_EQ(load<std::int32_t>(camera + 72), 3);
  EXPECT_EQ(std::memcmp(camera, theirs, 84), 0);  // PCL wrote its cloud's 4 x 3 with default pose too
}

// ------------------------------------------------------ choice by extension

TEST(IoWriterCloud, ExtensionPicksTheFormat) {
  const PointCloud cloud = organized_cloud(8, 6, true);
  const Labels labels = labels_for(cloud);
  const fs::path dir = scratch_dir();
  write_labelled_cloud(dir / "a.pcd", cloud, labels);
  write_labelled_cloud(dir / "b.PLY", cloud, labels);
  write_labelled_cloud(dir / "c.Pcd", cloud, labels, PcdEncoding::binary);
  const Bytes compressed = encode_labelled_pcd(cloud, labels, PcdEncoding::binary_compressed);
  EXPECT_EQ(test::read_bytes(dir / "a.pcd"), as_text(compressed));  // compressed unless told otherwise
  EXPECT_EQ(test::read_bytes(dir / "b.PLY"), as_text(encode_labelled_ply(cloud, labels)));
  EXPECT_EQ(test::read_bytes(dir / "c.Pcd"), as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary)));
  EXPECT_EQ(encode_labelled_cloud("x/y.pcd", cloud, labels), compressed);
  EXPECT_EQ(encode_labelled_cloud("y.ply", cloud, labels, PcdEncoding::binary), encode_labelled_ply(cloud, labels));
  for (const char* name : {"a.pcd", "b.PLY", "c.Pcd"}) expect_same_cloud(read_cloud(dir / name), cloud, labels);
}

TEST(IoWriterCloud, ExtensionPicksTheFormatWithObjects) {
  const PointCloud cloud = organized_cloud(8, 6, true);
  const Labels labels = labels_for(cloud), objects = objects_for(labels);
  const fs::path dir = scratch_dir();
  write_labelled_cloud(dir / "a.pcd", cloud, labels, PcdEncoding::binary_compressed, &objects);
  write_labelled_cloud(dir / "b.ply", cloud, labels, PcdEncoding::binary_compressed, &objects);
  write_labelled_cloud(dir / "c.pcd", cloud, labels, PcdEncoding::binary, &objects);
  EXPECT_EQ(test::read_bytes(dir / "a.pcd"),
            as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary_compressed, &objects)));
  EXPECT_EQ(test::read_bytes(dir / "b.ply"), as_text(encode_labelled_ply(cloud, labels, &objects)));
  EXPECT_EQ(test::read_bytes(dir / "c.pcd"), as_text(encode_labelled_pcd(cloud, labels, PcdEncoding::binary, &objects)));
  EXPECT_EQ(encode_labelled_cloud("x.pcd", cloud, labels, PcdEncoding::binary_compressed, nullptr), encode_labelled_cloud("x.pcd", cloud, labels));
  EXPECT_EQ(encode_labelled_cloud("x.ply", cloud, labels, PcdEncoding::binary_compressed, nullptr), encode_labelled_ply(cloud, labels));
  for (const char* name : {"a.pcd", "b.ply", "c.pcd"}) expect_same_cloud(read_cloud(dir / name), cloud, labels);
  write_labelled_cloud(dir / "d.pcd", cloud, labels, PcdEncoding::binary, &objects);
  write_labelled_pcd(dir / "e.pcd", cloud, labels, PcdEncoding::binary, &objects);
  EXPECT_EQ(test::read_bytes(dir / "d.pcd"), test::read_bytes(dir / "c.pcd"));
  EXPECT_EQ(test::read_bytes(dir / "e.pcd"), test::read_bytes(dir / "c.pcd"));
  const Labels short_objects(3, 1);
  expect_lccp_error([&] { write_labelled_cloud(dir / "short.ply", cloud, labels, PcdEncoding::binary_compressed, &short_objects); },
                    {"short.ply: objects and points differ in number"});
  expect_lccp_error([&] { encode_labelled_cloud(dir / "short.pcd", cloud, labels, PcdEncoding::binary_compressed, &short_objects); },
                    {"short.pcd: objects and points differ in number"});
  EXPECT_FALSE(fs::exists(dir / "short.ply"));
}

TEST(IoWriterCloud, UnknownExtensionAndBadInputNameThePath) {
  const PointCloud cloud = organized_cloud(4, 2, false);
  const Labels labels = labels_for(cloud);
  const fs::path dir = scratch_dir();
  using NameAndExtension = std::pair<std::string, std::string>;
  for (const auto& [name, ext] : {NameAndExtension{"out.xyz", ".xyz"}, {"out", ""}, {"out.pcd.gz", ".gz"}}) {
    const fs::path path = dir / name;
    try {
      write_labelled_cloud(path, cloud, labels);
      ADD_FAILURE() << "no lccp::Error for " << name;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), path.string() + ": unknown output format '" + ext + "' (use .pcd or .ply)");
    }
    expect_lccp_error([&] { encode_labelled_cloud(path, cloud, labels); }, {path.string() + ": unknown output format"});
  }
  expect_lccp_error([&] { write_labelled_cloud(dir / "short.ply", cloud, Labels(3, 1)); },
                    {"short.ply: labels and points differ in number"});
  expect_lccp_error([&] { encode_labelled_cloud(dir / "short.pcd", cloud, Labels(3, 1)); },
                    {"short.pcd: labels and points differ in number"});
  expect_lccp_error([&] { write_labelled_ply(dir / "none" / "out.ply", cloud, labels); },
                    {"out.ply", "does not exist"});
  EXPECT_TRUE(fs::is_empty(dir));
}

// ------------------------------------------------------- overlay PNG

struct Image {
  std::uint32_t width = 0, height = 0;
  std::vector<std::array<std::uint8_t, 3>> pixels;
};

std::uint32_t big_endian(const Bytes& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < 4; ++k) value = value << 8 | bytes[at + k];
  return value;
}

// Decodes our PNGs: 8-bit RGB, every row with filter type 0 (checked).
Image decode_png(const Bytes& png) {
  Image image;
  EXPECT_EQ(as_text(Bytes(png.begin(), png.begin() + 8)), std::string("\x89PNG\r\n\x1A\n", 8));
  EXPECT_EQ(as_text(Bytes(png.begin() + 12, png.begin() + 16)), "IHDR");
  image.width = big_endian(png, 16);
  image.height = big_endian(png, 20);
  EXPECT_EQ(png[24], 8);  // bit depth
  EXPECT_EQ(png[25], 2);  // RGB
  Bytes idat;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = big_endian(png, at);
    if (as_text(Bytes(png.begin() + at + 4, png.begin() + at + 8)) == "IDAT")
      idat.insert(idat.end(), png.begin() + at + 8, png.begin() + at + 8 + length);
    at += 12 + length;
  }
  const std::size_t row = 1 + 3 * std::size_t{image.width};
  Bytes raw(row * image.height);
  uLongf size = raw.size();
  EXPECT_EQ(uncompress(raw.data(), &size, idat.data(), idat.size()), Z_OK);
  EXPECT_EQ(size, raw.size());
  for (std::size_t y = 0; y < image.height; ++y) {
    EXPECT_EQ(raw[y * row], 0) << "filter of row " << y;
    for (std::size_t x = 0; x < image.width; ++x)
      image.pixels.push_back({raw[y * row + 1 + 3 * x], raw[y * row + 2 + 3 * x], raw[y * row + 3 + 3 * x]});
  }
  return image;
}

bool is_grey(const std::array<std::uint8_t, 3>& rgb) { return rgb[0] == rgb[1] && rgb[1] == rgb[2]; }

TEST(IoWriterPng, OverlayIsGreySceneBlendedWithLabelColours) {
  const PointCloud cloud = organized_cloud(12, 9, false);
  Labels labels = labels_for(cloud);
  for (std::size_t i = 0; i < labels.size(); i += 4) labels[i] = 0;  // some finite points unlabelled
  const Image image = decode_png(encode_label_png(cloud, labels, LabelImageStyle::overlay));
  ASSERT_EQ(image.width, 12u);
  ASSERT_EQ(image.height, 9u);
  ASSERT_EQ(image.pixels.size(), cloud.size());
  const Image grey = decode_png(encode_label_png(cloud, Labels(cloud.size(), 0), LabelImageStyle::overlay));
  int labelled = 0, unlabelled = 0, holes = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    SCOPED_TRACE("pixel " + std::to_string(i));
    const auto pixel = image.pixels[i];
    if (!is_finite(cloud.points[i])) {
      EXPECT_EQ(pixel, (std::array<std::uint8_t, 3>{0, 0, 0}));
      ++holes;
    } else if (labels[i] == 0) {
      EXPECT_TRUE(is_grey(pixel));
      EXPECT_GT(pixel[0], 0);
      EXPECT_EQ(pixel, grey.pixels[i]);
      ++unlabelled;
    } else {
      const auto color = label_color(labels[i]);
      EXPECT_NE(pixel, color);
      EXPECT_FALSE(is_grey(pixel));
      for (int c = 0; c < 3; ++c) EXPECT_EQ(pixel[c], (grey.pixels[i][c] + color[c] + 1) / 2);  // 50/50
      ++labelled;
    }
  }
  EXPECT_GT(labelled, 0);
  EXPECT_GT(unlabelled, 0);
  EXPECT_GT(holes, 0);
  EXPECT_EQ(encode_label_png(cloud, labels), encode_label_png(cloud, labels, LabelImageStyle::labels));
}

// A width x height plane z = 1 + slope x, seen from the origin.
PointCloud plane(float slope) {
  PointCloud cloud;
  cloud.width = 10;
  cloud.height = 8;
  for (std::uint32_t i = 0; i < 80; ++i) {
    const float x = 0.01f * (i % 10) - 0.05f, y = 0.01f * (i / 10) - 0.04f;
    cloud.points.emplace_back(x, y, 1.0f + slope * x);
  }
  return cloud;
}

TEST(IoWriterPng, ShadingFollowsSurfaceOrientation) {
  const Labels none(80, 0);
  const Image facing = decode_png(encode_label_png(plane(0.0f), none, LabelImageStyle::overlay));
  const Image tilted = decode_png(encode_label_png(plane(2.0f), none, LabelImageStyle::overlay));
  for (std::size_t i = 0; i < 80; ++i) {
    EXPECT_GE(facing.pixels[i][0], 250) << i;                        // |cos| ~ 1
    EXPECT_NEAR(tilted.pixels[i][0], 255 * (0.15 + 0.85 / std::sqrt(5.0)), 15) << i;  // normal (-2, 0, 1)
  }
  const fs::path path = scratch_dir() / "overlay.png";
  const LabelledCloud scene = read_cloud(kData / "mosd_test2.pcd");
  write_label_png(path, scene.cloud, *scene.labels, LabelImageStyle::overlay);
  const Image written = decode_png(to_bytes(test::read_bytes(path)));
  EXPECT_EQ(written.width, 640u);
  EXPECT_EQ(written.height, 480u);
  expect_lccp_error([&] { encode_label_png(organized_cloud(12, 1, false), Labels(12, 0), LabelImageStyle::overlay); },
                    {"a label image needs an organized cloud"});
}

// Hue in degrees [0, 360) and HSL lightness in [0, 1] of a pixel.
struct HueLightness {
  double hue = 0, lightness = 0;
};

HueLightness hue_lightness(const std::array<std::uint8_t, 3>& rgb) {
  const double r = rgb[0] / 255.0, g = rgb[1] / 255.0, b = rgb[2] / 255.0;
  const double max = std::max({r, g, b}), min = std::min({r, g, b}), chroma = max - min;
  double hue = 0;
  if (chroma > 0 && max == r) hue = std::fmod((g - b) / chroma + 6.0, 6.0);
  else if (chroma > 0 && max == g) hue = (b - r) / chroma + 2.0;
  else if (chroma > 0) hue = (r - g) / chroma + 4.0;
  return {60.0 * hue, (max + min) / 2};
}

double hue_distance(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 360.0 - d);
}

// Parts are told apart by hue, each within 60 deg of its object's hue, so the
// object stays one family of colours.
TEST(IoWriterPng, PartsHaveHuesOfTheirOwnNearTheirObjectsHue) {
  const PointCloud cloud = organized_cloud(12, 9, false);
  const Labels labels = labels_for(cloud), objects = objects_for(labels);
  const Image image = decode_png(encode_label_png(cloud, labels, LabelImageStyle::labels, &objects));
  ASSERT_EQ(image.pixels.size(), cloud.size());
  std::array<std::optional<HueLightness>, 10> seen;  // per part label
  std::array<std::uint32_t, 10> object_of{};
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    SCOPED_TRACE("pixel " + std::to_string(i));
    const auto pixel = image.pixels[i];
    EXPECT_EQ(pixel, part_color(objects[i], labels[i]));
    if (labels[i] == 0) {
      EXPECT_EQ(pixel, (std::array<std::uint8_t, 3>{0, 0, 0}));
    } else if (labels[i] == 7) {
      EXPECT_EQ(pixel, label_color(labels[i]));  // the support: as without objects
    } else {
      seen[labels[i]] = hue_lightness(pixel);
      object_of[labels[i]] = objects[i];
    }
  }
  for (const std::uint32_t part : {1, 2, 3, 4, 5, 6, 8, 9}) {
    ASSERT_TRUE(seen[part].has_value()) << part;
    EXPECT_GT(seen[part]->lightness, 0.2) << part;  // never black or white
    EXPECT_LT(seen[part]->lightness, 0.85) << part;
    const double object_hue = hue_lightness(label_color(object_of[part])).hue;
    EXPECT_LE(hue_distance(seen[part]->hue, object_hue), 61.0) << part;  // the object's family
  }
  for (const auto& [first, last] : {std::pair{1u, 3u}, {4u, 6u}, {8u, 9u}})  // the parts of one object
    for (std::uint32_t a = first; a < last; ++a)
      EXPECT_GT(hue_distance(seen[a]->hue, seen[a + 1]->hue), 40.0) << a;  // told apart by hue
  // Five consecutive part ids of one object: every two at least 15 deg apart.
  for (std::uint32_t a = 40; a < 45; ++a)
    for (std::uint32_t b = a + 1; b < 45; ++b)
      EXPECT_GT(hue_distance(hue_lightness(part_color(33, a)).hue, hue_lightness(part_color(33, b)).hue), 15.0)
          << a << " " << b;
  EXPECT_GT(hue_distance(hue_lightness(label_color(21)).hue, hue_lightness(label_color(22)).hue), 30.0);
}

TEST(IoWriterPng, ObjectColoursInOverlayAndWithoutObjects) {
  const PointCloud cloud = organized_cloud(12, 9, false);
  const Labels labels = labels_for(cloud), objects = objects_for(labels);
  for (const LabelImageStyle style : {LabelImageStyle::labels, LabelImageStyle::overlay})
    EXPECT_EQ(encode_label_png(cloud, labels, style, nullptr), encode_label_png(cloud, labels, style));
  const Image overlay = decode_png(encode_label_png(cloud, labels, LabelImageStyle::overlay, &objects));
  const Image grey = decode_png(encode_label_png(cloud, Labels(cloud.size(), 0), LabelImageStyle::overlay));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (labels[i] == 0) {
      EXPECT_EQ(overlay.pixels[i], grey.pixels[i]) << i;
      continue;
    }
    const auto color = part_color(objects[i], labels[i]);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(overlay.pixels[i][c], (grey.pixels[i][c] + color[c] + 1) / 2) << i;
  }
  const fs::path path = scratch_dir() / "objects.png";
  write_label_png(path, cloud, labels, LabelImageStyle::labels, &objects);
  EXPECT_EQ(test::read_bytes(path), as_text(encode_label_png(cloud, labels, LabelImageStyle::labels, &objects)));
  const Labels short_objects(5, 1);
  expect_lccp_error([&] { encode_label_png(cloud, labels, LabelImageStyle::labels, &short_objects); },
                    {"objects and points differ in number"});
  EXPECT_EQ(part_color(0, 5), label_color(5));
  EXPECT_EQ(part_color(9, 0), (std::array<std::uint8_t, 3>{0, 0, 0}));
}

TEST(IoWriterPng, LabelRgbIsThePixelsOfTheLabelImage) {
  const PointCloud cloud = organized_cloud(12, 9, false);
  const Labels labels = labels_for(cloud), objects = objects_for(labels);
  EXPECT_EQ(label_rgb(labels), decode_png(encode_label_png(cloud, labels)).pixels);
  EXPECT_EQ(label_rgb(labels, &objects),
            decode_png(encode_label_png(cloud, labels, LabelImageStyle::labels, &objects)).pixels);
  const Labels short_objects(5, 1);
  expect_lccp_error([&] { label_rgb(labels, &short_objects); }, {"labels and objects differ in number"});
}

}  // namespace
}  // namespace lccp
