#pragma once
// A file's bytes, mapped read-only (mmap(2)) for the lifetime of the object.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

namespace lccp::detail {

class MappedFile {
 public:
  // Throws lccp::Error naming the path when it cannot be opened or mapped.
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::span<const std::uint8_t> bytes() const { return {data_, size_}; }

 private:
  int fd_ = -1;
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace lccp::detail
