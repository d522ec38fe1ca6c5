// PendingFile and write_files_together: files appear whole or not at all, no
// temporary name is left behind, and no symlink is ever written through.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace lccp
