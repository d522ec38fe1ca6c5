// Tests for lccp/io/cloud_io.hpp (reading PCD/PLY, writing labelled PCD and PNG)
// and lccp/io/config_file.hpp (YAML presets).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <chrono>
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
#include "lccp/io/config_file.hpp"

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
  // append, not +: GCC 12's -Warray-bounds misfires on string + literal here (GCC bug 105651).
  write_bytes(path, std::string(kAsciiHeader)
                        .append("FIELDS a b c\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
                                "POINTS 2\nDATA ascii\n1 2 3\n4 5 6\n"));
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

// ------------------------------------------------- our own PCD/PLY readers

const fs::path kFormats = kData / "formats";

std::vector<std::uint8_t> to_bytes(const std::string& text) { return {text.begin(), text.end()}; }

LabelledCloud parse_pcd_text(const std::string& text, const ReadLimits& limits = {}) {
  return parse_pcd(to_bytes(text), "mem.pcd", limits);
}

LabelledCloud parse_ply_text(const std::string& text, const ReadLimits& limits = {}) {
  return parse_ply(to_bytes(text), "mem.ply", limits);
}

void expect_pcd_error(const std::string& text, std::initializer_list<std::string> parts) {
  SCOPED_TRACE(text.substr(0, 300));
  std::vector<std::string> all = {"mem.pcd: "};
  all.insert(all.end(), parts.begin(), parts.end());
  expect_lccp_error([&] { parse_pcd_text(text); }, all);
}

void expect_ply_error(const std::string& text, const std::string& part) {
  SCOPED_TRACE(text.substr(0, 300));
  expect_lccp_error([&] { parse_ply_text(text); }, {"mem.ply: ", part});
}

template <typename T>
std::string raw(T value) {
  return std::string(reinterpret_cast<const char*>(&value), sizeof value);
}

template <typename T>
std::string raw_big_endian(T value) {
  std::string bytes = raw(value);
  std::reverse(bytes.begin(), bytes.end());
  return bytes;
}

// An LZF stream of literal runs only (32 bytes at most each): valid, no back references.
std::string lzf_literals(const std::string& data) {
  std::string out;
  for (std::size_t at = 0; at < data.size(); at += 32) {
    const std::size_t n = std::min<std::size_t>(32, data.size() - at);
    out += static_cast<char>(n - 1);
    out += data.substr(at, n);
  }
  return out;
}

// DATA binary_compressed: sizes, then the LZF stream.
std::string compressed_section(const std::string& lzf, std::uint32_t raw_size) {
  return raw(static_cast<std::uint32_t>(lzf.size())) + raw(raw_size) + lzf;
}

std::string pcd_header(const std::string& fields_size_type_count, std::uint64_t width, std::uint64_t height,
                       const std::string& data) {
  return std::string(kAsciiHeader) + fields_size_type_count + "WIDTH " + std::to_string(width) + "\nHEIGHT " +
         std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(width * height) +
         "\nDATA " + data + "\n";
}

constexpr const char* kXyz = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";

// The cloud of tests/data/formats/pcl_normals_* (see its README).
void expect_pcl_normals_cloud(const LabelledCloud& in, bool organized) {
  EXPECT_EQ(in.cloud.width, organized ? 4u : 12u);
  EXPECT_EQ(in.cloud.height, organized ? 3u : 1u);
  ASSERT_EQ(in.cloud.size(), 12u);
  ASSERT_EQ(in.cloud.colors.size(), 12u);
  ASSERT_EQ(in.cloud.normals.size(), 12u);
  EXPECT_FALSE(in.labels.has_value());
  for (int i = 0; i < 12; ++i) {
    SCOPED_TRACE("point " + std::to_string(i));
    if (i % 5 == 3) {
      EXPECT_FALSE(is_finite(in.cloud.points[i]));
    } else {
      EXPECT_EQ(in.cloud.points[i], Eigen::Vector3f(0.25f * i, 1.0f - 0.5f * i, 1.0f + 0.125f * i));
    }
    EXPECT_EQ(in.cloud.colors[i], std::uint32_t(20 * i) << 16 | std::uint32_t(255 - 7 * i) << 8 | std::uint32_t(i));
    EXPECT_EQ(in.cloud.normals[i], Eigen::Vector3f(i % 3 == 0, i % 3 == 1, i % 3 == 2));
  }
}

TEST(IoFormats, PclWrittenPcdInEveryDataKind) {
  for (const char* kind : {"ascii", "binary", "compressed"}) {
    SCOPED_TRACE(kind);
    expect_pcl_normals_cloud(read_cloud(kFormats / (std::string("pcl_normals_") + kind + ".pcd")), true);
  }
}

TEST(IoFormats, PclWrittenPlyAsciiAndBinaryKeepOrganizedLayout) {
  // PCL's PLYWriter stores width and height in its camera element, after the vertices.
  for (const char* kind : {"ascii", "binary"}) {
    SCOPED_TRACE(kind);
    expect_pcl_normals_cloud(read_cloud(kFormats / (std::string("pcl_normals_") + kind + ".ply")), true);
  }
}

TEST(IoFormats, CountFiveFieldAndPaddingInEveryDataKind) {
  for (const char* kind : {"ascii", "binary", "compressed"}) {
    SCOPED_TRACE(kind);
    const LabelledCloud in = read_cloud(kFormats / (std::string("pcl_count5_") + kind + ".pcd"));
    EXPECT_EQ(in.cloud.width, 6u);
    EXPECT_EQ(in.cloud.height, 1u);
    ASSERT_EQ(in.cloud.size(), 6u);
    ASSERT_TRUE(in.labels.has_value());
    for (int i = 0; i < 6; ++i) {
      EXPECT_EQ(in.cloud.points[i], Eigen::Vector3f(1.5f * i, -2.0f * i, 3.0f + i)) << i;
      EXPECT_EQ((*in.labels)[i], std::uint32_t(1000 * i + 7)) << i;
    }
  }
  EXPECT_NE(read_bytes(kFormats / "pcl_count5_binary.pcd").find("FIELDS x histogram y z label _\n"), std::string::npos);
}

TEST(IoFormats, LabelledPcdHeaderIsPcls) {
  PointCloud cloud = small_cloud(3, 2, true);
  const std::string pcl = read_bytes(kFormats / "pcl_labelled_binary.pcd");
  const std::string data_line = "DATA binary\n";
  const std::string header = pcl.substr(0, pcl.find(data_line) + data_line.size());
  const std::vector<std::uint8_t> ours = encode_labelled_pcd(cloud, small_labels(cloud));
  ASSERT_EQ(ours.size(), header.size() + 6 * 20);
  EXPECT_EQ(std::string(ours.begin(), ours.begin() + header.size()), header);
  cloud.colors.clear();
  const std::vector<std::uint8_t> plain = encode_labelled_pcd(cloud, small_labels(cloud));
  std::string plain_header = header;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"x y z rgb label", "x y z label"},
                                 {"4 4 4 4 4", "4 4 4 4"}, {"F F F F U", "F F F U"}, {"1 1 1 1 1", "1 1 1 1"}})
    plain_header.replace(plain_header.find(from), from.size(), to);
  EXPECT_EQ(std::string(plain.begin(), plain.begin() + plain_header.size()), plain_header);
  EXPECT_EQ(plain.size(), plain_header.size() + 6 * 16);
}

TEST(IoFormats, EncodeRejectsMismatchedInput) {
  const PointCloud cloud = small_cloud(4, 2, true);
  expect_lccp_error([&] { encode_labelled_pcd(cloud, Labels(3, 1)); }, {"labels and points differ in number"});
  expect_lccp_error([&] { encode_labelled_pcd(PointCloud{}, Labels{}); }, {"no points"});
  const std::vector<std::uint8_t> png = encode_label_png(cloud, small_labels(cloud));
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png[1], 'P');
}

TEST(IoFormats, OrganizedRoundTripKeepsEveryBit) {
  PointCloud cloud = small_cloud(7, 5, true);
  cloud.points[4] = Eigen::Vector3f(-0.0f, std::numeric_limits<float>::infinity(), 1e-40f);  // denormal kept
  const Labels labels = small_labels(cloud);
  const LabelledCloud in = parse_pcd(encode_labelled_pcd(cloud, labels), "mem.pcd");
  EXPECT_EQ(in.cloud.width, 7u);
  EXPECT_EQ(in.cloud.height, 5u);
  expect_same_points(in.cloud.points, cloud.points);
  EXPECT_EQ(in.cloud.colors, cloud.colors);
  EXPECT_EQ(*in.labels, labels);
}

TEST(IoPcd, KeywordsInsideBinaryDataAreData) {
  // PCL 1.13 parsed header keywords wherever they appeared (a use-after-free).
  const std::string text = "\nCOLUMNS a b c\nPOINTS 4000000000\nDATA ascii\n";
  const std::size_t step = 12 + text.size();
  const std::string fields =
      "FIELDS x y z note\nSIZE 4 4 4 1\nTYPE F F F U\nCOUNT 1 1 1 " + std::to_string(text.size()) + "\n";
  std::string points;
  for (int i = 0; i < 2; ++i) points += raw(1.0f + i) + raw(2.0f) + raw(3.0f) + text;
  for (const std::string kind : {"binary", "binary_compressed"}) {
    SCOPED_TRACE(kind);
    std::string data = points;
    if (kind == "binary_compressed") {  // one array per field
      std::string planes;
      for (std::size_t offset : {0, 4, 8}) planes += points.substr(offset, 4) + points.substr(step + offset, 4);
      planes += text + text;
      data = compressed_section(lzf_literals(planes), static_cast<std::uint32_t>(planes.size()));
    }
    const LabelledCloud in = parse_pcd_text(pcd_header(fields, 2, 1, kind) + data);
    ASSERT_EQ(in.cloud.size(), 2u);
    EXPECT_EQ(in.cloud.points[0], Eigen::Vector3f(1, 2, 3));
    EXPECT_EQ(in.cloud.points[1], Eigen::Vector3f(2, 2, 3));
  }
}

TEST(IoPcd, TwoHundredMillionPointsInTinyFileFailFast) {
  // 196 bytes claiming 200 M points: PCL 1.13 took 21 s and 4.7 GB to fail.
  std::string file = std::string("VERSION 0.7\n") + kXyz +
                     "WIDTH 200000000\nHEIGHT 1\nPOINTS 200000000\nDATA binary_compressed\n";
  ASSERT_LT(file.size(), 196u - 8);
  const std::string lzf(196 - file.size() - 8, '\x1f');
  file += compressed_section(lzf, 2400000000u);
  ASSERT_EQ(file.size(), 196u);
  const fs::path path = scratch_dir() / "huge.pcd";
  write_bytes(path, file);
  const auto start = std::chrono::steady_clock::now();
  expect_read_error(path, "too many points (200000000, limit 50000000)");
  ReadLimits generous;
  generous.max_points = 300000000;
  expect_lccp_error([&] { read_cloud(path, generous); }, {"huge.pcd", "corrupt compressed data", "cannot expand"});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 0.5);
}

TEST(IoPcd, CorruptLzfStreams) {
  using namespace std::string_literals;
  const std::string head = pcd_header(kXyz, 2, 1, "binary_compressed");
  const std::string planes(24, '\x11');
  const std::string good = lzf_literals(planes);
  EXPECT_EQ(parse_pcd_text(head + compressed_section(good, 24)).cloud.size(), 2u);
  // 24 bytes as 1 literal, an 8-byte and a 15-byte back reference (distance 1).
  const std::string refs = "\x00\x11"s + "\xc0\x00"s + "\xe0\x06\x00"s;
  const LabelledCloud in = parse_pcd_text(head + compressed_section(refs, 24));
  std::uint32_t bits = 0x11111111u;
  float expected = 0;
  std::memcpy(&expected, &bits, 4);
  EXPECT_EQ(in.cloud.points[1], Eigen::Vector3f(expected, expected, expected));
  const std::vector<std::pair<std::string, std::string>> bad = {
      {good + "\x00\x11"s, "literal run past the declared raw size"},
      {good.substr(0, good.size() - 1), "literal run past the end of the compressed data"},
      {lzf_literals(planes.substr(0, 20)), "stream ends before the declared raw size"},
      {"\x00\x11\x20\x05"s, "back reference before the start of the data"},  // distance 6 after 1 byte
      {"\x00\x11\xe0"s, "back reference cut off"},
      {"\x00\x11\xe0\xff"s, "back reference cut off"},
      {"\x00\x11\xe0\xff\x00"s, "back reference past the declared raw size"},  // 264 bytes
  };
  for (const auto& [lzf, problem] : bad)
    expect_pcd_error(head + compressed_section(lzf, 24), {"corrupt compressed data (" + problem + ")"});
  expect_pcd_error(head + compressed_section(good, 28), {"corrupt compressed data (raw size 28, POINTS x point size is 24)"});
  expect_pcd_error(head + compressed_section(good, 24).substr(0, 20), {"truncated data (20 of 33 bytes)"});
  expect_pcd_error(head + "\x05", {"truncated data (1 of 8 bytes)"});
}

TEST(IoPcd, TruncatedDataOfEveryKind) {
  std::string binary = raw(1.0f) + raw(2.0f) + raw(3.0f);
  expect_pcd_error(pcd_header(kXyz, 2, 1, "binary") + binary, {"truncated data (12 of 24 bytes)"});
  expect_pcd_error(pcd_header(kXyz, 2, 1, "ascii") + "1 2 3\n", {"truncated"});
  expect_pcd_error(pcd_header(kXyz, 3, 1, "ascii") + "1 2 3\n\n\n4.000 5.000 6.000\n", {"truncated data (2 of 3 points)"});
  EXPECT_EQ(parse_pcd_text(pcd_header(kXyz, 2, 1, "ascii") + "1 2 3\r\n\r\n4 5 6").cloud.points[1],
            Eigen::Vector3f(4, 5, 6));  // CRLF, a blank line, no final newline
  expect_pcd_error(pcd_header(kXyz, 2, 1, "ascii") + "1 2 3\n4 5 6 7\n", {"truncated or malformed data (point 2)"});
  // Every cut of each PCL-written file either fails with one line or, past the data, reads.
  for (const auto& entry : fs::directory_iterator(kFormats)) {
    const std::string bytes = read_bytes(entry.path());
    if (entry.path().extension() == ".md") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const std::size_t data = bytes.find(entry.path().extension() == ".ply" ? "end_header\n" : "\nDATA ");
    for (std::size_t size = 0; size < bytes.size(); size += size < 900 ? 1 : 131) {
      try {
        const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + size);
        if (entry.path().extension() == ".ply") parse_ply(cut, "cut", {});
        else parse_pcd(cut, "cut", {});
        EXPECT_GT(size, data) << "a cut inside the header was accepted at " << size;
      } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      }
    }
  }
}

TEST(IoPcd, HugeDimensionsAreRejectedBeforeAllocating) {
  const std::string fields = std::string(kAsciiHeader) + kXyz;
  expect_pcd_error(fields + "WIDTH 4294967296\nHEIGHT 1\nPOINTS 4294967296\nDATA binary\n", {"more than 2^32 - 1"});
  // 65536 x 65536 wraps to 0 in 32 bits.
  expect_pcd_error(fields + "WIDTH 65536\nHEIGHT 65536\nPOINTS 0\nDATA binary\n", {"WIDTH x HEIGHT = 65536 x 65536 != POINTS 0"});
  expect_pcd_error(fields + "WIDTH 4294967295\nHEIGHT 4294967295\nPOINTS 1\nDATA binary\n", {"!= POINTS 1"});
  expect_pcd_error(fields + "WIDTH 1\nHEIGHT 1\nPOINTS 99999999999999999999999\nDATA binary\n", {"bad number"});
  expect_pcd_error(fields + "WIDTH 60000\nHEIGHT 60000\nPOINTS 3600000000\nDATA binary\n" + std::string(64, '\0'),
                   {"too many points (3600000000, limit 50000000)"});
  ReadLimits unlimited;
  unlimited.max_points = std::numeric_limits<std::uint64_t>::max();
  expect_lccp_error([&] { parse_pcd_text(fields + "WIDTH 60000\nHEIGHT 60000\nPOINTS 3600000000\nDATA binary\n" + std::string(64, '\0'), unlimited); },
                    {"truncated data (64 of 43200000000 bytes)"});
  expect_lccp_error([&] { parse_pcd_text(fields + "WIDTH 60000\nHEIGHT 60000\nPOINTS 3600000000\nDATA ascii\n1 2 3\n", unlimited); },
                    {"truncated data (6 bytes cannot hold 3600000000 points)"});
  expect_pcd_error(std::string(kAsciiHeader) + "FIELDS x y z\nCOUNT 1 1 16777216\nPOINTS 1\nDATA binary\n", {"points of more than"});
}

TEST(IoPcd, NegativeNanAndMalformedHeaderNumbers) {
  const std::string fields = std::string(kAsciiHeader) + kXyz;
  const std::string tail = "DATA ascii\n1 2 3\n";
  for (const char* bad : {"WIDTH -1\nHEIGHT 1\nPOINTS 1\n", "WIDTH 1\nHEIGHT nan\nPOINTS 1\n", "WIDTH 1\nHEIGHT 1\nPOINTS -5\n",
                          "WIDTH 1.0\nHEIGHT 1\nPOINTS 1\n", "WIDTH 1e0\nHEIGHT 1\nPOINTS 1\n", "WIDTH 1\nHEIGHT 1\nPOINTS\n",
                          "WIDTH 1 2\nHEIGHT 1\nPOINTS 1\n", "WIDTH +1\nHEIGHT 1\nPOINTS 1\n"})
    expect_pcd_error(fields + bad + tail, {"bad PCD header"});
  const std::string dims = "WIDTH 1\nHEIGHT 1\nPOINTS 1\n";
  const std::string head = std::string(kAsciiHeader) + "FIELDS x y z\n";
  expect_pcd_error(head + "SIZE 4 -4 4\n" + dims + tail, {"bad number '-4' in SIZE"});
  expect_pcd_error(head + "SIZE 4 3 4\n" + dims + tail, {"SIZE 3 of field 'y'"});
  expect_pcd_error(head + "TYPE F X F\n" + dims + tail, {"TYPE X with SIZE 4 of field 'y'"});
  expect_pcd_error(head + "SIZE 4 2 4\nTYPE F F F\n" + dims + tail, {"TYPE F with SIZE 2"});
  expect_pcd_error(head + "COUNT 1 0 1\n" + dims + tail, {"COUNT 0 of field 'y'"});
  expect_pcd_error(head + "COUNT 1 -1 1\n" + dims + tail, {"bad number '-1' in COUNT"});
  expect_pcd_error(head + "VIEWPOINT 0 0 nan 1 0 0 0\n" + dims + tail, {"bad number 'nan' in VIEWPOINT"});
  expect_pcd_error(head + "VIEWPOINT 0 0 0\n" + dims + tail, {"VIEWPOINT needs 7 numbers"});
}

TEST(IoPcd, InconsistentHeaders) {
  const std::string dims = "WIDTH 1\nHEIGHT 1\nPOINTS 1\n";
  const std::string head = kAsciiHeader;
  const std::string tail = "DATA ascii\n1 2 3\n";
  expect_pcd_error(head + kXyz + "FIELDS x y z\n" + dims + tail, {"FIELDS given twice"});
  expect_pcd_error(head + "FIELDS x y z\nCOLUMNS x y z\n" + dims + tail, {"FIELDS given twice"});
  expect_pcd_error(head + "FIELDS x y z\nSIZE 4 4\n" + dims + tail, {"SIZE, TYPE or COUNT does not match FIELDS"});
  expect_pcd_error(head + "FIELDS x y z\nWIDTH 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n" + tail, {"WIDTH given twice"});
  expect_pcd_error(head + "SIZE 4\n" + dims + tail, {"no FIELDS"});
  expect_pcd_error(head + kXyz + "WIDTH 1\nHEIGHT 1\n" + tail, {"no POINTS"});
  expect_pcd_error(head + kXyz + "HEIGHT 1\nPOINTS 1\n" + tail, {"HEIGHT without WIDTH"});
  expect_pcd_error(head + kXyz + dims + "DATA zip\n", {"unknown DATA 'zip'"});
  expect_pcd_error(head + kXyz + dims + "COLOUR red\n" + tail, {"unknown line 'COLOUR'"});
  expect_pcd_error(head + kXyz + dims, {"truncated PCD header (no DATA line)"});
  expect_pcd_error(head + kXyz + dims + "DATA binary", {"truncated PCD header"});
  expect_pcd_error(head + "FIELDS x y z\nTYPE F F I\n" + dims + tail, {"field 'z' is not floating point"});
  expect_pcd_error(head + "FIELDS x y z label\nTYPE F F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3 4\n",
                   {"field 'label' is not an integer type"});
  expect_pcd_error(head + "FIELDS x y z\nCOUNT 2 1 1\n" + dims + "DATA ascii\n1 1 2 3\n", {"field 'x' has 2 elements"});
  // Defaults as PCL's: no WIDTH/HEIGHT means one row of POINTS; SIZE 4, TYPE F, COUNT 1.
  const LabelledCloud in = parse_pcd_text(head + "FIELDS x y z\nPOINTS 2\n" + "DATA ascii\n1 2 3\n4 5 6\n");
  EXPECT_EQ(in.cloud.width, 2u);
  EXPECT_EQ(in.cloud.height, 1u);
}

TEST(IoPcd, AsciiValuesMustFitTheirType) {
  const std::string fields = "FIELDS x y z label\nSIZE 4 4 4 2\nTYPE F F F U\nCOUNT 1 1 1 1\n";
  const std::string head = pcd_header(fields, 1, 1, "ascii");
  EXPECT_EQ(*parse_pcd_text(head + "+1 -2 3e-2 65535\n").labels, (Labels{65535}));
  expect_pcd_error(head + "1 2 3 65536\n", {"bad value '65536' for field 'label' (point 1)"});
  expect_pcd_error(head + "1 2 3 -1\n", {"bad value '-1' for field 'label'"});
  expect_pcd_error(head + "1 two 3 4\n", {"bad value 'two' for field 'y'"});
  expect_pcd_error(head + "1 2 1e39 4\n", {"bad value '1e39' for field 'z'"});
  expect_pcd_error(head + "1 2 3 4.0\n", {"bad value '4.0'"});
}

TEST(IoPcd, PaddingAndMultiElementFieldsInEveryDataKind) {
  // x, 3 bytes of `_` padding, a 2-element int16 field, y z, label: PCL's layout rules.
  const std::string fields = "FIELDS x _ pair y z label\nSIZE 4 1 2 4 4 1\nTYPE F U I F F U\nCOUNT 1 3 2 1 1 1\n";
  std::string binary;
  for (int i = 0; i < 3; ++i)
    binary += raw(0.5f * i) + std::string(3, '\x7f') + raw<std::int16_t>(-1) + raw<std::int16_t>(2) + raw(1.0f * i) +
              raw(2.0f) + static_cast<char>(10 + i);
  std::string planes;  // compressed: `_` left out, one array per field
  for (int i = 0; i < 3; ++i) planes += raw(0.5f * i);
  for (int i = 0; i < 3; ++i) planes += raw<std::int16_t>(-1) + raw<std::int16_t>(2);
  for (int i = 0; i < 3; ++i) planes += raw(1.0f * i);
  for (int i = 0; i < 3; ++i) planes += raw(2.0f);
  for (int i = 0; i < 3; ++i) planes += static_cast<char>(10 + i);
  const std::vector<std::string> files = {
      pcd_header(fields, 3, 1, "binary") + binary,
      pcd_header(fields, 3, 1, "binary_compressed") +
          compressed_section(lzf_literals(planes), static_cast<std::uint32_t>(planes.size())),
      pcd_header(fields, 3, 1, "ascii") + "0 1 2 3 -1 2 0 2 10\n0.5 0 0 0 -1 2 1 2 11\n1 255 255 255 -1 2 2 2 12\n"};
  for (const std::string& file : files) {
    const LabelledCloud in = parse_pcd_text(file);
    ASSERT_EQ(in.cloud.size(), 3u);
    EXPECT_EQ(in.cloud.points[2], Eigen::Vector3f(1, 2, 2));
    EXPECT_EQ(*in.labels, (Labels{10, 11, 12}));
  }
}

TEST(IoPcd, LimitsAndNonRegularFiles) {
  const std::string four = pcd_header(kXyz, 2, 2, "ascii") + "1 2 3\n1 2 3\n1 2 3\n1 2 3\n";
  ReadLimits three;
  three.max_points = 3;
  expect_lccp_error([&] { parse_pcd_text(four, three); }, {"mem.pcd: too many points (4, limit 3)"});
  const fs::path dir = scratch_dir();
  write_bytes(dir / "four.pcd", four);
  ReadLimits small;
  small.max_file_bytes = 100;
  expect_lccp_error([&] { read_cloud(dir / "four.pcd", small); }, {"four.pcd", "file too large (", "limit 100)"});
  EXPECT_EQ(read_cloud(dir / "four.pcd").cloud.size(), 4u);
  ASSERT_EQ(::mkfifo((dir / "fifo.pcd").c_str(), 0600), 0);
  expect_read_error(dir / "fifo.pcd", "not a regular file");  // and no wait for a writer
  fs::create_symlink("/dev/null", dir / "null.ply");
  expect_read_error(dir / "null.ply", "not a regular file");
}

TEST(IoPcd, LongHeaderLinesAreRefusedNotStored) {
  std::string fields = "FIELDS x y z";
  for (int k = 0; k < 70000; ++k) fields += " f";
  expect_pcd_error(std::string(kAsciiHeader) + fields + "\nPOINTS 1\nDATA ascii\n1 2 3\n",
                   {"bad PCD header (more than 65536 words in FIELDS)"});
  const std::string comment = "# " + std::string(1 << 20, 'c') + "\n";  // comments are skipped, however long
  EXPECT_EQ(parse_pcd_text(comment + pcd_header(kXyz, 1, 1, "ascii") + "1 2 3\n").cloud.size(), 1u);
}

// ------------------------------------------------------------------- PLY

struct PlyVertex {
  float x, y, z;
  std::uint8_t r, g, b;
  float nx, ny, nz;
  std::int32_t label;
};

const std::vector<PlyVertex> kPlyVertices = {
    {1, 2, 3, 255, 0, 7, 0, 0, 1, 5}, {-1.5f, 0.25f, 8, 1, 2, 3, 1, 0, 0, 70000}, {4, 5, 6, 9, 8, 7, 0, 1, 0, 0}};

enum class Faces { none, before, after };

std::string ply_header(const std::string& format, Faces faces) {
  std::string header = "ply\nformat " + format + " 1.0\ncomment made by io_test\nobj_info faces " +
                       std::to_string(static_cast<int>(faces)) + "\n";
  const std::string face = "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\n";
  if (faces == Faces::before) header += face;
  header += "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
            "property uchar green\nproperty uchar blue\nproperty list ushort double extra\n"
            "property float nx\nproperty float ny\nproperty float nz\nproperty int label\n";
  if (faces == Faces::after) header += face;
  return header + "end_header\n";
}

// The same cloud as ascii, binary_little_endian or binary_big_endian, each
// vertex with a list of i doubles, the faces (0 1 2) and (2 1 0 1) around it.
std::string make_ply(const std::string& format, Faces faces) {
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  const auto put = [&](auto value) {
    if (ascii) return std::to_string(+value) + " ";
    return big ? raw_big_endian(value) : raw(value);
  };
  std::string face_data;
  for (const std::vector<std::int32_t>& face : {std::vector<std::int32_t>{0, 1, 2}, {2, 1, 0, 1}}) {
    face_data += put(static_cast<std::uint8_t>(face.size()));
    for (const std::int32_t index : face) face_data += put(index);
    face_data += put(std::uint8_t{1}) + (ascii ? "\n" : "");
  }
  std::string vertex_data;
  for (std::size_t i = 0; i < kPlyVertices.size(); ++i) {
    const PlyVertex& v = kPlyVertices[i];
    vertex_data += put(v.x) + put(v.y) + put(v.z) + put(v.r) + put(v.g) + put(v.b) + put(static_cast<std::uint16_t>(i));
    for (std::size_t k = 0; k < i; ++k) vertex_data += put(1e300);
    vertex_data += put(v.nx) + put(v.ny) + put(v.nz) + put(v.label) + (ascii ? "\n" : "");
  }
  return ply_header(format, faces) + (faces == Faces::before ? face_data + vertex_data
                                                               : vertex_data + (faces == Faces::after ? face_data : ""));
}

TEST(IoPly, EveryFormatWithFacesBeforeAndAfterVertices) {
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    for (const Faces faces : {Faces::none, Faces::before, Faces::after}) {
      SCOPED_TRACE(std::string(format) + " faces " + std::to_string(static_cast<int>(faces)));
      const LabelledCloud in = parse_ply_text(make_ply(format, faces));
      ASSERT_EQ(in.cloud.size(), 3u);
      EXPECT_EQ(in.cloud.width, 3u);
      EXPECT_EQ(in.cloud.height, 1u);
      ASSERT_EQ(in.cloud.normals.size(), 3u);
      ASSERT_TRUE(in.labels.has_value());
      for (std::size_t i = 0; i < 3; ++i) {
        const PlyVertex& v = kPlyVertices[i];
        EXPECT_EQ(in.cloud.points[i], Eigen::Vector3f(v.x, v.y, v.z)) << i;
        EXPECT_EQ(in.cloud.colors[i], std::uint32_t{v.r} << 16 | std::uint32_t{v.g} << 8 | v.b) << i;
        EXPECT_EQ(in.cloud.normals[i], Eigen::Vector3f(v.nx, v.ny, v.nz)) << i;
        EXPECT_EQ((*in.labels)[i], static_cast<std::uint32_t>(v.label)) << i;
      }
    }
  }
}

TEST(IoPly, TruncationsNeverCrash) {
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    for (const Faces faces : {Faces::before, Faces::after}) {
      const std::string file = make_ply(format, faces);
      for (std::size_t size = 0; size < file.size(); ++size) {
        SCOPED_TRACE(std::string(format) + " cut at " + std::to_string(size));
        try {
          parse_ply_text(file.substr(0, size));
          const bool only_spaces_cut = file.find_first_not_of(" \n", size) == std::string::npos;
          EXPECT_TRUE(std::string(format) == "ascii" && only_spaces_cut) << "a cut file was accepted";
        } catch (const Error& e) {
          EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
      }
    }
  }
}

TEST(IoPly, PackedColourAndViewport) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
  const LabelledCloud in = parse_ply_text(head + "property uint rgba\nelement camera 1\nproperty int viewportx\n"
                                          "property int viewporty\nend_header\n1 2 3 4278190335\n1 2 3 65280\n"
                                          "1 2 3 16711680\n1 2 3 0\n2 2\n");
  EXPECT_EQ(in.cloud.colors, (std::vector<std::uint32_t>{0x0000FFu, 0x00FF00u, 0xFF0000u, 0u}));
  EXPECT_EQ(in.cloud.width, 2u);
  EXPECT_EQ(in.cloud.height, 2u);
  const LabelledCloud flat = parse_ply_text(head + "element camera 1\nproperty int viewportx\nproperty int viewporty\n"
                                            "end_header\n1 2 3\n1 2 3\n1 2 3\n1 2 3\n3 2\n");
  EXPECT_EQ(flat.cloud.width, 4u);  // 3 x 2 does not cover 4 vertices
  EXPECT_EQ(flat.cloud.height, 1u);
}

TEST(IoPly, HeaderAndDataErrors) {
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string ok = "ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "end_header\n1 2 3\n";
  EXPECT_EQ(parse_ply_text(ok).cloud.size(), 1u);
  expect_ply_error("ply\nformat ascii 1.0\nelement face 1\nproperty uchar a\nend_header\n1\n", "no vertex element");
  expect_ply_error("ply\nformat ascii 2.0\nelement vertex 1\n" + xyz + "end_header\n1 2 3\n", "bad format line");
  expect_ply_error("ply\nformat binary_middle_endian 1.0\nelement vertex 1\n" + xyz + "end_header\n", "unknown format");
  expect_ply_error("ply\nelement vertex 1\n" + xyz + "end_header\n1 2 3\n", "no format line");
  expect_ply_error("ply\nformat ascii 1.0\nproperty float x\nend_header\n", "property before any element");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty int128 x\nend_header\n", "unknown property type 'int128'");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n", "list count type");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex -1\n" + xyz + "end_header\n", "bad element count '-1'");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "wibble\nend_header\n", "unknown header line 'wibble'");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz, "no end_header");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nproperty float y\nproperty float z\nend_header\n1 2 3\n",
                   "field 'x' is not floating point");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "property float red\nproperty float green\n"
                   "property float blue\nend_header\n1 2 3 1 1 1\n", "colour property 'red' is not uchar");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 2\n" + xyz + "end_header\n1 2 3\n4 5\n", "truncated PLY data");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "end_header\n1 2 x\n", "bad value 'x' in PLY data");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 0\n" + xyz + "end_header\n", "no points");
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 60000000\n" + xyz + "end_header\n1 2 3\n",
                   "too many points (60000000, limit 50000000)");
}

TEST(IoPly, HugeOrNegativeCountsFailFast) {
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string vertex = "element vertex 1\n" + xyz;
  const auto start = std::chrono::steady_clock::now();
  // A billion billion faces before the vertices: rejected by size, not by reading them.
  expect_ply_error("ply\nformat binary_little_endian 1.0\nelement face 1000000000000000000\n"
                   "property list uchar int vertex_indices\n" + vertex + "end_header\n" + std::string(64, '\0'),
                   "truncated PLY data");
  expect_ply_error("ply\nformat ascii 1.0\nelement face 1000000000000000000\nproperty list uchar int v\n" + vertex +
                   "end_header\n3 0 1 2\n1 2 3\n", "truncated PLY data");
  // Elements without properties take no bytes, however many.
  EXPECT_EQ(parse_ply_text("ply\nformat ascii 1.0\nelement nothing 18446744073709551615\n" + vertex +
                           "end_header\n1 2 3\n").cloud.size(), 1u);
  expect_ply_error("ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list char int v\n" + vertex +
                   "end_header\n\xff" + std::string(12, '\0'), "negative list length");
  expect_ply_error("ply\nformat binary_big_endian 1.0\nelement face 1\nproperty list uint uchar v\n" + vertex +
                   "end_header\n\xff\xff\xff\xff" + std::string(12, '\0'), "truncated PLY data");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
}

TEST(IoPly, HeaderSizeIsBounded) {
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  std::string many = "ply\nformat ascii 1.0\nelement vertex 1\n" + xyz;
  for (int k = 0; k < 5000; ++k) many += "property uchar p\n";
  expect_ply_error(many + "end_header\n", "too many properties");
  const std::string comment = "comment" + std::string(1 << 20, ' ') + "\n";
  EXPECT_EQ(parse_ply_text("ply\nformat ascii 1.0\n" + comment + "element vertex 1\n" + xyz + "end_header\n1 2 3\n")
                .cloud.size(), 1u);
  expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1 2 3 4 5 6 7 8\n" + xyz + "end_header\n", "bad element line");
}

// ---------------------------------------------------------------- config

TEST(IoConfig, NonScalarKeysAndValuesAreOneLineErrors) {
  for (const char* yaml : {"[a]: 1\n", "{x: 1}: 2\n", "? [a, b]\n: 3\n", "voxel_size_m: 0.005\n? {a: b}\n: 1\n"})
    expect_lccp_error([&] { parse_config(yaml, "c.yaml"); }, {"c.yaml: ", "a config key must be a plain name, not a list or map"});
  expect_lccp_error([] { parse_config("voxel_size_m: [1, 2]\n", "c.yaml"); }, {"c.yaml: ", "'voxel_size_m' needs a single value"});
  expect_lccp_error([] { parse_config("voxel_size_m: {a: 1}\n", "c.yaml"); }, {"'voxel_size_m' needs a single value"});
  expect_lccp_error([] { parse_config("voxel_size_m:\n", "c.yaml"); }, {"'voxel_size_m' needs a single value"});
  expect_lccp_error([] { parse_config("- a\n- b\n", "c.yaml"); }, {"c.yaml: expected a map of key: value"});
  expect_lccp_error([] { parse_config("just text\n", "c.yaml"); }, {"c.yaml: expected a map of key: value"});
  expect_lccp_error([] { parse_config("a: [1, 2\n", "c.yaml"); }, {"c.yaml: not valid YAML (line"});
  expect_lccp_error([] { parse_config(std::string(100000, '['), "c.yaml"); }, {"c.yaml: not valid YAML"});
  expect_lccp_error([] { parse_config("\"bad\\nkey\": 1\n", "c.yaml"); }, {"unknown config key 'bad?key'"});
  expect_lccp_error([] { parse_config("voxel_size_m: \"1\\n2\"\n", "c.yaml"); }, {"'1?2' is not a number"});
  EXPECT_EQ(parse_config("", "c.yaml").objects.voxels.voxel_size_m, LccpConfig{}.voxels.voxel_size_m);
  EXPECT_EQ(parse_config("voxel_size_m: 0.0075\nsanity_criterion: off\n", "c.yaml").objects.voxels.voxel_size_m, 0.0075f);
}

TEST(IoConfig, FileErrorsNameTheFile) {
  const fs::path dir = scratch_dir();
  write_bytes(dir / "key.yaml", "[a]: 1\n");
  expect_lccp_error([&] { load_config(dir / "key.yaml"); }, {(dir / "key.yaml").string() + ": ", "plain name"});
  expect_lccp_error([&] { load_config(dir / "absent.yaml"); }, {"absent.yaml: cannot open config file"});
  expect_lccp_error([&] { load_config(dir); }, {"cannot open config file"});
  write_bytes(dir / "big.yaml", "# " + std::string(2 << 20, 'x') + "\n");
  expect_lccp_error([&] { load_config(dir / "big.yaml"); }, {"big.yaml: config file larger than"});
  EXPECT_EQ(load_config(fs::path(LCCP_CONFIG_DIR) / "p2.yaml").objects.supervoxels.seed_size_m, 0.06f);
}

}  // namespace
}  // namespace lccp
