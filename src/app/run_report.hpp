#pragma once
// What a stream run measured: per-frame records and their summary statistics.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lccp/metrics/statistics.hpp"
#include "lccp/pipeline/pipeline.hpp"

namespace lccp::app {

struct FrameRecord {
  std::uint64_t index = 0;
  std::uint64_t timestamp_us = 0;
  double captured_s = 0;         // since the run started
  double back_projection_ms = 0;
  StageTimes stages;
  double end_to_end_ms = 0;      // captured -> labels ready
  std::uint32_t segments = 0;
  bool failed = false;

  // End to end minus the stages: waiting for a free slot (K frames in flight),
  // between nodes and for the frames before it (the sequencer). >= 0.
  double waiting_ms() const;
};


// Processor time the whole process used during a run (getrusage: every thread,
// including the capture thread and OpenNI2's), against the run's wall time.
struct CpuUse {
  double user_s = 0;
  double system_s = 0;
  double wall_s = 0;
  unsigned cores = 1;  // cores available to the process (tbb::this_task_arena::max_concurrency())

  double percent_of_one_core() const { return wall_s > 0 ? 100.0 * (user_s + system_s) / wall_s : 0; }
  double percent_of_cores() const { return percent_of_one_core() / cores; }
};

// The process's user and system time so far, for CpuUse (as a difference of two readings).
struct CpuTimes {
  double user_s = 0;
  double system_s = 0;
};
CpuTimes process_cpu_times();

class RunReport {
 public:
  explicit RunReport(Clock::time_point start) : start_(start) {}
  void add(const FrameResult& result);
  void finish(const PipelineStats& stats, const CpuUse& cpu) {
    stats_ = stats;
    cpu_ = cpu;
  }

  const std::vector<FrameRecord>& frames() const { return frames_; }
  const PipelineStats& stats() const { return stats_; }
  const CpuUse& cpu() const { return cpu_; }
  double frames_per_second() const;
  Percentiles end_to_end_ms() const;  // over every frame handed over, failed ones included
  // One per-frame time (e.g. a stage's) over the frames that
  // did not fail: a failed frame's later stages never ran.
  Percentiles percentiles_of(const std::function<double(const FrameRecord&)>& ms) const;

  // One line: counts_text(), fps, latency p50 / p95 / max.
  std::string summary_line() const;
  void write_json(const std::filesystem::path& path, const std::string& source) const;

 private:
  Clock::time_point start_;
  std::vector<FrameRecord> frames_;
  PipelineStats stats_;
  CpuUse cpu_;
};

// "81 received + 3 sensor gaps = 70 completed + 0 failed + 14 dropped": the
// frames the source produced, then where each went (PipelineStats::adds_up).
std::string counts_text(const PipelineStats& stats);

// JSON (nlohmann-json, https://json.nlohmann.me; members in the order added)
// for the reports: the counts' members ("frames_received": 81, ...) and a
// latency row ({"p50": ..., "p95": ..., "p99": ..., "max": ...}). A
// non-finite number is written as null (RFC 8259 has no NaN).
using Json = nlohmann::ordered_json;
Json counts_json(const PipelineStats& stats);
Json percentiles_json(const Percentiles& percentiles);

// `document` indented by 2, with a newline at the end (the report files).
std::string json_text(const Json& document);

// `document` on one line, a space after each ':' and ',' (Python's
// json.dumps style), with a newline at the end: lccp eval --json, one object a line.
std::string json_line(const Json& document);

}  // namespace lccp::app
