#pragma once
// The reports of `lccp profile`: report.json, frames.csv and report.html (one
// self-contained page: inline SVG and CSS, no script, nothing fetched), and the
// table printed to stdout.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "lccp/capture/open_source.hpp"
#include "lccp/config.hpp"
#include "run_report.hpp"

namespace lccp::app {

// What was profiled, and how.
struct ProfileSetup {
  std::string source;                 // the SOURCE arguments, space-separated
  SourceKind kind = SourceKind::recording;
  std::string config_file;            // empty: the defaults (P1)
  std::vector<std::string> settings;  // --set key=value, in order
  SceneConfig config;                 // the result
  unsigned threads = 1;               // TBB's thread limit (--threads, else every core)
  unsigned frames_in_flight = 2;      // K
  DropPolicy drop_policy = DropPolicy::block;
  bool realtime = false;              // a recording paced by its timestamps
};

// One row of the latency breakdown.
struct LatencyRow {
  enum class Kind {
    node,        // a node of the pipeline (a group of the method's stages)
    stage,       // one of the method's stages, inside the node above it
    waiting,     // end to end minus the nodes: waiting for a slot, between nodes, for earlier frames
    end_to_end,  // captured -> labels ready
  };
  std::string key;    // JSON key
  std::string label;  // for people
  Kind kind;
  std::function<double(const FrameRecord&)> ms;
};

// back-projection; then per pipeline node (kPipelineNodes) the node and its
// stages (kStages); waiting; end to end.
const std::vector<LatencyRow>& latency_rows();

// Stages x p50 / p95 / p99 / max (ms), then throughput, frames dropped, CPU use.
std::string profile_table(const ProfileSetup& setup, const RunReport& report);

// Writes report.json, frames.csv and report.html into `directory` (which must
// exist), each appearing whole (temp file, then rename). Throws lccp::Error.
void write_profile_reports(const std::filesystem::path& directory, const ProfileSetup& setup, const RunReport& report);

// The single files, for the above.
void write_profile_json(const std::filesystem::path& path, const ProfileSetup& setup, const RunReport& report);
void write_frames_csv(const std::filesystem::path& path, const RunReport& report);
void write_profile_html(const std::filesystem::path& path, const ProfileSetup& setup, const RunReport& report);

}  // namespace lccp::app
