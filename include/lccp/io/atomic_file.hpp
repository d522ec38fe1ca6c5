#pragma once
// Files that appear whole or not at all: the one way every writer in LCCP
// Stream creates a file.
//
// A PendingFile is an unnamed file in the target's folder (Linux O_TMPFILE,
// open(2)); it gets the target's name only on commit(). If the process dies
// first (an exception, Ctrl-C, kill -9), the kernel frees it and nothing is
// left behind. Where the file system has no O_TMPFILE, a file with an
// unpredictable name is created exclusively (O_CREAT | O_EXCL | O_NOFOLLOW)
// instead and removed if not committed. Neither way ever follows a symlink
// planted at a temporary name, and committing replaces a symlink at the
// target rather than writing through it. One exception: a target that exists
// and is not a regular file or folder (a device such as /dev/full, a FIFO, a
// socket, symlinks followed) or that names one of the process's own
// descriptors (/dev/stdout, /dev/fd/N, /proc/self/fd/N) is written into as it
// is, byte by byte, never replaced: its errors (ENOSPC on /dev/full) are the
// write's, and what was written before a failure stays written.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <span>
#include <string_view>
#include <vector>

namespace lccp {

class PendingFile {
 public:
  // Throws lccp::Error naming the target if its folder is missing or not writable.
  explicit PendingFile(std::filesystem::path target);
  // A pending file that has a (hidden, unpredictable) name from the start, for a
  // library that must open the file by path itself (openni::Recorder). A kill
  // before commit() leaves that hidden file behind.
  static PendingFile named(std::filesystem::path target);
  ~PendingFile();  // discards the file unless committed
  PendingFile(PendingFile&& other) noexcept;
  PendingFile& operator=(PendingFile&&) = delete;
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  void write(std::span<const std::uint8_t> bytes);  // throws lccp::Error on a short write
  void write(std::string_view text);
  // Gives the file its target name, atomically replacing any file there.
  void commit();

  const std::filesystem::path& target() const { return target_; }
  // The temporary name of a named() pending file (it ends like the target).
  const std::filesystem::path& temporary_path() const { return named_; }
  int descriptor() const { return fd_; }

 private:
  PendingFile(std::filesystem::path target, bool unnamed);
  bool open_in_place();  // a special file or own descriptor: fd_ is the target itself

  std::filesystem::path target_;
  std::filesystem::path named_;  // the temporary name, when O_TMPFILE is not available
  int fd_ = -1;
  bool committed_ = false;
  bool in_place_ = false;  // written into the target directly (open_in_place)
};

// True if a PendingFile for `path` writes into it in place: a device, FIFO or
// socket, or one of the process's own descriptors (/dev/stdout).
bool written_in_place(const std::filesystem::path& path);

// Writes bytes to path so that the file appears only when complete.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void write_file_atomically(const std::filesystem::path& path, std::string_view text);
// Writes what `write` puts on the stream, likewise (reports: JSON, CSV, HTML).
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

// Creates an output folder and its parents if missing: the one way every
// command makes one. Throws lccp::Error "cannot create output folder PATH:
// reason" when that fails or PATH exists and is not a folder.
void create_output_folder(const std::filesystem::path& path);

// One file of a set written together.
struct FileBytes {
  std::filesystem::path path;
  std::vector<std::uint8_t> bytes;
};

// Writes a set of files (one frame's outputs): all are written in full under
// no name first, so a failure while writing leaves none; then they get their
// names in the list's order, back to back. No program can make two names
// appear in one step (rename(2) moves one), so a kill -9 between two of those
// renames leaves only the list's first files: the last file marks a whole set,
// and callers list their main output (the labelled cloud) last.
void write_files_together(std::span<const FileBytes> files);

}  // namespace lccp
