#include "run_report.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>

#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"

namespace lccp::app {
namespace {

double seconds(const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); }

}  // namespace

double FrameRecord::waiting_ms() const { return std::max(0.0, end_to_end_ms - back_projection_ms - stages.total_ms()); }

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

Json counts_json(const PipelineStats& s) {
  return {{"frames_received", s.frames_received},
          {"sensor_gaps", s.sensor_gaps},
          {"frames_completed", s.frames_completed},
          {"frames_failed", s.frames_failed},
          {"frames_dropped", s.frames_dropped}};
}

Json percentiles_json(const Percentiles& p) { return {{"p50", p.p50}, {"p95", p.p95}, {"p99", p.p99}, {"max", p.max}}; }

// Bytes that are not UTF-8 (a path is any bytes) become U+FFFD instead of an exception.
std::string json_text(const Json& document) { return document.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

namespace {

// Arrays and objects spaced as json_line says; anything else as nlohmann writes it.
std::string spaced(const Json& value) {
  if (!value.is_structured()) return value.dump(-1, ' ', false, Json::error_handler_t::replace);
  std::string text;
  for (auto item = value.begin(); item != value.end(); ++item) {
    if (!text.empty()) text += ", ";
    if (value.is_object()) text += spaced(Json(item.key())) + ": ";
    text += spaced(item.value());
  }
  return value.is_object() ? "{" + text + "}" : "[" + text + "]";
}

}  // namespace

std::string json_line(const Json& document) { return spaced(document) + "\n"; }

std::string RunReport::summary_line() const {
  const Percentiles latency = end_to_end_ms();
  char line[256];
  std::snprintf(line, sizeof line, " | %.1f frames/s | latency ms p50 %.1f p95 %.1f max %.1f", frames_per_second(),
                latency.p50, latency.p95, latency.max);
  return "frames " + counts_text(stats_) + line;
}

void RunReport::write_json(const std::filesystem::path& path, const std::string& source) const {
  Json document = {{"source", source}};
  document.update(counts_json(stats_));
  document["wall_seconds"] = stats_.wall_seconds;
  document["frames_per_second"] = frames_per_second();
  document["end_to_end_ms"] = percentiles_json(end_to_end_ms());
  write_file_atomically(path, std::string_view(json_text(document)));
}

}  // namespace lccp::app
