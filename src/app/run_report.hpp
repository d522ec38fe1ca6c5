#pragma once
// What a stream run measured: per-frame records and their summary statistics.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

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
};

struct Percentiles {
  double p50 = 0, p95 = 0, p99 = 0, max = 0;
};
Percentiles percentiles(std::vector<double> values);

class RunReport {
 public:
  explicit RunReport(Clock::time_point start) : start_(start) {}
  void add(const FrameResult& result);
  void finish(const PipelineStats& stats) { stats_ = stats; }

  const std::vector<FrameRecord>& frames() const { return frames_; }
  const PipelineStats& stats() const { return stats_; }
  std::uint64_t frames_failed() const;
  double frames_per_second() const;
  Percentiles end_to_end_ms() const;

  // One line: frames done / dropped / failed, fps, latency p50 / p95 / max.
  std::string summary_line() const;
  void write_json(const std::filesystem::path& path, const std::string& source) const;

 private:
  Clock::time_point start_;
  std::vector<FrameRecord> frames_;
  PipelineStats stats_;
};

}  // namespace lccp::app
