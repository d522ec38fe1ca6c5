#include "mapped_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "lccp/error.hpp"

namespace lccp::detail {

MappedFile::MappedFile(const std::filesystem::path& path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error("cannot open " + path.string() + ": " + std::strerror(errno));
  struct stat info {};
  if (::fstat(fd_, &info) == 0) {
    size_ = static_cast<std::size_t>(info.st_size);
    void* data = size_ == 0 ? nullptr : ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd_, 0);
    if (data != MAP_FAILED) {
      data_ = static_cast<const std::uint8_t*>(data);
      return;
    }
  }
  const std::string reason = std::strerror(errno);
  ::close(fd_);
  throw Error("cannot read " + path.string() + ": " + reason);
}

MappedFile::~MappedFile() {
  if (data_ != nullptr) ::munmap(const_cast<std::uint8_t*>(data_), size_);
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace lccp::detail
