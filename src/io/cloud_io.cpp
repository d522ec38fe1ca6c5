// read_cloud (the file, then the PCD or PLY parser by extension), the
// labelled-PCD and label-PNG encoders, and their atomic writers.
#include "lccp/io/cloud_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, const std::string& problem) {
  throw Error(path.string() + ": " + problem);
}

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Closes a file descriptor when it goes out of scope.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// The whole of a regular file of at most max_bytes. Opened without blocking
// (a FIFO would wait for a writer) and checked on the open descriptor, so a
// file swapped after a check is still caught. A file that shrinks while it
// is read yields the bytes that were there; the parsers check every length.
std::vector<std::uint8_t> read_regular_file(const fs::path& path, std::uint64_t max_bytes) {
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY));
  if (file.get() < 0) {
    if (errno == ENOENT) fail(path, "no such file");
    fail(path, std::string("cannot open (") + std::strerror(errno) + ")");
  }
  struct stat status {};
  if (::fstat(file.get(), &status) != 0) fail(path, std::string("cannot read (") + std::strerror(errno) + ")");
  if (S_ISDIR(status.st_mode)) fail(path, "is a directory, not a point cloud file");
  if (!S_ISREG(status.st_mode)) fail(path, "not a regular file");
  const auto size = static_cast<std::uint64_t>(status.st_size);
  if (size > max_bytes)
    fail(path, "file too large (" + std::to_string(size) + " bytes, limit " + std::to_string(max_bytes) + ")");
  std::vector<std::uint8_t> bytes(size);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(file.get(), bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path, std::string("cannot read (") + std::strerror(errno) + ")");
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  bytes.resize(done);
  return bytes;
}

// The problem with writing these labels for this cloud, or empty.
std::string labelled_cloud_problem(const PointCloud& cloud, const Labels& labels) {
  if (labels.size() != cloud.size()) return "labels and points differ in number";
  if (std::uint64_t{cloud.width} * cloud.height != cloud.size()) return "width x height != number of points";
  if (cloud.has_colors() && cloud.colors.size() != cloud.size()) return "colours and points differ in number";
  if (cloud.size() == 0) return "no points to write";
  return {};
}

void check_labelled_cloud(const PointCloud& cloud, const Labels& labels) {
  if (const std::string problem = labelled_cloud_problem(cloud, labels); !problem.empty()) throw Error(problem);
}

template <typename T>
void append(std::vector<std::uint8_t>& out, T value) {
  std::uint8_t bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);
  out.insert(out.end(), bytes, bytes + sizeof value);
}

// The header PCL's PCDWriter::generateHeaderBinary writes for these fields
// (io/src/pcd_io.cpp): rgb is a float field holding 0xAARRGGBB with alpha 255,
// the bytes of PCL's PointXYZRGB.
std::string labelled_pcd_header(const PointCloud& cloud) {
  std::string header = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n";
  header += cloud.has_colors() ? "FIELDS x y z rgb label\nSIZE 4 4 4 4 4\nTYPE F F F F U\nCOUNT 1 1 1 1 1\n"
                               : "FIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n";
  header += "WIDTH " + std::to_string(cloud.width) + "\nHEIGHT " + std::to_string(cloud.height) +
            "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(cloud.size()) + "\nDATA binary\n";
  return header;
}

// Minimal PNG encoder: 8-bit RGB, no interlace, filter type 0 on every row.
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(value >> shift));
}

void put_chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_u32(out, static_cast<std::uint32_t>(crc32(0, out.data() + start, static_cast<uInt>(out.size() - start))));
}

std::vector<std::uint8_t> deflate(const std::vector<std::uint8_t>& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> packed(size);
  if (compress2(packed.data(), &size, raw.data(), static_cast<uLong>(raw.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
    throw std::runtime_error("zlib compress2 failed");
  packed.resize(size);
  return packed;
}

std::vector<std::uint8_t> encode_png(std::uint32_t width, std::uint32_t height, const Labels& labels) {
  std::vector<std::uint8_t> raw;
  raw.reserve((1 + std::size_t{width} * 3) * height);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (i % width == 0) raw.push_back(0);  // filter type: none
    const auto rgb = label_color(labels[i]);
    raw.insert(raw.end(), rgb.begin(), rgb.end());
  }
  std::vector<std::uint8_t> header;
  put_u32(header, width);
  put_u32(header, height);
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bit, RGB, deflate, filter 0, no interlace
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  put_chunk(png, "IHDR", header);
  put_chunk(png, "IDAT", deflate(raw));
  put_chunk(png, "IEND", {});
  return png;
}

// Runs an encoder; its lccp::Error gets the path in front.
template <typename Encode>
std::vector<std::uint8_t> encode_for(const fs::path& path, Encode&& encode) {
  try {
    return encode();
  } catch (const Error& e) {
    fail(path, e.what());
  }
}

}  // namespace

LabelledCloud read_cloud(const std::filesystem::path& path, const ReadLimits& limits) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) fail(path, "no such file");
  if (fs::is_directory(status)) fail(path, "is a directory, not a point cloud file");
  const std::string ext = lower_extension(path);
  if (ext != ".pcd" && ext != ".ply") fail(path, "unsupported format '" + ext + "' (expected .pcd or .ply)");
  const std::vector<std::uint8_t> bytes = read_regular_file(path, limits.max_file_bytes);
  return ext == ".pcd" ? parse_pcd(bytes, path.string(), limits) : parse_ply(bytes, path.string(), limits);
}

std::vector<std::uint8_t> encode_labelled_pcd(const PointCloud& cloud, const Labels& labels) {
  check_labelled_cloud(cloud, labels);
  const std::string header = labelled_pcd_header(cloud);
  const std::size_t step = cloud.has_colors() ? 20 : 16;
  std::vector<std::uint8_t> out(header.begin(), header.end());
  out.reserve(header.size() + step * cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int k = 0; k < 3; ++k) append(out, cloud.points[i][k]);
    if (cloud.has_colors()) append(out, 0xFF000000u | cloud.colors[i]);
    append(out, labels[i]);
  }
  return out;
}

std::vector<std::uint8_t> encode_label_png(const PointCloud& cloud, const Labels& labels) {
  if (!cloud.organized()) throw Error("a label image needs an organized cloud");
  check_labelled_cloud(cloud, labels);
  return encode_png(cloud.width, cloud.height, labels);
}

void write_labelled_pcd(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels) {
  write_file_atomically(path, encode_for(path, [&] { return encode_labelled_pcd(cloud, labels); }));
}

void write_label_png(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels) {
  write_file_atomically(path, encode_for(path, [&] { return encode_label_png(cloud, labels); }));
}

// Hue steps by the golden ratio (Fibonacci hashing, exact in integers), so
// neighbouring ids land about 137 degrees apart; saturation cycles over three
// levels; value is fixed and high, so no label is ever black.
std::array<std::uint8_t, 3> label_color(std::uint32_t label) {
  if (label == 0) return {0, 0, 0};
  const double hue = static_cast<std::uint32_t>(label * 2654435769u) / 4294967296.0 * 6.0;  // [0, 6)
  const double saturation = 0.95 - 0.2 * (label % 3);
  const double value = 0.95;
  const double f = hue - std::floor(hue);
  const double p = value * (1 - saturation), q = value * (1 - saturation * f), t = value * (1 - saturation * (1 - f));
  const double rgb[6][3] = {{value, t, p}, {q, value, p}, {p, value, t}, {p, q, value}, {t, p, value}, {value, p, q}};
  const auto& c = rgb[static_cast<int>(hue) % 6];
  const auto byte = [](double x) { return static_cast<std::uint8_t>(std::lround(x * 255.0)); };
  return {byte(c[0]), byte(c[1]), byte(c[2])};
}

}  // namespace lccp
