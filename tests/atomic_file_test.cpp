// PendingFile and write_files_together: files appear whole or not at all, no
// temporary name is left behind, and no symlink is ever written through.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"
#include "test_files.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

TEST(AtomicFile, NothingIsVisibleBeforeCommitAndNothingIsLeftWithoutIt) {
  const fs::path dir = test::scratch_dir("atomic");
  {
    PendingFile file(dir / "out.pcd");
    file.write(std::string_view("half of a file"));
    EXPECT_EQ(entries(dir), std::vector<std::string>{}) << "a pending file must have no name in the folder";
  }
  EXPECT_EQ(entries(dir), std::vector<std::string>{}) << "an uncommitted file must leave nothing";
}

TEST(AtomicFile, CommitGivesTheWholeFileItsNameOnly) {
  const fs::path dir = test::scratch_dir("atomic");
  write_file_atomically(dir / "summary.json", std::string_view("{\"frames\": 3}\n"));
  EXPECT_EQ(entries(dir), std::vector<std::string>{"summary.json"});
  EXPECT_EQ(test::read_bytes(dir / "summary.json"), "{\"frames\": 3}\n");
}

TEST(AtomicFile, AnExistingFileIsReplacedWhole) {
  const fs::path dir = test::scratch_dir("atomic");
  test::write_bytes(dir / "out.png", "old contents, longer than the new ones");
  write_file_atomically(dir / "out.png", bytes_of("new"));
  EXPECT_EQ(test::read_bytes(dir / "out.png"), "new");
  EXPECT_EQ(entries(dir), std::vector<std::string>{"out.png"});
}

TEST(AtomicFile, ASymlinkAtTheTargetIsReplacedNotWrittenThrough) {
  const fs::path dir = test::scratch_dir("atomic");
  test::write_bytes(dir / "victim", "precious");
  fs::create_symlink(dir / "victim", dir / "out.pcd");
  write_file_atomically(dir / "out.pcd", bytes_of("labels"));
  EXPECT_EQ(test::read_bytes(dir / "victim"), "precious");
  EXPECT_FALSE(fs::is_symlink(dir / "out.pcd"));
  EXPECT_EQ(test::read_bytes(dir / "out.pcd"), "labels");
}

TEST(AtomicFile, AMissingFolderIsOneLineNamingIt) {
  const fs::path dir = test::scratch_dir("atomic");
  try {
    write_file_atomically(dir / "no-such-folder" / "out.pcd", bytes_of("x"));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("no-such-folder"), std::string::npos) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(AtomicFile, AFrameSetAppearsWholeWithNothingElse) {
  const fs::path dir = test::scratch_dir("atomic");
  test::write_bytes(dir / "frame_1.png", "stale");
  const std::vector<FileBytes> files{{dir / "frame_1.pcd", bytes_of("cloud")}, {dir / "frame_1.png", bytes_of("image")}};
  write_files_together(files);
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"frame_1.pcd", "frame_1.png"}));
  EXPECT_EQ(test::read_bytes(dir / "frame_1.pcd"), "cloud");
  EXPECT_EQ(test::read_bytes(dir / "frame_1.png"), "image");
}

TEST(AtomicFile, ASetWithAnUnwritableMemberWritesNone) {
  const fs::path dir = test::scratch_dir("atomic");
  const std::vector<FileBytes> files{{dir / "frame_1.pcd", bytes_of("cloud")},
                                     {dir / "missing" / "frame_1.png", bytes_of("image")}};
  EXPECT_THROW(write_files_together(files), Error);
  EXPECT_EQ(entries(dir), std::vector<std::string>{});
}

TEST(AtomicFile, ASetIsNamedInItsOrderSoTheLastFileMarksAWholeSet) {
  const fs::path dir = test::scratch_dir("atomic");
  fs::create_directories(dir / "frame_1.pcd" / "in_the_way");  // the last name cannot be given
  const std::vector<FileBytes> files{{dir / "frame_1.png", bytes_of("image")}, {dir / "frame_1.pcd", bytes_of("cloud")}};
  EXPECT_THROW(write_files_together(files), Error);
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"frame_1.pcd", "frame_1.png"}));  // no hidden file left
  EXPECT_TRUE(fs::is_directory(dir / "frame_1.pcd"));
  EXPECT_EQ(test::read_bytes(dir / "frame_1.png"), "image");
}

TEST(AtomicFile, ANamedPendingFileIsHiddenUnpredictableAndRemovedUnlessCommitted) {
  const fs::path dir = test::scratch_dir("atomic");
  fs::path first;
  {
    PendingFile file = PendingFile::named(dir / "take.oni");
    first = file.temporary_path();
    EXPECT_EQ(first.parent_path(), dir);
    EXPECT_EQ(first.filename().string().front(), '.');
    EXPECT_EQ(first.extension(), ".oni") << "a library may choose its format by the extension";
    EXPECT_TRUE(fs::exists(first));
  }
  EXPECT_EQ(entries(dir), std::vector<std::string>{});
  PendingFile file = PendingFile::named(dir / "take.oni");
  EXPECT_NE(file.temporary_path(), first);
  test::write_bytes(file.temporary_path(), "written by a library");
  file.commit();
  EXPECT_EQ(entries(dir), std::vector<std::string>{"take.oni"});
  EXPECT_EQ(test::read_bytes(dir / "take.oni"), "written by a library");
}

// A device with /dev/full's numbers (Linux: char 1, 7; every write fails with
// ENOSPC) made in `dir`, so that a failing test never touches /dev/full itself.
// Root may make one (the tests run as root, as CI does); elsewhere /dev/full.
fs::path full_device(const fs::path& dir) {
  const fs::path path = dir / "full";
  if (::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, 7)) == 0) return path;
  return "/dev/full";
}

// A device is written into and never replaced: a full one fails as a write does.
TEST(AtomicFile, ADeviceIsWrittenIntoNeverReplaced) {
  const fs::path dir = test::scratch_dir("atomic");
  const fs::path full = full_device(dir);
  try {
    write_file_atomically(full, bytes_of("labels"));
    ADD_FAILURE() << "no error writing to a full device";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_character_file(full)) << full << " was replaced";
  write_file_atomically(dir / "null_like", bytes_of("a regular file beside it is unaffected"));
}

// A FIFO is written into (a reader gets the bytes), not replaced by a file.
TEST(AtomicFile, AFifoIsWrittenIntoNeverReplaced) {
  const fs::path dir = test::scratch_dir("atomic");
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // so the writer's open does not wait
  ASSERT_GE(reader, 0);
  write_file_atomically(fifo, std::string_view("{\"frames\": 3}\n"));
  char buffer[64] = {};
  const ssize_t n = ::read(reader, buffer, sizeof buffer);
  ::close(reader);
  EXPECT_EQ(std::string(buffer, n > 0 ? static_cast<std::size_t>(n) : 0), "{\"frames\": 3}\n");
  EXPECT_TRUE(fs::is_fifo(fifo)) << "the FIFO was replaced";
  EXPECT_EQ(entries(dir), std::vector<std::string>{"pipe"});
}

}  // namespace
}  // namespace lccp
