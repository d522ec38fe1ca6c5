// End-to-end tests of the `lccp` command line: the real binary is run on real
// scenes and on broken inputs, with stdout, stderr and the exit status captured.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cli_runner.hpp"
#include "test_files.hpp"
#include "lccp/cloud.hpp"
#include "lccp/io/cloud_io.hpp"

namespace lccp {
namespace {

using namespace test;  // run_lccp, expect_error and the other runner helpers

namespace fs = std::filesystem;

const fs::path kData = LCCP_TEST_DATA_DIR;
const fs::path kConfig = LCCP_CONFIG_DIR;
const fs::path kOrganizedScene = kData / "mosd_test2.pcd";    // 640 x 480, has a GT label field
const fs::path kUnorganizedScene = kData / "mosd_test43.pcd";  // 170986 x 1

// Header keyword -> its words, up to and including DATA.
std::map<std::string, std::vector<std::string>> pcd_header(const fs::path& path) {
  std::map<std::string, std::vector<std::string>> header;
  std::ifstream in(path, std::ios::binary);
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string key;
    if (!(words >> key) || key[0] == '#') continue;
    std::vector<std::string>& values = header[key];
    for (std::string word; words >> word;) values.push_back(word);
    if (key == "DATA") break;
  }
  return header;
}

std::uint32_t big_endian_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) value = (value << 8) | static_cast<unsigned char>(bytes.at(at + i));
  return value;
}

// An ascii PCD with the given fields (all float, 4 bytes) and point rows.
std::string ascii_pcd(const std::vector<std::string>& fields, std::uint32_t width, std::uint32_t height,
                      const std::vector<std::string>& rows) {
  std::string names, sizes, types, counts;
  for (const std::string& field : fields) {
    names += " " + field;
    sizes += " 4";
    types += " F";
    counts += " 1";
  }
  std::string text = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS" + names + "\nSIZE" + sizes +
                     "\nTYPE" + types + "\nCOUNT" + counts + "\nWIDTH " + std::to_string(width) + "\nHEIGHT " +
                     std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(width * height) +
                     "\nDATA ascii\n";
  for (const std::string& row : rows) text += row + "\n";
  return text;
}

// Each test gets a fresh folder: `work_` holds inputs the test writes and the
// outputs lccp writes; the captured stdout/stderr live beside it.
class CliTest : public LccpBinaryTest {
 protected:
  CliTest() : LccpBinaryTest("lccp_cli") {}

  fs::path out_pcd() const { return work_ / "out.pcd"; }
  fs::path out_png() const { return work_ / "out.png"; }

  // `lccp segment INPUT -o OUT.pcd --png OUT.png EXTRA...` must fail with one
  // line naming the problem and leave the work folder as it was.
  void expect_segment_fails(const fs::path& input, const std::vector<std::string>& extra,
                            std::initializer_list<std::string> phrases) {
    const std::set<std::string> before = list_dir(work_);
    std::vector<std::string> args = {"segment", input.string(), "-o", out_pcd().string(), "--png",
                                     out_png().string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run(args);
    expect_error(r, phrases);
    EXPECT_EQ(list_dir(work_), before) << "files left behind by: " << r.command;
  }

  // Segments the organized scene into out.pcd (and out.png); returns the summary line.
  std::string segment_scene(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = {"segment", kOrganizedScene.string(), "-o", out_pcd().string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run(args);
    expect_success(r);
    return r.out;
  }

};

// --- A. bad inputs: one line, exit 1, nothing written ------------------------------

TEST_F(CliTest, MissingInputFile) {
  expect_segment_fails(work_ / "absent.pcd", {}, {"absent.pcd", "no such file"});
}

TEST_F(CliTest, TextFileIsNotAPointCloud) {
  write_bytes(work_ / "x.pcd", "hello, this is not a point cloud\nsecond line\n");
  expect_segment_fails(work_ / "x.pcd", {}, {"x.pcd", "not a point cloud"});
}

TEST_F(CliTest, PngRenamedToPcdIsNotAPointCloud) {
  // A complete 1 x 1 RGBA PNG.
  const unsigned char png[] = {0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48,
                               0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00,
                               0x00, 0x1F, 0x15, 0xC4, 0x89, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x44, 0x41, 0x54, 0x78,
                               0x9C, 0x63, 0x00, 0x01, 0x00, 0x00, 0x05, 0x00, 0x01, 0x0D, 0x0A, 0x2D, 0xB4, 0x00,
                               0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};
  write_bytes(work_ / "image.pcd", std::string(std::begin(png), std::end(png)));
  expect_segment_fails(work_ / "image.pcd", {}, {"image.pcd", "not a point cloud"});
}

TEST_F(CliTest, TruncatedPcd) {
  const std::string scene = read_bytes(kOrganizedScene);
  ASSERT_GT(scene.size(), 1000u);
  write_bytes(work_ / "half.pcd", scene.substr(0, scene.size() / 2));
  write_bytes(work_ / "head.pcd", scene.substr(0, 200));
  expect_segment_fails(work_ / "half.pcd", {}, {"half.pcd", "truncated"});
  expect_segment_fails(work_ / "head.pcd", {}, {"head.pcd", "truncated"});
}

TEST_F(CliTest, PcdWithoutXyzFields) {
  write_bytes(work_ / "abc.pcd", ascii_pcd({"a", "b", "c"}, 2, 2, {"1 2 3", "4 5 6", "7 8 9", "1 1 1"}));
  expect_segment_fails(work_ / "abc.pcd", {}, {"abc.pcd", "no x/y/z"});
}

TEST_F(CliTest, EmptyCloud) {
  write_bytes(work_ / "empty.pcd", ascii_pcd({"x", "y", "z"}, 0, 1, {}));
  expect_segment_fails(work_ / "empty.pcd", {}, {"no points"});
}

TEST_F(CliTest, AllNanCloud) {
  // Organized, so that --png is legal and the empty content is what fails.
  write_bytes(work_ / "nan.pcd", ascii_pcd({"x", "y", "z"}, 2, 2, std::vector<std::string>(4, "nan nan nan")));
  expect_segment_fails(work_ / "nan.pcd", {}, {"no finite points"});
}

TEST_F(CliTest, VoxelSizeNotPositive) {
  expect_segment_fails(kOrganizedScene, {"--set", "voxel_size_m=0"}, {"voxel_size_m"});
  expect_segment_fails(kOrganizedScene, {"--set", "voxel_size_m=-0.01"}, {"voxel_size_m"});
}

TEST_F(CliTest, SeedSmallerThanVoxel) {
  expect_segment_fails(kOrganizedScene, {"--set", "seed_size_m=0.001"}, {"seed_size_m"});
}

TEST_F(CliTest, UnknownConfigKeyInSet) {
  expect_segment_fails(kOrganizedScene, {"--set", "bogus=1"}, {"unknown config key", "bogus"});
}

TEST_F(CliTest, UnknownConfigKeyInYaml) {
  write_bytes(work_ / "bogus.yaml", "voxel_size_m: 0.005\nbogus: 1\n");
  expect_segment_fails(kOrganizedScene, {"--config", (work_ / "bogus.yaml").string()},
                       {"bogus.yaml", "unknown config key", "bogus"});
}

TEST_F(CliTest, NonNumericValueInYaml) {
  write_bytes(work_ / "words.yaml", "voxel_size_m: five millimetres\n");
  expect_segment_fails(kOrganizedScene, {"--config", (work_ / "words.yaml").string()},
                       {"words.yaml", "voxel_size_m", "not a number"});
}

TEST_F(CliTest, MissingConfigFile) {
  expect_segment_fails(kOrganizedScene, {"--config", (work_ / "absent.yaml").string()}, {"absent.yaml", "cannot open"});
}

TEST_F(CliTest, UnwritablePngRemovesThePcdAlreadyWritten) {
  const std::set<std::string> before = list_dir(work_);
  const RunResult r = run({"segment", kOrganizedScene.string(), "-o", out_pcd().string(), "--png",
                           (work_ / "absent_folder" / "out.png").string()});
  expect_error(r, {"out.png", "does not exist"});
  EXPECT_EQ(list_dir(work_), before) << "files left behind by: " << r.command;
}

TEST_F(CliTest, NumberBeyondAFloatIsOutOfRange) {
  write_bytes(work_ / "huge.yaml", "voxel_size_m: 1e308\n");
  expect_segment_fails(kOrganizedScene, {"--config", (work_ / "huge.yaml").string()},
                       {"huge.yaml", "voxel_size_m", "1e308", "out of range"});
  expect_segment_fails(kOrganizedScene, {"--set", "max_points=4294967296"}, {"max_points", "out of range"});
}

// A device at the output path is written into, never replaced by a file: a full
// one fails with the write's error, and the device stays.
TEST_F(CliTest, FullDeviceAsOutputFailsAndStaysADevice) {
  const fs::path full = root_ / "full";  // /dev/full's numbers, beside the work folder
  const fs::path device = ::mknod(full.c_str(), S_IFCHR | 0666, makedev(1, 7)) == 0 ? full : fs::path("/dev/full");
  for (const char* option : {"--png", "--segments"}) {
    SCOPED_TRACE(option);
    const std::set<std::string> before = list_dir(work_);
    expect_error(run({"segment", kOrganizedScene.string(), "-o", out_pcd().string(), option, device.string()}),
                 {device.string(), "No space left on device"});
    EXPECT_TRUE(fs::is_character_file(device)) << device << " was replaced";
    EXPECT_EQ(list_dir(work_), before);
  }
}

// /dev/stdout is this process's standard output: the JSON goes there, then the summary.
TEST_F(CliTest, SegmentsToStandardOutput) {
  const RunResult r = run({"segment", kOrganizedScene.string(), "-o", out_pcd().string(), "--segments", "/dev/stdout"});
  expect_success(r);
  EXPECT_EQ(r.out.rfind("{\"frame\":0,", 0), 0u) << r.out.substr(0, 200);
  const std::size_t summary = r.out.find("points 307200");
  ASSERT_NE(summary, std::string::npos) << r.out.substr(0, 200);
  EXPECT_GT(summary, 1000u) << "the summary did not follow the JSON";
  EXPECT_TRUE(fs::is_symlink("/dev/stdout"));
}

// In a batch, an input that fails leaves no output, is named in its error line
// and makes the exit status 1; the other inputs complete.
TEST_F(CliTest, FailedInputOfABatchLeavesNoOutputAndFailsTheRun) {
  write_bytes(work_ / "far.pcd", ascii_pcd({"x", "y", "z"}, 3, 1, {"0 0 1", "0 0.01 1", "600 0 1"}));
  const fs::path out = work_ / "out";
  const RunResult r = run({"segment", (work_ / "far.pcd").string(), kOrganizedScene.string(), "-o", out.string()});
  SCOPED_TRACE(describe(r));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("lccp: error: " + (work_ / "far.pcd").string() + ": ", 0), 0u);
  EXPECT_NE(r.err.find("max_coordinate_m"), std::string::npos);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  EXPECT_NE(r.out.find("2 received + 0 sensor gaps = 1 completed + 1 failed"), std::string::npos);
  EXPECT_EQ(list_dir(out), (std::set<std::string>{"mosd_test2.pcd", "summary.json"}));
}

// --- B. happy path ----------------------------------------------------------------

TEST_F(CliTest, SegmentsOrganizedSceneToPcdAndPng) {
  const RunResult r = run({"segment", kOrganizedScene.string(), "-o", out_pcd().string(), "--png", out_png().string()});
  expect_success(r);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_NE(r.out.find("segments"), std::string::npos) << r.out;
  EXPECT_EQ(list_dir(work_), (std::set<std::string>{"out.pcd", "out.png"}));

  // Header: a uint32 label field, organized 640 x 480.
  const auto header = pcd_header(out_pcd());
  const auto& fields = header.count("FIELDS") ? header.at("FIELDS") : std::vector<std::string>{};
  const auto label = std::find(fields.begin(), fields.end(), "label");
  ASSERT_NE(label, fields.end()) << "no label field in " << out_pcd();
  const auto index = static_cast<std::size_t>(label - fields.begin());
  ASSERT_TRUE(header.count("TYPE") && header.count("SIZE")) << "no TYPE or SIZE line";
  ASSERT_LT(index, header.at("TYPE").size());
  ASSERT_LT(index, header.at("SIZE").size());
  EXPECT_EQ(header.at("TYPE")[index], "U");
  EXPECT_EQ(header.at("SIZE")[index], "4");
  EXPECT_EQ(header.count("WIDTH") ? header.at("WIDTH") : std::vector<std::string>{}, std::vector<std::string>{"640"});
  EXPECT_EQ(header.count("HEIGHT") ? header.at("HEIGHT") : std::vector<std::string>{}, std::vector<std::string>{"480"});

  // Content: the input's points in place; 0 exactly on non-finite points;
  // labels dense 1..K, K as in the summary.
  const LabelledCloud input = read_cloud(kOrganizedScene);
  const LabelledCloud output = read_cloud(out_pcd());
  ASSERT_TRUE(output.labels.has_value());
  ASSERT_EQ(output.cloud.size(), input.cloud.size());
  EXPECT_EQ(output.cloud.width, 640u);
  EXPECT_EQ(output.cloud.height, 480u);
  std::vector<std::size_t> segment_sizes;
  std::size_t finite = 0, mislabelled = 0, moved = 0;
  for (std::size_t i = 0; i < output.cloud.size(); ++i) {
    const bool is_point = is_finite(output.cloud.points[i]);
    const std::uint32_t l = (*output.labels)[i];
    finite += is_point;
    mislabelled += is_point != (l != 0);
    moved += is_point != is_finite(input.cloud.points[i]) ||
             (is_point && output.cloud.points[i] != input.cloud.points[i]);
    if (l >= segment_sizes.size()) segment_sizes.resize(l + 1, 0);
    ++segment_sizes[l];
  }
  EXPECT_EQ(mislabelled, 0u) << "points whose label is 0 iff they are finite is violated";
  EXPECT_EQ(moved, 0u) << "output points differ from the input's";
  EXPECT_EQ(finite, summary_count(r.out, "finite"));
  const std::size_t k = segment_sizes.empty() ? 0 : segment_sizes.size() - 1;
  EXPECT_GE(k, 1u);
  EXPECT_EQ(k, summary_count(r.out, "segments"));
  for (std::size_t l = 1; l <= k; ++l) {
    EXPECT_GT(segment_sizes[l], 0u) << "label " << l << " unused: labels are not dense 1.." << k;
  }

  // PNG: signature, then IHDR with 640 x 480.
  const std::string png = read_bytes(out_png());
  ASSERT_GE(png.size(), 33u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(big_endian_u32(png, 16), 640u);
  EXPECT_EQ(big_endian_u32(png, 20), 480u);
}

TEST_F(CliTest, PngOfUnorganizedCloudFails) {
  expect_segment_fails(kUnorganizedScene, {}, {"mosd_test43.pcd", "organized"});
}

TEST_F(CliTest, ThreadCountDoesNotChangeOutput) {
  const fs::path one = work_ / "one.pcd", two = work_ / "two.pcd";
  expect_success(run({"--threads", "1", "segment", kOrganizedScene.string(), "-o", one.string()}));
  expect_success(run({"--threads", "2", "segment", kOrganizedScene.string(), "-o", two.string()}));
  const std::string bytes_one = read_bytes(one);
  EXPECT_FALSE(bytes_one.empty());
  EXPECT_TRUE(bytes_one == read_bytes(two)) << "--threads 1 and --threads 2 give different files";
}

// README: `lccp segment IN.pcd -o OUT.pcd [...] [--threads N]`.
TEST_F(CliTest, ThreadsOptionAfterSubcommandAsDocumented) {
  const fs::path one = work_ / "one.pcd";
  const RunResult r = run({"segment", kOrganizedScene.string(), "-o", one.string(), "--threads", "1"});
  expect_success(r);
  ASSERT_EQ(r.exit_code, 0) << "the documented position of --threads is rejected";
  segment_scene();
  const std::string bytes_one = read_bytes(one);
  EXPECT_FALSE(bytes_one.empty());
  EXPECT_TRUE(bytes_one == read_bytes(out_pcd())) << "--threads 1 output differs from the default run's";
}

TEST_F(CliTest, PresetP2GivesFewerSupervoxelsThanP1) {
  const std::string p1 = segment_scene({"--config", (kConfig / "p1.yaml").string()});
  const std::string p2 = segment_scene({"--config", (kConfig / "p2.yaml").string()});
  const unsigned long p1_supervoxels = summary_count(p1, "supervoxels");
  const unsigned long p2_supervoxels = summary_count(p2, "supervoxels");
  EXPECT_GT(p2_supervoxels, 0u);
  EXPECT_LT(p2_supervoxels, p1_supervoxels) << "P1: " << p1 << "P2: " << p2;
}

// README: segments numbered 1..K. Stable ids belong to a stream; the files of a
// batch are unrelated clouds, each numbered 1..K of its own.
TEST_F(CliTest, EachFileOfABatchHasLabelsOneToK) {
  const fs::path out = work_ / "out";
  for (const std::string config : {"p1", "robot"}) {
    SCOPED_TRACE(config);
    fs::remove_all(out);
    expect_success(run({"segment", kOrganizedScene.string(), (kData / "mosd_test34.pcd").string(), "-o", out.string(),
                        "--config", config, "--quiet"}));
    for (const char* name : {"mosd_test2.pcd", "mosd_test34.pcd"}) {
      SCOPED_TRACE(name);
      const fs::path single = work_ / (std::string("single_") + name);
      expect_success(run({"segment", (kData / name).string(), "-o", single.string(), "--config", config}));
      const LabelledCloud batch = read_cloud(out / name), alone = read_cloud(single);
      ASSERT_TRUE(batch.labels && alone.labels);
      EXPECT_EQ(*batch.labels, *alone.labels) << "a file of a batch is labelled as it is alone";
      std::set<std::uint32_t> used(batch.labels->begin(), batch.labels->end());
      used.erase(0);
      ASSERT_FALSE(used.empty());
      EXPECT_EQ(*used.begin(), 1u);
    }
  }
}

// --- C. eval ----------------------------------------------------------------------

TEST_F(CliTest, EvalOfSegmentationScoresAboveFloor) {
  segment_scene();
  const RunResult r = run({"eval", out_pcd().string(), kOrganizedScene.string(), "--ignore", "0-9", "--json"});
  expect_success(r);
  ASSERT_GE(r.out.size(), 2u);
  EXPECT_EQ(r.out.front(), '{') << r.out;
  EXPECT_EQ(r.out.substr(r.out.size() - 2), "}\n") << r.out;
  EXPECT_GT(json_number(r.out, "wov"), 0.9) << r.out;
}

TEST_F(CliTest, EvalOfGroundTruthAgainstItselfIsPerfect) {
  const RunResult r = run({"eval", kOrganizedScene.string(), kOrganizedScene.string(), "--ignore", "0-9", "--json"});
  expect_success(r);
  EXPECT_DOUBLE_EQ(json_number(r.out, "wov"), 1.0) << r.out;
  EXPECT_DOUBLE_EQ(json_number(r.out, "fp"), 0.0) << r.out;
}

TEST_F(CliTest, EvalOfCloudWithoutLabelsFails) {
  write_bytes(work_ / "plain.pcd", ascii_pcd({"x", "y", "z"}, 2, 1, {"0 0 1", "0 0.01 1"}));
  expect_error(run({"eval", (work_ / "plain.pcd").string(), kOrganizedScene.string()}), {"plain.pcd", "no label"});
  expect_error(run({"eval", kOrganizedScene.string(), (work_ / "plain.pcd").string()}), {"plain.pcd", "no label"});
}

TEST_F(CliTest, EvalOfCloudsOfDifferentSizesFails) {
  expect_error(run({"eval", kUnorganizedScene.string(), kOrganizedScene.string()}), {"170986", "307200"});
}

TEST_F(CliTest, EvalWithEmptyIgnoreRangeFails) {
  expect_error(run({"eval", kOrganizedScene.string(), kOrganizedScene.string(), "--ignore", "9-0"}),
               {"--ignore", "9-0"});
}

// A labelled cloud of labels.size() points along x, for eval's hand-made scenes.
void write_labels(const fs::path& path, const Labels& labels) {
  PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(labels.size());
  for (std::size_t k = 0; k < labels.size(); ++k) cloud.points.emplace_back(0.01f * float(k), 0.0f, 1.0f);
  write_labelled_pcd(path, cloud, labels);
}

// A mug (body 50, handle 51) and a can (30) on a table (1); the prediction splits
// the handle off, and the second one also merges the can into the table.
const Labels kMugTruth = {1, 1, 1, 50, 50, 50, 50, 51, 51, 30, 30};
const Labels kHandleSplitOff = {1, 1, 1, 4, 4, 4, 4, 5, 5, 6, 6};
const Labels kCanInTheTable = {1, 1, 1, 4, 4, 4, 4, 5, 5, 1, 1};

TEST_F(CliTest, EvalObjectLevelMergesTheGroundTruthsParts) {
  write_labels(work_ / "truth.pcd", kMugTruth);
  write_labels(work_ / "pred.pcd", kHandleSplitOff);
  const std::string pred = (work_ / "pred.pcd").string(), truth = (work_ / "truth.pcd").string();
  const RunResult parts = run({"eval", pred, truth, "--ignore", "0-9", "--json"});
  expect_success(parts);
  EXPECT_DOUBLE_EQ(json_number(parts.out, "wov"), 1.0) << parts.out;
  EXPECT_DOUBLE_EQ(json_number(parts.out, "ground_truth_regions"), 3) << parts.out;
  EXPECT_NE(parts.out.find("\"object_level\": false"), std::string::npos) << parts.out;
  // The mug is one region of 6 points, its best segment 4 of them: WOv = (6 * 4/6 + 2) / 8.
  const RunResult objects = run({"eval", pred, truth, "--ignore", "0-9", "--object-level", "--json"});
  expect_success(objects);
  EXPECT_DOUBLE_EQ(json_number(objects.out, "wov"), 0.75) << objects.out;
  EXPECT_DOUBLE_EQ(json_number(objects.out, "ground_truth_regions"), 2) << objects.out;
  EXPECT_NE(objects.out.find("\"object_level\": true"), std::string::npos) << objects.out;
  EXPECT_DOUBLE_EQ(json_number(objects.out, "objects_lost"), 0) << objects.out;
  // Text: the scores line as before, then the objects lost.
  const RunResult text = run({"eval", pred, truth, "--ignore", "0-9", "--object-level"});
  expect_success(text);
  EXPECT_TRUE(std::regex_search(text.out, std::regex("^WOv 0\\.7500  tp .*\\(2 regions, 11 points\\)\n"
                                                     "objects lost into the support: 0\n$")))
      << text.out;
}

// A two-level result (robot) carries its objects in an `object` field beside
// the parts' `label`: at object level eval scores that field. The parts split
// the mug's handle off; its object holds the whole mug, so the objects score 1.
TEST_F(CliTest, EvalObjectLevelScoresATwoLevelResultsObjectField) {
  write_labels(work_ / "truth.pcd", kMugTruth);
  PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(kMugTruth.size());
  for (std::size_t k = 0; k < kMugTruth.size(); ++k) cloud.points.emplace_back(0.01f * float(k), 0.0f, 1.0f);
  const Labels objects = {1, 1, 1, 2, 2, 2, 2, 2, 2, 3, 3};
  write_labelled_pcd(work_ / "pred.pcd", cloud, kHandleSplitOff, PcdEncoding::binary, &objects);
  const std::string pred = (work_ / "pred.pcd").string(), truth = (work_ / "truth.pcd").string();
  const RunResult by_objects = run({"eval", pred, truth, "--ignore", "0-9", "--object-level", "--json"});
  expect_success(by_objects);
  EXPECT_DOUBLE_EQ(json_number(by_objects.out, "wov"), 1.0) << by_objects.out;
  // The parts, as before, against the truth's regions: the label field.
  const RunResult by_parts = run({"eval", pred, truth, "--ignore", "0-9", "--json"});
  expect_success(by_parts);
  EXPECT_DOUBLE_EQ(json_number(by_parts.out, "wov"), 1.0) << by_parts.out;
  EXPECT_DOUBLE_EQ(json_number(by_parts.out, "ground_truth_regions"), 3) << by_parts.out;
}

TEST_F(CliTest, EvalCountsObjectsLostIntoTheTable) {
  write_labels(work_ / "truth.pcd", kMugTruth);
  write_labels(work_ / "pred.pcd", kCanInTheTable);
  const std::string pred = (work_ / "pred.pcd").string(), truth = (work_ / "truth.pcd").string();
  for (const bool object_level : {false, true}) {
    std::vector<std::string> args = {"eval", pred, truth, "--ignore", "0-9"};
    if (object_level) args.push_back("--object-level");
    const RunResult text = run(args);
    expect_success(text);
    EXPECT_NE(text.out.find("\nobjects lost into the support: 1 (30)\n"), std::string::npos) << text.out;
    args.push_back("--json");
    const RunResult json = run(args);
    EXPECT_DOUBLE_EQ(json_number(json.out, "objects_lost"), 1) << json.out;
    EXPECT_NE(json.out.find("\"lost_labels\": [30]}"), std::string::npos) << json.out;
  }
  // A support range without the table's label 1: nothing is lost into it.
  const RunResult wall = run({"eval", pred, truth, "--support", "2-9", "--json"});
  EXPECT_DOUBLE_EQ(json_number(wall.out, "objects_lost"), 0) << wall.out;
}

TEST_F(CliTest, EvalOfFoldersNamesTheFramesThatLostObjects) {
  for (const char* folder : {"pred", "truth"}) fs::create_directory(work_ / folder);
  write_labels(work_ / "truth" / "a.pcd", kMugTruth);
  write_labels(work_ / "truth" / "b.pcd", kMugTruth);
  write_labels(work_ / "pred" / "a.pcd", kHandleSplitOff);
  write_labels(work_ / "pred" / "b.pcd", kCanInTheTable);
  const std::string pred = (work_ / "pred").string(), truth = (work_ / "truth").string();
  const RunResult text = run({"eval", pred, truth, "--ignore", "0-9", "--object-level"});
  expect_success(text);
  EXPECT_TRUE(std::regex_search(text.out, std::regex("^b\\.pcd: objects lost into the support: 1 \\(30\\)\n"
                                                     "mean over 2 frames: WOv [0-9.]+  tp .*\n"
                                                     "objects lost into the support: 1\n$")))
      << text.out;
  const RunResult json = run({"eval", pred, truth, "--ignore", "0-9", "--json"});
  expect_success(json);
  EXPECT_DOUBLE_EQ(json_number(json.out, "objects_lost"), 1) << json.out;
  EXPECT_DOUBLE_EQ(json_number(json.out, "frames"), 2) << json.out;
  EXPECT_NE(json.out.find("\"lost_frames\": {\"b.pcd\": [30]}"), std::string::npos) << json.out;
}

TEST_F(CliTest, EvalObjectLevelOfGroundTruthAgainstItselfIsPerfect) {
  const RunResult r =
      run({"eval", kOrganizedScene.string(), kOrganizedScene.string(), "--ignore", "0-9", "--object-level", "--json"});
  expect_success(r);
  EXPECT_DOUBLE_EQ(json_number(r.out, "wov"), 1.0) << r.out;
  EXPECT_DOUBLE_EQ(json_number(r.out, "objects_lost"), 0) << r.out;
}

TEST_F(CliTest, EvalWithSupportRangeHoldingZeroFails) {
  expect_error(run({"eval", kOrganizedScene.string(), kOrganizedScene.string(), "--support", "0-9"}),
               {"--support", "0-9"});
  expect_error(run({"eval", kOrganizedScene.string(), kOrganizedScene.string(), "--support", "table"}),
               {"--support", "table"});
}

// --- D. usage errors ----------------------------------------------------------------

// With several inputs or a folder -o names a folder: a .pcd or .ply name there is a
// mistake (it made a folder y.pcd/), refused before anything is written.
TEST_F(CliTest, SeveralInputsWithOutputNamingAFileAreRefused) {
  const std::set<std::string> before = list_dir(work_);
  for (const char* name : {"y.pcd", "y.ply"}) {
    expect_usage_error(run({"segment", kOrganizedScene.string(), (kData / "mosd_test34.pcd").string(), "-o",
                            (work_ / name).string()}),
                       {name, "must name a folder"});
    expect_usage_error(run({"segment", kData.string(), "-o", (work_ / name).string()}), {name, "must name a folder"});
  }
  EXPECT_EQ(list_dir(work_), before);
}

// --png writes PNG bytes, so it takes only a .png name.
TEST_F(CliTest, PngWithAnotherExtensionIsRefused) {
  const std::set<std::string> before = list_dir(work_);
  for (const char* name : {"x.jpg", "x.PNG.txt", "x"}) {
    expect_usage_error(run({"segment", kOrganizedScene.string(), "-o", out_pcd().string(), "--png",
                            (work_ / name).string()}),
                       {name, ".png"});
  }
  EXPECT_EQ(list_dir(work_), before);
}

// --frames 0 and --seconds 0: one short line, not CLI11's range of 309 digits.
TEST_F(CliTest, FramesOrSecondsBelowTheirBoundSayWhatIsWrong) {
  const std::string recording = (kData / ".." / ".." / "recordings" / "mosd_scenes.oni").string();
  for (const auto& [option, value, phrase] : {std::tuple{"--frames", "0", "--frames: must be at least 1"},
                                              {"--frames", "0.5", "--frames: must be at least 1"},
                                              {"--seconds", "0", "--seconds: must be more than 0"},
                                              {"--seconds", "-2", "--seconds: must be more than 0"}}) {
    const RunResult r = run({"replay", recording, option, value});
    expect_usage_error(r, {phrase});
    EXPECT_LT(r.err.size(), 80u) << r.err;
  }
}

// replay without -o writes nothing, so --help shows --save's default as applying with -o.
TEST_F(CliTest, HelpShowsSavesDefaultOnlyWithOutputFolder) {
  for (const char* command : {"replay", "live"}) {
    const RunResult r = run({command, "--help"});
    expect_success(r);
    const std::size_t save = r.out.find("--save");
    ASSERT_NE(save, std::string::npos) << r.out;
    const std::string line = r.out.substr(save, r.out.find('\n', save) - save);
    EXPECT_EQ(line.find("=[png]"), std::string::npos) << line;
    EXPECT_NE(line.find("with -o, default png"), std::string::npos) << line;
  }
}

// A URI no driver opens: the URI once, then the reason.
TEST_F(CliTest, BadUriIsNamedOnce) {
  for (const std::string uri : {"virtual://no-such-scene", "usb://0000/0000"}) {
    const RunResult r = run({"live", "--uri", uri, "--frames", "3"}, kQuickTimeoutSeconds);
    expect_error(r, {uri});
    std::size_t count = 0;
    for (std::size_t at = r.err.find(uri); at != std::string::npos; at = r.err.find(uri, at + 1)) ++count;
    EXPECT_EQ(count, 1u) << r.err;
  }
}

TEST_F(CliTest, UsageErrors) {
  const std::set<std::string> before = list_dir(work_);
  expect_usage_error(run({}));
  expect_usage_error(run({"frobnicate", kOrganizedScene.string()}));
  expect_usage_error(run({"segment"}));
  expect_usage_error(run({"segment", kOrganizedScene.string()}));  // no -o
  expect_usage_error(run({"eval", kOrganizedScene.string()}));     // no ground truth
  expect_usage_error(run({"--threads", "0", "segment", kOrganizedScene.string(), "-o", out_pcd().string()}));
  EXPECT_EQ(list_dir(work_), before);
}

}  // namespace
}  // namespace lccp
