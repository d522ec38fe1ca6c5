#include "run_report.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"

namespace lccp::app {
namespace {

double seconds(const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); }

}  // namespace

double FrameRecord::waiting_ms() const { return std::max(0.0, end_to_end_ms - back_projection_ms - stages.total_ms()); }

Percentiles percentiles(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  const auto at = [&](double q) {  // nearest rank
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
    return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
  };
  return {at(0.50), at(0.95), at(0.99), values.back()};
}

CpuTimes process_cpu_times() {
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return {};
  return {seconds(usage.ru_utime), seconds(usage.ru_stime)};
}

void RunReport::add(const FrameResult& result) {
  FrameRecord record;
  record.index = result.frame.index;
  record.timestamp_us = result.frame.timestamp_us;
  record.captured_s = std::chrono::duration<double>(result.frame.captured - start_).count();
  record.back_projection_ms = result.back_projection_ms;
  record.stages = result.segmentation.times;
  record.end_to_end_ms = result.end_to_end_ms();
  record.segments = result.segmentation.segment_count;
  record.failed = !result.error.empty();
  frames_.push_back(record);
}

double RunReport::frames_per_second() const {
  return stats_.wall_seconds > 0 ? static_cast<double>(stats_.frames_completed) / stats_.wall_seconds : 0;
}

Percentiles RunReport::end_to_end_ms() const {
  std::vector<double> values;
  for (const auto& f : frames_) values.push_back(f.end_to_end_ms);
  return percentiles(std::move(values));
}

Percentiles RunReport::percentiles_of(const std::function<double(const FrameRecord&)>& ms) const {
  std::vector<double> values;
  for (const auto& f : frames_) {
    if (!f.failed) values.push_back(ms(f));
  }
  return percentiles(std::move(values));
}

std::string counts_text(const PipelineStats& s) {
  const auto n = [](std::uint64_t count) { return std::to_string(count); };
  return n(s.frames_received) + " received + " + n(s.sensor_gaps) + " sensor gaps = " + n(s.frames_completed) +
         " completed + " + n(s.frames_failed) + " failed + " + n(s.frames_dropped) + " dropped";
}

void write_counts_json(std::ostream& out, const PipelineStats& s, const char* indent) {
  out << indent << "\"frames_received\": " << s.frames_received << ",\n"
      << indent << "\"sensor_gaps\": " << s.sensor_gaps << ",\n"
      << indent << "\"frames_completed\": " << s.frames_completed << ",\n"
      << indent << "\"frames_failed\": " << s.frames_failed << ",\n"
      << indent << "\"frames_dropped\": " << s.frames_dropped;
}

std::string RunReport::summary_line() const {
  const Percentiles latency = end_to_end_ms();
  char line[256];
  std::snprintf(line, sizeof line, " | %.1f frames/s | latency ms p50 %.1f p95 %.1f max %.1f", frames_per_second(),
                latency.p50, latency.p95, latency.max);
  return "frames " + counts_text(stats_) + line;
}

void RunReport::write_json(const std::filesystem::path& path, const std::string& source) const {
  const Percentiles latency = end_to_end_ms();
  write_file_atomically(path, [&](std::ostream& out) {
    out << "{\n  \"source\": " << json_string(source) << ",\n";
    write_counts_json(out, stats_, "  ");
    out << ",\n  \"wall_seconds\": " << stats_.wall_seconds << ",\n"
        << "  \"frames_per_second\": " << frames_per_second() << ",\n"
        << "  \"end_to_end_ms\": {\"p50\": " << latency.p50 << ", \"p95\": " << latency.p95
        << ", \"p99\": " << latency.p99 << ", \"max\": " << latency.max << "}\n}\n";
  });
}

std::string json_string(std::string_view text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
      quoted += escaped;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}


}  // namespace lccp::app
