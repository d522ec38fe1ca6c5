// What the command line promises a user, through the binary: output formats by
// extension, no silent fallback to the virtual sensor, counts that add up,
// truth only for the synthetic scene and in mOSD's labels, one-line errors with documented exit
// codes, --version, preset names, folders in and out, label images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

#include "cli_runner.hpp"
#include "test_clouds.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/synthetic/tabletop_scene.hpp"
#include "test_files.hpp"

namespace lccp {
namespace {

using namespace lccp::test;

const fs::path kData = LCCP_TEST_DATA_DIR;
const fs::path kScene = kData / "mosd_test2.pcd";
const fs::path kRecordings = fs::path(LCCP_CONFIG_DIR).parent_path() / "recordings";

class CliPromisesTest : public LccpBinaryTest {
 protected:
  CliPromisesTest() : LccpBinaryTest("lccp_cli_promises") {}
};

TEST_F(CliPromisesTest, SegmentWritesPlyWhenAskedAndRefusesUnknownExtensions) {
  const fs::path pcd = work_ / "out.pcd";
  const fs::path ply = work_ / "out.ply";
  expect_success(run({"segment", kScene.string(), "-o", pcd.string()}));
  expect_success(run({"segment", kScene.string(), "-o", ply.string()}));
  EXPECT_EQ(read_bytes(ply).rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  const LabelledCloud from_pcd = read_cloud(pcd);
  const LabelledCloud from_ply = read_cloud(ply);
  ASSERT_TRUE(from_pcd.labels && from_ply.labels);
  EXPECT_EQ(*from_pcd.labels, *from_ply.labels);
  EXPECT_NE(read_bytes(pcd).find("DATA binary_compressed"), std::string::npos) << "the default PCD encoding";

  expect_error(run({"segment", kScene.string(), "-o", (work_ / "out.xyz").string()}), {"out.xyz", ".pcd or .ply"});
  EXPECT_FALSE(fs::exists(work_ / "out.xyz"));
}

TEST_F(CliPromisesTest, SegmentTakesFilesOrAFolderAndWritesOneOutputEach) {
  const fs::path out = work_ / "many";
  const RunResult r = run({"segment", (kData / "mosd_test2.pcd").string(), (kData / "mosd_test60.pcd").string(), "-o",
                           out.string(), "--save", "pcd,png", "--quiet"});
  expect_success(r);
  EXPECT_EQ(list_dir(out), (std::set<std::string>{"mosd_test2.pcd", "mosd_test2.png", "mosd_test60.pcd",
                                                   "mosd_test60.png", "summary.json"}));
  const fs::path folder_out = work_ / "folder";
  expect_success(run({"segment", kData.string(), "-o", folder_out.string(), "--quiet"}));
  std::size_t pcds = 0;
  for (const auto& entry : fs::directory_iterator(kData)) pcds += entry.path().extension() == ".pcd";
  std::size_t written = 0;
  for (const std::string& name : list_dir(folder_out)) written += fs::path(name).extension() == ".pcd";
  EXPECT_EQ(written, pcds);
  // The same segments as one file at a time (the stream's ids stay stable from one file to the next).
  const fs::path single = work_ / "single.pcd";
  expect_success(run({"segment", (kData / "mosd_test60.pcd").string(), "-o", single.string()}));
  EXPECT_TRUE(same_partition(*read_cloud(single).labels, *read_cloud(out / "mosd_test60.pcd").labels));
}

TEST_F(CliPromisesTest, LiveWithoutASensorFailsInOneLineInsteadOfStreamingTheVirtualOne) {
  const fs::path out = work_ / "out";
  const RunResult r = run({"live", "--frames", "3", "-o", out.string()}, kQuickTimeoutSeconds);
  expect_error(r, {"no OpenNI2 depth sensor found", "virtual://synthetic"});
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliPromisesTest, DevicesListsTheVirtualSensorWithItsDepthModes) {
  const RunResult r = run({"devices"}, kQuickTimeoutSeconds);
  expect_success(r);
  EXPECT_NE(r.out.find("virtual://synthetic"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("LCCP Stream"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("640x480 @ 30 Hz"), std::string::npos) << r.out;
}

// A 30 Hz sensor against one thread, one frame in flight and 3 mm voxels: the
// table-top scene (300k points) then takes far longer than 33 ms a frame, so
// frames are dropped.
TEST_F(CliPromisesTest, LiveCountsAddUpWithDropsInEveryReport) {
  const fs::path out = work_ / "out";
  const RunResult r = run({"--threads", "1", "live", "--uri", "virtual://synthetic", "--frames", "40", "--inflight", "1",
                           "--set", "voxel_size_m=0.003", "-o", out.string(), "--quiet", "--log-level", "warn"});
  expect_success(r);
  const std::string summary = read_bytes(out / "summary.json");
  const auto n = [&](const char* key) { return static_cast<long>(json_number(summary, key)); };
  EXPECT_EQ(n("frames_received"), 40);
  EXPECT_GT(n("frames_dropped"), 0) << summary;
  expect_counts_add_up(summary, r.out);
}

TEST_F(CliPromisesTest, TruthRefusesARecordingOfAnythingButTheSyntheticScene) {
  const fs::path out = work_ / "truth";
  const RunResult r = run({"truth", (kRecordings / "mosd_scenes.oni").string(), "-o", out.string()});
  expect_error(r, {"mosd_scenes.oni", "not a recording of the synthetic scene"});
  EXPECT_FALSE(fs::exists(out));
}

// The truth of the synthetic recording in mOSD's labels: 0 no return, 1 table, 2
// floor and wall, object n's parts n * 10 + k, the mug's handle (51) its own part.
TEST_F(CliPromisesTest, TruthOfTheSyntheticRecordingLabelsObjectsAndTheirParts) {
  const fs::path out = work_ / "truth";
  expect_success(run({"truth", (kRecordings / "synthetic_tabletop.oni").string(), "-o", out.string()}));
  const std::set<std::uint32_t> known = {synthetic::kNoReturnLabel, synthetic::kTableLabel,
                                         synthetic::kBackgroundLabel,  10, 20, 30, 40, 50, 51};
  const std::set<std::string> files = list_dir(out);
  EXPECT_EQ(files.size(), 60u);
  std::size_t frames_with_handle = 0, sample = 0;
  for (const std::string& name : files) {
    if (sample++ % 5 != 0) continue;  // every 5th frame: 0, 5, ..., 55
    const LabelledCloud truth = read_cloud(out / name);
    ASSERT_TRUE(truth.labels) << name;
    std::size_t handle = 0;
    for (const std::uint32_t label : *truth.labels) {
      ASSERT_TRUE(known.count(label)) << name << " label " << label;
      handle += label == synthetic::object_label(synthetic::kMugObject, synthetic::kHandlePart);
    }
    frames_with_handle += handle >= 200;  // seen side-on in the first 1.5 s
  }
  EXPECT_GE(frames_with_handle, 3u);
  // The truth as a prediction: perfect for the parts; at object level the
  // handle is a segment split off the mug (5 objects a frame).
  const RunResult parts = run({"eval", out.string(), out.string(), "--ignore", "0-9", "--json"});
  expect_success(parts);
  EXPECT_DOUBLE_EQ(json_number(parts.out, "wov"), 1.0) << parts.out;
  EXPECT_GT(json_number(parts.out, "ground_truth_regions"), 300) << parts.out;
  const RunResult objects = run({"eval", out.string(), out.string(), "--ignore", "0-9", "--object-level", "--json"});
  expect_success(objects);
  EXPECT_DOUBLE_EQ(json_number(objects.out, "ground_truth_regions"), 300) << objects.out;
  EXPECT_LT(json_number(objects.out, "wov"), 1.0) << objects.out;
  EXPECT_GT(json_number(objects.out, "wov"), 0.97) << objects.out;
  EXPECT_DOUBLE_EQ(json_number(objects.out, "objects_lost"), 0) << objects.out;
}

TEST_F(CliPromisesTest, UsageErrorsAreOneLineWithExitTwo) {
  expect_usage_error(run({}, kQuickTimeoutSeconds), {"subcommand"});
  expect_usage_error(run({"segment", kScene.string(), "-o", (work_ / "x.pcd").string(), "--no-such-option"}, kQuickTimeoutSeconds), {"--no-such-option"});
  expect_usage_error(run({"replay"}, kQuickTimeoutSeconds), {"recording"});
  expect_usage_error(run({"replay", (kRecordings / "mosd_scenes.oni").string(), "--frames", "0"}, kQuickTimeoutSeconds),
                     {"--frames"});
  expect_usage_error(run({"live", "--uri", "virtual://synthetic", "--seconds", "0"}, kQuickTimeoutSeconds),
                     {"--seconds"});
  expect_usage_error(run({"replay", (kRecordings / "mosd_scenes.oni").string(), "--save", "pcd"}, kQuickTimeoutSeconds),
                     {"--save needs -o"});
}

TEST_F(CliPromisesTest, VersionAndHelpAreForPeople) {
  const RunResult version = run({"--version"}, kQuickTimeoutSeconds);
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out.rfind("lccp ", 0), 0u) << version.out;
  for (const char* command : {"segment", "replay", "live", "profile", "record", "truth", "eval", "devices"}) {
    const RunResult help = run({command, "--help"}, kQuickTimeoutSeconds);
    EXPECT_EQ(help.exit_code, 0) << command;
    for (const char* type : {"UINT", "INT in", "FLOAT", "TEXT:", ":POSITIVE", "[1 - "}) {
      EXPECT_EQ(help.out.find(type), std::string::npos) << command << " --help shows '" << type << "':\n" << help.out;
    }
  }
}

TEST_F(CliPromisesTest, ConfigTakesAPresetNameAsWellAsAPath) {
  const fs::path by_name = work_ / "by_name.pcd";
  const fs::path by_path = work_ / "by_path.pcd";
  expect_success(run({"segment", kScene.string(), "-o", by_name.string(), "--config", "p2"}));
  expect_success(run({"segment", kScene.string(), "-o", by_path.string(), "--config",
                      (fs::path(LCCP_CONFIG_DIR) / "p2.yaml").string()}));
  EXPECT_EQ(read_bytes(by_name), read_bytes(by_path));
  expect_error(run({"segment", kScene.string(), "-o", by_name.string(), "--config", "p9"}, kQuickTimeoutSeconds),
               {"p9", "no such preset"});
}

TEST_F(CliPromisesTest, OverlayLabelImageShowsTheSceneUnderTheLabels) {
  const fs::path labels = work_ / "labels.png";
  const fs::path overlay = work_ / "overlay.png";
  expect_success(run({"segment", kScene.string(), "-o", (work_ / "a.pcd").string(), "--png", labels.string()}));
  expect_success(run({"segment", kScene.string(), "-o", (work_ / "b.pcd").string(), "--png", overlay.string(), "--overlay"}));
  const std::string image = read_bytes(overlay);
  EXPECT_EQ(image.rfind("\x89PNG\r\n\x1a\n", 0), 0u);
  EXPECT_NE(image, read_bytes(labels));
}

}  // namespace
}  // namespace lccp
