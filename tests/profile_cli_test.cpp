// End-to-end tests of `lccp profile` through the real binary: a bundled
// recording, a folder of clouds and the virtual sensor.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "test_files.hpp"

namespace lccp {
namespace {

using namespace test;  // run_lccp, expect_error and the other runner helpers

const fs::path kRecordings = fs::path(LCCP_CONFIG_DIR).parent_path() / "recordings";
const std::set<std::string> kReports{"frames.csv", "report.html", "report.json"};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

// The {"p50": .., "p95": .., "p99": .., "max": ..} object of one latency row in report.json.
struct Latency {
  double p50, p95, p99, max;
};
Latency latency(const std::string& report, const std::string& row) {
  const std::size_t at = report.find("\"" + row + "\": {");
  if (at == std::string::npos) {
    ADD_FAILURE() << "no latency row " << row << " in: " << report;
    return {-1, -1, -1, -1};
  }
  const std::string object = report.substr(at, report.find('}', at) - at);
  return {json_number(object, "p50"), json_number(object, "p95"), json_number(object, "p99"),
          json_number(object, "max")};
}

class ProfileCliTest : public LccpBinaryTest {
 protected:
  ProfileCliTest() : LccpBinaryTest("lccp_profile_cli") {}
  void SetUp() override {
    LccpBinaryTest::SetUp();
    out_ = root_ / "out";
  }
  RunResult profile(std::vector<std::string> args, int timeout_seconds = kRunTimeoutSeconds) {
    args.insert(args.begin(), "profile");
    args.insert(args.end(), {"-o", out_.string(), "--quiet", "--log-level", "warn"});
    return run_lccp(capture_, args, timeout_seconds);
  }
  // frames.csv: the header, then one row of 19 fields per frame with increasing indices.
  std::size_t check_frames_csv() {
    const std::vector<std::string> lines = lines_of(read_bytes(out_ / "frames.csv"));
    EXPECT_FALSE(lines.empty());
    if (lines.empty()) return 0;
    EXPECT_EQ(lines[0],
              "index,timestamp_us,captured_s,back_projection_ms,support_ms,voxelize_ms,normals_ms,seeds_ms,growth_ms,"
              "adjacency_ms,classify_ms,components_ms,filter_ms,parts_ms,geometry_ms,ids_ms,end_to_end_ms,segments,"
              "failed");
    for (std::size_t row = 1; row < lines.size(); ++row) {
      const std::vector<std::string> fields = fields_of(lines[row]);
      EXPECT_EQ(fields.size(), 19u) << lines[row];
      if (row > 1) {
        EXPECT_GT(std::stoull(fields_of(lines[row])[0]), std::stoull(fields_of(lines[row - 1])[0])) << lines[row];
      }
      EXPECT_GT(std::stod(fields.at(12)), 0) << "end_to_end_ms of " << lines[row];
    }
    return lines.size() - 1;
  }

  fs::path out_;
};

TEST_F(ProfileCliTest, RecordingGivesTheReportsForEveryFrame) {
  const RunResult r = profile({(kRecordings / "mosd_scenes.oni").string(), "--frames", "10"});
  expect_success(r);
  EXPECT_EQ(list_dir(out_), kReports);

  const std::string report = read_bytes(out_ / "report.json");
  EXPECT_EQ(json_number(report, "frames_received"), 10) << report;
  EXPECT_EQ(json_number(report, "frames_completed"), 10) << report;
  EXPECT_EQ(json_number(report, "frames_dropped"), 0) << report;
  EXPECT_EQ(json_number(report, "frames_failed"), 0) << report;
  EXPECT_GT(json_number(report, "frames_per_second"), 0) << report;
  EXPECT_GT(json_number(report, "cpu_percent_of_one_core"), 0) << report;
  EXPECT_EQ(json_number(report, "frames_in_flight"), 2) << report;
  EXPECT_EQ(check_frames_csv(), 10u);

  const Latency end_to_end = latency(report, "end_to_end");
  EXPECT_GT(end_to_end.p50, 0);
  EXPECT_LE(end_to_end.p50, end_to_end.p95);
  EXPECT_LE(end_to_end.p95, end_to_end.p99);
  EXPECT_LE(end_to_end.p99, end_to_end.max);
  double stage_medians = 0;
  for (const char* node : {"back_projection", "voxelize_normals", "supervoxels", "graph_labels"}) {
    const Latency stage = latency(report, node);
    EXPECT_GT(stage.p50, 0) << node;
    EXPECT_LE(stage.max, end_to_end.max) << node;
    stage_medians += stage.p50;
  }
  EXPECT_LE(stage_medians, 1.15 * end_to_end.p50) << report;  // each frame waits as well

  const std::string html = read_bytes(out_ / "report.html");
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("frame period 33.3 ms"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("src="), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos) << "the page must not fetch anything";

  for (const char* row : {"back-projection", "voxelize + normals", "seeds + growth",
                          "adjacency + classify + components + filter", "end to end", "p50", "p95", "p99", "max",
                          "throughput", "10 received + 0 sensor gaps = 10 completed + 0 failed + 0 dropped",
                          "CPU use"}) {
    EXPECT_NE(r.out.find(row), std::string::npos) << "stdout has no '" << row << "': " << r.out;
  }
}

TEST_F(ProfileCliTest, FolderOfCloudsGivesOneFramePerCloud) {
  expect_success(profile({LCCP_TEST_DATA_DIR}));
  const std::string report = read_bytes(out_ / "report.json");
  EXPECT_EQ(json_number(report, "frames_completed"), 4) << report;
  EXPECT_EQ(json_number(report, "frames_failed"), 0) << report;
  EXPECT_EQ(check_frames_csv(), 4u);
}

TEST_F(ProfileCliTest, LiveVirtualSensorAccountsForEveryFrame) {
  const RunResult r = profile({"virtual://synthetic", "--frames", "15"});
  expect_success(r);
  const std::string report = read_bytes(out_ / "report.json");
  // The counts add up, and stdout, report.json and report.html say the same.
  expect_counts_add_up(report, r.out);
  expect_counts_add_up(report, read_bytes(out_ / "report.html"));
  EXPECT_EQ(json_number(report, "frames_received"), 15) << report;
  // Every frame taken is completed or dropped; frames_dropped also counts the frame
  // numbers the sensor skipped, which a loaded machine or a sanitizer build makes many.
  EXPECT_GE(json_number(report, "frames_completed") + json_number(report, "frames_dropped"), 15) << report;
  EXPECT_GE(json_number(report, "frames_completed"), 1) << report;
  EXPECT_EQ(check_frames_csv(), static_cast<std::size_t>(json_number(report, "frames_completed")));
}

TEST_F(ProfileCliTest, BadArgumentsFailAtOnceAndLeaveNoReports) {
  const std::string recording = (kRecordings / "mosd_scenes.oni").string();
  expect_usage_error(profile({recording, "--inflight", "0"}, kQuickTimeoutSeconds));
  expect_error(profile({(root_ / "absent.oni").string()}, kQuickTimeoutSeconds), {"absent.oni", "no such file"});
  expect_error(profile({(root_ / "absent").string()}, kQuickTimeoutSeconds), {"absent", "no such file"});
  expect_error(profile({LCCP_TEST_DATA_DIR, "--realtime"}, kQuickTimeoutSeconds), {"--realtime"});
  expect_error(profile({"virtual://synthetic", LCCP_TEST_DATA_DIR}, kQuickTimeoutSeconds), {"virtual://synthetic", "only source"});
  expect_error(profile({(fs::path(LCCP_CONFIG_DIR) / "p1.yaml").string()}, kQuickTimeoutSeconds), {"p1.yaml", "not a source"});
  EXPECT_FALSE(fs::exists(out_));
}

}  // namespace
}  // namespace lccp
