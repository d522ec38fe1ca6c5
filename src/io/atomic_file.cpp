// PendingFile: O_TMPFILE and linkat(2) where the file system has them (see
// open(2), "O_TMPFILE"), else an exclusive file with a random name; commit
// renames over the target (rename(2) replaces the target's directory entry,
// a symlink included, and never follows it). A target that exists and is not
// a regular file (a device, a FIFO, a socket, or this process's own
// descriptor such as /dev/stdout) is written into instead, as cp(1) and a
// shell's redirection do: renaming over /dev/full would replace the device.
#include "lccp/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <optional>
#include <cstring>
#include <sstream>
#include <string>

#include "lccp/error.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

fs::path folder_of(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}

[[noreturn]] void fail(const fs::path& target, const std::string& what, int error) {
  throw Error(target.string() + ": cannot write (" + what + ": " + std::strerror(error) + ")");
}

// A hidden name beside the target that nobody can predict: 64 random bits.
fs::path random_name_beside(const fs::path& target) {
  std::uint64_t bits = 0;
  if (::getrandom(&bits, sizeof bits, 0) != sizeof bits) fail(target, "getrandom", errno);
  char suffix[24];
  std::snprintf(suffix, sizeof suffix, "%016llx", static_cast<unsigned long long>(bits));
  std::string name(".lccp-");
  name.append(suffix).append("-").append(target.filename().string());  // keeps the target's extension
  return folder_of(target) / name;
}

int open_named_exclusive(const fs::path& name) {
  return ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
}

// Gives an O_TMPFILE file a name: /proc/self/fd/N with AT_SYMLINK_FOLLOW is
// the unprivileged way (linkat(2)). Fails with EEXIST if the name is taken.
bool link_anonymous(int fd, const fs::path& name) {
  const std::string self = "/proc/self/fd/" + std::to_string(fd);
  return ::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0;
}

// The descriptor number N if `path` leads, through symlinks, to /proc/self/fd/N
// or /dev/fd/N (/dev/stdout is /proc/self/fd/1): one of this process's own
// open files, written through that descriptor (so its offset is shared).
std::optional<int> own_descriptor(fs::path path) {
  for (int hop = 0; hop < 8; ++hop) {
    const std::string text = path.lexically_normal().string();
    for (const std::string prefix : {"/proc/self/fd/", "/dev/fd/"}) {
      if (text.rfind(prefix, 0) != 0) continue;
      int fd = -1;
      const auto [end, error] = std::from_chars(text.data() + prefix.size(), text.data() + text.size(), fd);
      if (error == std::errc{} && end == text.data() + text.size()) return fd;
    }
    std::error_code ec;
    if (!fs::is_symlink(path, ec)) return std::nullopt;
    const fs::path link = fs::read_symlink(path, ec);
    if (ec) return std::nullopt;
    path = link.is_absolute() ? link : folder_of(path) / link;
  }
  return std::nullopt;
}

// An existing target that is not a regular file or folder (symlinks followed):
// a device, a FIFO, a socket. Such a file is written into, never replaced.
bool is_special_file(const fs::path& target) {
  struct stat st {};
  return ::stat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

}  // namespace

PendingFile::PendingFile(fs::path target) : PendingFile(std::move(target), true) {}

PendingFile PendingFile::named(fs::path target) { return PendingFile(std::move(target), false); }

PendingFile::PendingFile(fs::path target, bool unnamed) : target_(std::move(target)) {
  if (unnamed && open_in_place()) return;
  const fs::path folder = folder_of(target_);
  if (unnamed) fd_ = ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
  if (fd_ >= 0) return;  // mode 0644 less the umask, as for any new file
  const int error = errno;
  std::error_code ignored;
  if (!fs::is_directory(folder, ignored)) {
    throw Error(target_.string() + ": cannot write (folder '" + folder.string() + "' does not exist)");
  }
  if (unnamed && error != EOPNOTSUPP && error != EISDIR && error != EINVAL) fail(target_, "open", error);
  for (int attempt = 0; attempt < 8 && fd_ < 0; ++attempt) {
    named_ = random_name_beside(target_);
    fd_ = open_named_exclusive(named_);
    if (fd_ < 0 && errno != EEXIST) fail(target_, "open", errno);
  }
  if (fd_ < 0) fail(target_, "open", EEXIST);
}

// This process's own descriptor (/dev/stdout) or a device, FIFO or socket:
// written in place from the first byte (nothing to name on commit).
bool PendingFile::open_in_place() {
  if (const std::optional<int> own = own_descriptor(target_)) {
    fd_ = ::fcntl(*own, F_DUPFD_CLOEXEC, 0);
    if (fd_ < 0) fail(target_, "dup", errno);
  } else if (is_special_file(target_)) {
    fd_ = ::open(target_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0) fail(target_, "open", errno);
  } else {
    return false;
  }
  in_place_ = true;
  return true;
}

PendingFile::PendingFile(PendingFile&& other) noexcept
    : target_(std::move(other.target_)), named_(std::move(other.named_)), fd_(other.fd_), committed_(other.committed_),
      in_place_(other.in_place_) {
  other.fd_ = -1;
  other.named_.clear();
}

PendingFile::~PendingFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !named_.empty()) ::unlink(named_.c_str());
}

void PendingFile::write(std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(target_, "write", n < 0 ? errno : ENOSPC);
    done += static_cast<std::size_t>(n);
  }
}

void PendingFile::write(std::string_view text) {
  write(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void PendingFile::commit() {
  if (committed_) return;
  if (in_place_) {  // written as it went; a device may still refuse at close (a full disk over NFS)
    if (::close(fd_) != 0) fail(target_, "close", errno);
    fd_ = -1;
    committed_ = true;
    return;
  }
  if (named_.empty()) {
    // A new name: link it directly. An existing one: link under a random
    // name, then rename over the target.
    if (link_anonymous(fd_, target_)) {
      committed_ = true;
      return;
    }
    if (errno != EEXIST) fail(target_, "link", errno);
    for (int attempt = 0; attempt < 8 && named_.empty(); ++attempt) {
      const fs::path name = random_name_beside(target_);
      if (link_anonymous(fd_, name)) named_ = name;
      else if (errno != EEXIST) fail(target_, "link", errno);
    }
    if (named_.empty()) fail(target_, "link", EEXIST);
  }
  if (::rename(named_.c_str(), target_.c_str()) != 0) fail(target_, "rename", errno);
  committed_ = true;
}

bool written_in_place(const fs::path& path) { return own_descriptor(path) || is_special_file(path); }

void write_file_atomically(const fs::path& path, std::span<const std::uint8_t> bytes) {
  PendingFile file(path);
  file.write(bytes);
  file.commit();
}

void write_file_atomically(const fs::path& path, std::string_view text) {
  write_file_atomically(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  std::ostringstream text;
  write(text);
  write_file_atomically(path, std::string_view(text.view()));
}

void write_files_together(std::span<const FileBytes> files) {
  std::vector<PendingFile> pending;
  pending.reserve(files.size());
  for (const FileBytes& file : files) {
    pending.emplace_back(file.path);
    pending.back().write(file.bytes);
  }
  for (PendingFile& file : pending) file.commit();
}

void create_output_folder(const std::filesystem::path& path) {
  std::error_code error;
  std::filesystem::create_directories(path, error);
  if (std::filesystem::is_directory(path)) return;
  throw Error("cannot create output folder " + path.string() + ": " +
              (error ? error.message() : std::string("a file of that name exists")));
}

}  // namespace lccp
