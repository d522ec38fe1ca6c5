// Tests for lccp/io/cloud_io.hpp: reading PCD/PLY, writing labelled PCD and PNG.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "test_files.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"

namespace lccp {
namespace {

using test::read_bytes;
using test::write_bytes;

namespace fs = std::filesystem;

const fs::path kData = LCCP_TEST_DATA_DIR;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

fs::path scratch_dir() { return test::scratch_dir("lccp_io"); }

using test::expect_lccp_error;

void expect_read_error(const fs::path& path, const std::string& problem) {
  expect_lccp_error([&] { read_cloud(path); }, {path.filename().string(), problem});
}

// Reads a truncated copy: must throw lccp::Error (or, if allowed, succeed), never crash.
void read_truncated(const std::string& bytes, std::size_t size, const fs::path& path, bool must_fail) {
  write_bytes(path, bytes.substr(0, size));
  SCOPED_TRACE("truncated at " + std::to_string(size));
  try {
    read_cloud(path);
    EXPECT_FALSE(must_fail);
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

// A small organized cloud with NaN holes, colours and labels.
PointCloud small_cloud(std::uint32_t width, std::uint32_t height, bool colors) {
  PointCloud cloud;
  cloud.width = width;
  cloud.height = height;
  for (std::uint32_t i = 0; i < width * height; ++i) {
    const bool hole = i % 5 == 3;
    cloud.points.push_back(hole ? Eigen::Vector3f(kNaN, kNaN, kNaN) : Eigen::Vector3f(0.1f * i, -0.37f * i, 1.0f + i));
    if (colors) cloud.colors.push_back((i * 0x0A1B2Cu + 0x30405u) & 0xFFFFFFu);
  }
  return cloud;
}

Labels small_labels(const PointCloud& cloud) {
  Labels labels;
  for (std::size_t i = 0; i < cloud.size(); ++i) labels.push_back(is_finite(cloud.points[i]) ? 1 + i % 7 : 0);
  return labels;
}

bool same_float(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

void expect_same_points(const std::vector<Eigen::Vector3f>& a, const std::vector<Eigen::Vector3f>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(same_float(a[i][k], b[i][k])) << "point " << i << " axis " << k;
}

constexpr const char* kAsciiHeader =
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n";

// ---------------------------------------------------------------- reading

TEST(IoRead, MosdOrganizedScene) {
  const LabelledCloud in = read_cloud(kData / "mosd_test2.pcd");
  const PointCloud& cloud = in.cloud;
  EXPECT_EQ(cloud.width, 640u);
  EXPECT_EQ(cloud.height, 480u);
  ASSERT_EQ(cloud.size(), 307200u);
  EXPECT_TRUE(cloud.organized());
  ASSERT_EQ(cloud.colors.size(), cloud.size());
  EXPECT_FALSE(cloud.has_normals());
  ASSERT_TRUE(in.labels.has_value());
  ASSERT_EQ(in.labels->size(), cloud.size());
  std::size_t finite = 0;
  std::set<std::uint32_t> values;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    values.insert((*in.labels)[i]);
    if (is_finite(cloud.points[i])) ++finite;
    else EXPECT_EQ((*in.labels)[i], 0u) << "non-finite point " << i;
  }
  EXPECT_EQ(finite, 188026u);
  EXPECT_EQ(values, (std::set<std::uint32_t>{0, 1, 20, 30}));
  EXPECT_TRUE(std::any_of(cloud.colors.begin(), cloud.colors.end(), [](std::uint32_t c) { return c != 0; }));
  for (const std::uint32_t c : cloud.colors) ASSERT_EQ(c & 0xFF000000u, 0u);
}

TEST(IoRead, MosdUnorganizedScene) {
  const LabelledCloud in = read_cloud(kData / "mosd_test43.pcd");
  EXPECT_EQ(in.cloud.height, 1u);
  EXPECT_EQ(in.cloud.width, 170986u);
  EXPECT_EQ(in.cloud.size(), 170986u);
  EXPECT_FALSE(in.cloud.organized());
  EXPECT_TRUE(in.labels.has_value());
}

TEST(IoRead, ExtensionIsCaseInsensitive) {
  const fs::path path = scratch_dir() / "SCENE.PCD";
  fs::copy_file(kData / "mosd_test2.pcd", path);
  EXPECT_EQ(read_cloud(path).cloud.size(), 307200u);
}

TEST(IoRead, RoundTripWithColours) {
  const fs::path path = scratch_dir() / "out.pcd";
  const PointCloud cloud = small_cloud(8, 4, true);
  const Labels labels = small_labels(cloud);
  write_labelled_pcd(path, cloud, labels);
  const LabelledCloud in = read_cloud(path);
  EXPECT_EQ(in.cloud.width, 8u);
  EXPECT_EQ(in.cloud.height, 4u);
  expect_same_points(in.cloud.points, cloud.points);
  EXPECT_EQ(in.cloud.colors, cloud.colors);
  ASSERT_TRUE(in.labels.has_value());
  EXPECT_EQ(*in.labels, labels);
  EXPECT_NE(read_bytes(path).find("FIELDS x y z rgb label"), std::string::npos);
  EXPECT_NE(read_bytes(path).find("DATA binary\n"), std::string::npos);
}

TEST(IoRead, RoundTripWithoutColours) {
  const fs::path path = scratch_dir() / "out.pcd";
  const PointCloud cloud = small_cloud(30, 1, false);
  const Labels labels = small_labels(cloud);
  write_labelled_pcd(path, cloud, labels);
  const LabelledCloud in = read_cloud(path);
  EXPECT_EQ(in.cloud.width, 30u);
  EXPECT_EQ(in.cloud.height, 1u);
  expect_same_points(in.cloud.points, cloud.points);
  EXPECT_FALSE(in.cloud.has_colors());
  EXPECT_EQ(*in.labels, labels);
  EXPECT_NE(read_bytes(path).find("FIELDS x y z label"), std::string::npos);
}

TEST(IoRead, AsciiPcdFieldsInAnyOrder) {
  const fs::path path = scratch_dir() / "order.pcd";
  write_bytes(path, std::string(kAsciiHeader) +
                        "FIELDS label z y x\nSIZE 2 4 4 4\nTYPE U F F F\nCOUNT 1 1 1 1\n"
                        "WIDTH 2\nHEIGHT 2\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n"
                        "7 3 2 1\n0 nan nan nan\n65535 6 5 4\n9 -0.5 0.25 0.125\n");
  const LabelledCloud in = read_cloud(path);
  EXPECT_EQ(in.cloud.width, 2u);
  EXPECT_EQ(in.cloud.height, 2u);
  ASSERT_EQ(in.cloud.size(), 4u);
  EXPECT_EQ(in.cloud.points[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_FALSE(is_finite(in.cloud.points[1]));
  EXPECT_EQ(in.cloud.points[2], Eigen::Vector3f(4, 5, 6));
  EXPECT_EQ(in.cloud.points[3], Eigen::Vector3f(0.125f, 0.25f, -0.5f));
  EXPECT_FALSE(in.cloud.has_colors());
  EXPECT_EQ(*in.labels, (Labels{7, 0, 65535, 9}));
}

TEST(IoRead, AsciiPlyWithColours) {
  const fs::path path = scratch_dir() / "hand.ply";
  write_bytes(path,
              "ply\nformat ascii 1.0\ncomment written by hand\nelement vertex 3\n"
              "property float x\nproperty float y\nproperty float z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
              "1 2 3 255 0 0\n4 5 6 0 128 0\n-1 -2 -3.5 1 2 3\n");
  const LabelledCloud in = read_cloud(path);
  EXPECT_EQ(in.cloud.width, 3u);
  EXPECT_EQ(in.cloud.height, 1u);
  ASSERT_EQ(in.cloud.size(), 3u);
  EXPECT_EQ(in.cloud.points[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(in.cloud.points[2], Eigen::Vector3f(-1, -2, -3.5f));
  EXPECT_EQ(in.cloud.colors, (std::vector<std::uint32_t>{0xFF0000u, 0x008000u, 0x010203u}));
  EXPECT_FALSE(in.labels.has_value());
}

TEST(IoRead, PlyLabelsAndDoubles) {
  const fs::path path = scratch_dir() / "labels.ply";
  write_bytes(path,
              "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\n"
              "property double z\nproperty int label\nproperty uchar red\nproperty uchar green\n"
              "property uchar blue\nproperty uchar alpha\nend_header\n"
              "1 2 3 7 10 20 30 0\n4 5 6 12 40 50 60 255\n");
  const LabelledCloud in = read_cloud(path);
  ASSERT_EQ(in.cloud.size(), 2u);
  EXPECT_EQ(in.cloud.points[1], Eigen::Vector3f(4, 5, 6));
  EXPECT_EQ(in.cloud.colors, (std::vector<std::uint32_t>{0x0A141Eu, 0x28323Cu}));
  ASSERT_TRUE(in.labels.has_value());
  EXPECT_EQ(*in.labels, (Labels{7, 12}));
}

TEST(IoRead, NormalsFromPcdAndPly) {
  const fs::path dir = scratch_dir();
  write_bytes(dir / "n.pcd", std::string(kAsciiHeader) +
                                 "FIELDS normal_z x normal_x y normal_y z rgba\nSIZE 4 4 4 4 4 4 4\n"
                                 "TYPE F F F F F F U\nCOUNT 1 1 1 1 1 1 1\nWIDTH 2\nHEIGHT 1\n"
                                 "POINTS 2\nDATA ascii\n1 10 0 20 0 30 4278255360\n0 1 0.6 2 0.8 3 255\n");
  const LabelledCloud pcd = read_cloud(dir / "n.pcd");
  ASSERT_EQ(pcd.cloud.normals.size(), 2u);
  EXPECT_EQ(pcd.cloud.normals[0], Eigen::Vector3f(0, 0, 1));
  EXPECT_EQ(pcd.cloud.normals[1], Eigen::Vector3f(0.6f, 0.8f, 0));
  EXPECT_EQ(pcd.cloud.points[0], Eigen::Vector3f(10, 20, 30));
  EXPECT_EQ(pcd.cloud.colors, (std::vector<std::uint32_t>{0x00FF00u, 0x0000FFu}));  // alpha dropped

  write_bytes(dir / "n.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
              "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n"
              "1 2 3 0 1 0\n");
  const LabelledCloud ply = read_cloud(dir / "n.ply");
  ASSERT_EQ(ply.cloud.normals.size(), 1u);
  EXPECT_EQ(ply.cloud.normals[0], Eigen::Vector3f(0, 1, 0));
}

TEST(IoRead, AllNanCloudIsNotAnError) {
  const fs::path path = scratch_dir() / "nan.pcd";
  write_bytes(path, std::string(kAsciiHeader) +
                        "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
                        "POINTS 2\nDATA ascii\nnan nan nan\nnan nan nan\n");
  const LabelledCloud in = read_cloud(path);
  ASSERT_EQ(in.cloud.size(), 2u);
  EXPECT_FALSE(is_finite(in.cloud.points[0]));
  EXPECT_FALSE(is_finite(in.cloud.points[1]));
}

// ----------------------------------------------------------------- errors

TEST(IoErrors, MissingFileDirectoryAndFormat) {
  const fs::path dir = scratch_dir();
  expect_read_error(dir / "absent.pcd", "no such file");
  fs::create_directory(dir / "folder.pcd");
  expect_read_error(dir / "folder.pcd", "directory");
  write_bytes(dir / "cloud.xyz", "1 2 3\n");
  expect_read_error(dir / "cloud.xyz", "unsupported format '.xyz' (expected .pcd or .ply)");
}

TEST(IoErrors, TextFileIsNotAPointCloud) {
  const fs::path dir = scratch_dir();
  write_bytes(dir / "notes.pcd", "hello world\nthis is not a point cloud\n");
  expect_read_error(dir / "notes.pcd", "not a point cloud");
  write_bytes(dir / "notes.ply", "hello world\nthis is not a point cloud\n");
  expect_read_error(dir / "notes.ply", "not a readable PLY");
  write_bytes(dir / "empty.pcd", "");
  expect_read_error(dir / "empty.pcd", "not a point cloud");
}

TEST(IoErrors, NoXyzFields) {
  const fs::path path = scratch_dir() / "abc.pcd";
  write_bytes(path, std::string(kAsciiHeader) +
                        "FIELDS a b c\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
                        "POINTS 2\nDATA ascii\n1 2 3\n4 5 6\n");
  expect_read_error(path, "no x/y/z fields");
}

TEST(IoErrors, ZeroPoints) {
  const fs::path dir = scratch_dir();
  for (const char* data : {"ascii", "binary"}) {
    const fs::path path = dir / (std::string("zero_") + data + ".pcd");
    write_bytes(path, std::string(kAsciiHeader) +
                          "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 0\nHEIGHT 1\n"
                          "POINTS 0\nDATA " + data + "\n");
    expect_read_error(path, "no points");
  }
  write_bytes(dir / "zero.ply",
              "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
              "property float z\nend_header\n");
  expect_read_error(dir / "zero.ply", "no points");
}

TEST(IoErrors, TruncatedCompressedPcd) {
  const std::string bytes = read_bytes(kData / "mosd_test2.pcd");
  const std::string data_line = "DATA binary_compressed\n";
  const std::size_t data = bytes.find(data_line) + data_line.size();
  std::uint32_t compressed = 0;
  std::memcpy(&compressed, bytes.data() + data, 4);
  const std::size_t end = data + 8 + compressed;  // PCL pads the file after this
  ASSERT_LT(end, bytes.size());
  const fs::path path = scratch_dir() / "cut.pcd";
  write_bytes(path, bytes.substr(0, end));  // the padding is not needed
  EXPECT_EQ(read_cloud(path).cloud.size(), 307200u);
  std::vector<std::size_t> sizes = {0, 1, 10, 50, 100, 150, 190, 200, data - 1, data, data + 4, data + 8, end - 1};
  for (std::size_t k = 1; k < 40; ++k) sizes.push_back(end * k / 40);
  for (const std::size_t size : sizes) read_truncated(bytes, size, path, true);
  write_bytes(path, bytes.substr(0, end / 2));
  expect_read_error(path, "truncated");
}

TEST(IoErrors, TruncatedBinaryPcdAtEveryByte) {
  const fs::path dir = scratch_dir();
  const PointCloud cloud = small_cloud(6, 3, true);
  write_labelled_pcd(dir / "full.pcd", cloud, small_labels(cloud));
  const std::string bytes = read_bytes(dir / "full.pcd");
  const std::string data_line = "DATA binary\n";
  const std::size_t end = bytes.find(data_line) + data_line.size() + cloud.size() * 20;
  ASSERT_LE(end, bytes.size());  // PCL pads binary files with zeros after the data
  for (std::size_t size = 0; size < bytes.size(); size += size < end + 8 ? 1 : 97)
    read_truncated(bytes, size, dir / "cut.pcd", size < end);
  write_bytes(dir / "cut.pcd", bytes.substr(0, end - 5));
  expect_read_error(dir / "cut.pcd", "truncated");
}

TEST(IoErrors, TruncatedAsciiPcdNeverCrashes) {
  const std::string bytes = std::string(kAsciiHeader) +
                            "FIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH 3\n"
                            "HEIGHT 1\nPOINTS 3\nDATA ascii\n1.5 2.5 3.5 1\n4.5 5.5 6.5 2\n7.5 8.5 9.5 3\n";
  const fs::path path = scratch_dir() / "cut.pcd";
  // Only a cut after the last word (or inside a multi-digit last number)
  // leaves a file that looks complete.
  const std::size_t last_line = bytes.rfind("7.5");
  for (std::size_t size = 0; size < bytes.size(); ++size) read_truncated(bytes, size, path, size <= last_line + 12);
  write_bytes(path, bytes.substr(0, last_line + 4));
  expect_read_error(path, "truncated");
}

TEST(IoErrors, TruncatedPlyNeverCrashes) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  for (int i = 0; i < 4; ++i) {
    const float xyz[3] = {1.0f * i, 2.0f * i, 3.0f};
    bytes.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    bytes.append({static_cast<char>(10 * i), 20, 30});
  }
  const fs::path path = scratch_dir() / "cut.ply";
  write_bytes(path, bytes);
  const LabelledCloud full = read_cloud(path);
  ASSERT_EQ(full.cloud.size(), 4u);
  EXPECT_EQ(full.cloud.points[3], Eigen::Vector3f(3, 6, 3));
  EXPECT_EQ(full.cloud.colors[3], 0x1E141Eu);
  for (std::size_t size = 0; size < bytes.size(); ++size) read_truncated(bytes, size, path, true);
}

TEST(IoErrors, CorruptCompressedSize) {
  std::string bytes = read_bytes(kData / "mosd_test43.pcd");
  const std::string data_line = "DATA binary_compressed\n";
  const std::size_t data = bytes.find(data_line) + data_line.size();
  const std::uint32_t huge = 0x7FFFFFFF;
  std::string wrong_raw = bytes;
  std::memcpy(wrong_raw.data() + data + 4, &huge, 4);  // raw size != POINTS x point size
  const fs::path path = scratch_dir() / "corrupt.pcd";
  write_bytes(path, wrong_raw);
  expect_read_error(path, "corrupt");
  std::memcpy(bytes.data() + data, &huge, 4);  // compressed size beyond the file
  write_bytes(path, bytes);
  expect_read_error(path, "truncated");
}

TEST(IoErrors, NothingIsPrinted) {
  const fs::path dir = scratch_dir();
  write_bytes(dir / "notes.ply", "hello\n");
  const std::string bytes = read_bytes(kData / "mosd_test2.pcd");
  write_bytes(dir / "cut.pcd", bytes.substr(0, 5000));
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  EXPECT_THROW(read_cloud(dir / "notes.ply"), Error);
  EXPECT_THROW(read_cloud(dir / "cut.pcd"), Error);
  EXPECT_NO_THROW(read_cloud(kData / "mosd_test43.pcd"));
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// ---------------------------------------------------------------- writing

std::uint32_t big_endian(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < 4; ++k) value = value << 8 | static_cast<std::uint8_t>(bytes[at + k]);
  return value;
}

TEST(IoWrite, LabelPngOfMosdScene) {
  const LabelledCloud in = read_cloud(kData / "mosd_test2.pcd");
  const fs::path path = scratch_dir() / "labels.png";
  write_label_png(path, in.cloud, *in.labels);
  const std::string png = read_bytes(path);
  ASSERT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1A\n", 8));
  std::string ihdr, idat;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = big_endian(png, at);
    const std::string type = png.substr(at + 4, 4), body = png.substr(at + 8, length);
    const auto* typed = reinterpret_cast<const Bytef*>(png.data() + at + 4);
    EXPECT_EQ(crc32(0, typed, 4 + length), big_endian(png, at + 8 + length)) << type;
    if (type == "IHDR") ihdr = body;
    if (type == "IDAT") idat += body;
    at += 12 + length;
  }
  ASSERT_EQ(ihdr.size(), 13u);
  EXPECT_EQ(big_endian(ihdr, 0), 640u);
  EXPECT_EQ(big_endian(ihdr, 4), 480u);
  EXPECT_EQ(ihdr.substr(8), std::string("\x08\x02\x00\x00\x00", 5));
  const std::size_t row = 1 + 640 * 3;
  std::vector<Bytef> raw(row * 480);
  uLongf raw_size = raw.size();
  ASSERT_EQ(uncompress(raw.data(), &raw_size, reinterpret_cast<const Bytef*>(idat.data()), idat.size()), Z_OK);
  ASSERT_EQ(raw_size, raw.size());
  for (std::size_t i = 0; i < in.cloud.size(); ++i) {
    const std::size_t y = i / 640, x = i % 640;
    if (x == 0) {
      ASSERT_EQ(raw[y * row], 0) << "filter byte of row " << y;
    }
    const auto color = label_color((*in.labels)[i]);
    for (std::size_t c = 0; c < 3; ++c) ASSERT_EQ(raw[y * row + 1 + 3 * x + c], color[c]) << "pixel " << i;
  }
}

TEST(IoWrite, LabelPngNeedsOrganizedCloud) {
  const PointCloud cloud = small_cloud(12, 1, false);
  const fs::path path = scratch_dir() / "flat.png";
  expect_lccp_error([&] { write_label_png(path, cloud, small_labels(cloud)); },
               {"flat.png", "a label image needs an organized cloud"});
  EXPECT_FALSE(fs::exists(path));
}

TEST(IoWrite, LabelCountMustMatch) {
  const PointCloud cloud = small_cloud(4, 2, true);
  const fs::path dir = scratch_dir();
  const Labels short_labels(cloud.size() - 1, 1);
  expect_lccp_error([&] { write_labelled_pcd(dir / "a.pcd", cloud, short_labels); }, {"a.pcd", "labels"});
  expect_lccp_error([&] { write_label_png(dir / "a.png", cloud, short_labels); }, {"a.png", "labels"});
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(IoWrite, MissingFolderLeavesNothing) {
  const PointCloud cloud = small_cloud(4, 2, true);
  const Labels labels = small_labels(cloud);
  const fs::path dir = scratch_dir();
  const fs::path missing = dir / "no_such_folder";
  expect_lccp_error([&] { write_labelled_pcd(missing / "out.pcd", cloud, labels); }, {"out.pcd", "does not exist"});
  expect_lccp_error([&] { write_label_png(missing / "out.png", cloud, labels); }, {"out.png", "does not exist"});
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(IoWrite, FailedRenameLeavesNoTempFile) {
  const PointCloud cloud = small_cloud(4, 2, true);
  const Labels labels = small_labels(cloud);
  const fs::path dir = scratch_dir();
  fs::create_directory(dir / "taken.pcd");  // a folder where the file should go
  fs::create_directory(dir / "taken.png");
  expect_lccp_error([&] { write_labelled_pcd(dir / "taken.pcd", cloud, labels); }, {"taken.pcd", "cannot write"});
  expect_lccp_error([&] { write_label_png(dir / "taken.png", cloud, labels); }, {"taken.png", "cannot write"});
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"taken.pcd", "taken.png"}));
}

TEST(IoWrite, OverwritesExistingFile) {
  const fs::path path = scratch_dir() / "out.pcd";
  write_bytes(path, "old");
  const PointCloud cloud = small_cloud(5, 2, false);
  write_labelled_pcd(path, cloud, small_labels(cloud));
  EXPECT_EQ(read_cloud(path).cloud.size(), 10u);
}

// ----------------------------------------------------------- label colours

TEST(IoLabelColor, BlackOnlyForZero) {
  EXPECT_EQ(label_color(0), (std::array<std::uint8_t, 3>{0, 0, 0}));
  for (std::uint32_t k = 1; k <= 1000; ++k) {
    const auto c = label_color(k);
    ASSERT_GT(std::max({c[0], c[1], c[2]}), 200) << "label " << k;
  }
  EXPECT_NE(label_color(0xFFFFFFFFu), label_color(0));
}

TEST(IoLabelColor, NeighboursLookDifferent) {
  for (std::uint32_t k = 1; k < 1000; ++k) {
    const auto a = label_color(k), b = label_color(k + 1);
    int distance = 0;
    for (int c = 0; c < 3; ++c) distance += std::abs(int(a[c]) - int(b[c]));
    ASSERT_GE(distance, 150) << "labels " << k << " and " << k + 1;
  }
  EXPECT_EQ(label_color(20), label_color(20));  // deterministic
  EXPECT_NE(label_color(20), label_color(30));
}

}  // namespace
}  // namespace lccp
