// read_cloud (the file, then the PCD or PLY parser by extension), the choice
// of labelled-cloud encoder by extension, and the atomic writers. The
// encoders are in pcd_format.cpp, ply_format.cpp and label_image.cpp.
#include "lccp/io/cloud_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
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

std::vector<std::uint8_t> encode_labelled_cloud(const std::filesystem::path& path_for_extension,
                                                const PointCloud& cloud, const Labels& labels, PcdEncoding encoding,
                                                const Labels* objects) {
  const std::string ext = lower_extension(path_for_extension);
  if (ext != ".pcd" && ext != ".ply")
    fail(path_for_extension,
         "unknown output format '" + path_for_extension.extension().string() + "' (use .pcd or .ply)");
  return encode_for(path_for_extension, [&] {
    return ext == ".pcd" ? encode_labelled_pcd(cloud, labels, encoding, objects)
                         : encode_labelled_ply(cloud, labels, objects);
  });
}

void write_labelled_pcd(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels,
                        PcdEncoding encoding, const Labels* objects) {
  write_file_atomically(path, encode_for(path, [&] { return encode_labelled_pcd(cloud, labels, encoding, objects); }));
}

void write_labelled_ply(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels,
                        const Labels* objects) {
  write_file_atomically(path, encode_for(path, [&] { return encode_labelled_ply(cloud, labels, objects); }));
}

void write_labelled_cloud(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels,
                          PcdEncoding encoding, const Labels* objects) {
  write_file_atomically(path, encode_labelled_cloud(path, cloud, labels, encoding, objects));
}

void write_label_png(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels,
                     LabelImageStyle style, const Labels* objects) {
  write_file_atomically(path, encode_for(path, [&] { return encode_label_png(cloud, labels, style, objects); }));
}

}  // namespace lccp
