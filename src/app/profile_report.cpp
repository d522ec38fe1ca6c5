#include "profile_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <spdlog/fmt/fmt.h>

#include "lccp/io/atomic_file.hpp"
#include "lccp/io/config_file.hpp"

namespace lccp::app {
namespace {

using Kind = LatencyRow::Kind;

constexpr double kFramePeriodMs = 1000.0 / 30.0;  // a 30 Hz sensor

// The colours of the pipeline nodes and of the waiting time, in latency_rows() order.
// Back-projection, one per kPipelineNodes entry, waiting.
constexpr std::array<const char*, 7> kPartColours{"#8c564b", "#1f77b4", "#2ca02c", "#9467bd",
                                                  "#e377c2", "#17becf", "#c7c7c7"};
static_assert(kPartColours.size() == kPipelineNodes.size() + 2);

const char* policy_name(DropPolicy policy) { return policy == DropPolicy::drop_oldest ? "drop_oldest" : "block"; }

// The rows that add up to end to end: the nodes, then the waiting time.
std::vector<LatencyRow> parts() {
  std::vector<LatencyRow> rows;
  for (const LatencyRow& row : latency_rows()) {
    if (row.kind == Kind::node || row.kind == Kind::waiting) rows.push_back(row);
  }
  return rows;
}

LatencyRow end_to_end_row() {
  const std::vector<LatencyRow>& rows = latency_rows();
  return *std::find_if(rows.begin(), rows.end(), [](const LatencyRow& row) { return row.kind == Kind::end_to_end; });
}

// "1 frame", "2 frames".
std::string counted(std::uint64_t count, const char* noun) { return fmt::format("{} {}{}", count, noun, count == 1 ? "" : "s"); }

// A config value as JSON: true/false and numbers as they are, anything else a string.
Json config_value_json(const std::string& text) {
  if (text == "true" || text == "false") return text == "true";
  for (const bool whole : {true, false}) {  // "8" stays 8, not 8.0
    std::istringstream in(text);
    std::int64_t integer = 0;
    double number = 0;
    if (whole ? !(in >> integer) : !(in >> number)) continue;
    if (in.peek() == std::char_traits<char>::eof()) return whole ? Json(integer) : Json(number);
  }
  return text;
}

// (key, value) of every config key, from describe_config's "key: value    # meaning" lines.
std::vector<std::pair<std::string, std::string>> config_entries(const SceneConfig& config) {
  std::vector<std::pair<std::string, std::string>> entries;
  std::istringstream lines(describe_config(config));
  for (std::string line; std::getline(lines, line);) {
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;
    std::string value = line.substr(colon + 2, line.find(" #", colon) - colon - 2);
    while (!value.empty() && value.back() == ' ') value.pop_back();
    entries.emplace_back(line.substr(0, colon), value);
  }
  return entries;
}

std::string config_line(const ProfileSetup& setup) {
  std::string line = setup.config_file.empty() ? "defaults (P1)" : setup.config_file;
  for (const std::string& setting : setup.settings) line += ", " + setting;
  return line;
}

std::string html_escape(std::string_view text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

// A round tick spacing (1, 2 or 5 times a power of ten) giving about `ticks` ticks over `range`.
double tick_step(double range, int ticks) {
  if (!(range > 0)) return 1;
  const double raw = range / ticks;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double multiple : {1.0, 2.0, 5.0}) {
    if (raw <= multiple * magnitude) return multiple * magnitude;
  }
  return 10 * magnitude;
}

// "12", "0.5", "2.5": a tick label without trailing zeros.
std::string tick_label(double value) { return fmt::format("{:g}", std::abs(value) < 1e-9 ? 0.0 : value); }

// A plot area inside an SVG: data coordinates to pixels.
struct PlotArea {
  double left, top, width, height;  // pixels
  double x0, x1, y1;                // data: x from x0 to x1, y from 0 to y1

  double x(double value) const { return left + (value - x0) / (x1 - x0) * width; }
  double y(double value) const { return top + height - value / y1 * height; }
  double bottom() const { return top + height; }
  double right() const { return left + width; }
};

// Grid lines and labels of the y axis (0 to y1), the frame and the axis titles.
std::string axes(const PlotArea& area, double y_step, const std::string& x_title, const std::string& y_title) {
  std::string svg;
  for (double value = 0; value <= area.y1 + 1e-9; value += y_step) {
    const double y = area.y(value);
    svg += fmt::format("<line class=\"grid\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\"/>", area.left, y,
                       area.right(), y);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>", area.left - 6, y + 4,
                       tick_label(value));
  }
  svg += fmt::format("<rect class=\"frame\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\"/>", area.left,
                     area.top, area.width, area.height);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>", area.left + area.width / 2,
                     area.bottom() + 34, html_escape(x_title));
  svg += fmt::format("<text transform=\"translate(14 {:.1f}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
                     area.top + area.height / 2, html_escape(y_title));
  return svg;
}

// Tick marks and labels along the x axis, at multiples of `step` from x0 to x1.
std::string x_ticks(const PlotArea& area, double step) {
  std::string svg;
  for (double value = std::ceil(area.x0 / step) * step; value <= area.x1 + 1e-9; value += step) {
    const double x = area.x(value);
    svg += fmt::format("<line class=\"axis\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\"/>", x,
                       area.bottom(), x, area.bottom() + 4);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>", x, area.bottom() + 16,
                       tick_label(value));
  }
  return svg;
}

// (1) End-to-end latency per frame against capture time, with the p50 and p99
// lines and the 33 ms frame period.
std::string latency_plot(const RunReport& report) {
  const std::vector<FrameRecord>& frames = report.frames();
  const Percentiles end_to_end = report.percentiles_of(end_to_end_row().ms);
  double last_s = 0, highest_ms = kFramePeriodMs;
  for (const FrameRecord& f : frames) {
    last_s = std::max(last_s, f.captured_s);
    highest_ms = std::max(highest_ms, f.end_to_end_ms);
  }
  const double y_step = tick_step(highest_ms * 1.05, 6);
  const PlotArea area{60, 12, 690, 250, 0, last_s > 0 ? last_s : 1, std::ceil(highest_ms * 1.05 / y_step) * y_step};

  std::string svg = "<svg viewBox=\"0 0 900 310\" width=\"900\" height=\"310\" role=\"img\" "
                    "aria-label=\"end-to-end latency per frame over capture time\">";
  svg += axes(area, y_step, "capture time (s since the run started)", "end-to-end latency (ms)");
  svg += x_ticks(area, tick_step(area.x1 - area.x0, 8));

  // The reference lines, labelled at the right; labels closer than 12 px are pushed apart.
  struct Line {
    double ms;
    std::string label;
    const char* style;
  };
  std::vector<Line> lines{{kFramePeriodMs, "frame period 33.3 ms", "period"},
                          {end_to_end.p50, fmt::format("p50 {:.1f} ms", end_to_end.p50), "p50"},
                          {end_to_end.p99, fmt::format("p99 {:.1f} ms", end_to_end.p99), "p99"}};
  std::sort(lines.begin(), lines.end(), [](const Line& a, const Line& b) { return a.ms > b.ms; });
  double previous_label_y = -1e9;
  for (const Line& line : lines) {
    const double y = area.y(line.ms);
    const double label_y = std::max(y + 4, previous_label_y + 12);
    previous_label_y = label_y;
    svg += fmt::format("<line class=\"{}\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\"/>", line.style,
                       area.left, y, area.right(), y);
    svg += fmt::format("<text class=\"{}-label\" x=\"{:.1f}\" y=\"{:.1f}\">{}</text>", line.style, area.right() + 6,
                       label_y, line.label);
  }

  std::string points;
  for (const FrameRecord& f : frames) points += fmt::format("{:.1f},{:.1f} ", area.x(f.captured_s), area.y(f.end_to_end_ms));
  svg += "<polyline class=\"latency\" points=\"" + points + "\"/>";
  if (frames.size() <= 2000) {
    for (const FrameRecord& f : frames) {
      svg += fmt::format("<circle class=\"{}\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.2\"><title>frame {}: {:.1f} ms{}</title></circle>",
                         f.failed ? "failed" : "point", area.x(f.captured_s), area.y(f.end_to_end_ms), f.index,
                         f.end_to_end_ms, f.failed ? " (failed)" : "");
    }
  }
  return svg + "</svg>\n";
}

// The colour key of the pipeline nodes and the waiting time.
std::string parts_legend() {
  std::string html = "<p class=\"legend\">";
  const std::vector<LatencyRow> rows = parts();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    html += fmt::format("<span class=\"key\" style=\"background:{}\"></span>{}", kPartColours[i], rows[i].label);
  }
  return html + "</p>\n";
}

// (2a) One stacked bar: the median of each node and of the waiting time, and
// where the median end to end falls.
std::string median_bar(const RunReport& report) {
  const std::vector<LatencyRow> rows = parts();
  std::vector<double> medians;
  double sum = 0;
  for (const LatencyRow& row : rows) {
    medians.push_back(report.percentiles_of(row.ms).p50);
    sum += medians.back();
  }
  const double end_to_end = report.percentiles_of(end_to_end_row().ms).p50;
  const double x_step = tick_step(std::max(sum, end_to_end) * 1.05, 8);
  const double x1 = std::max(std::ceil(std::max(sum, end_to_end) * 1.05 / x_step) * x_step, x_step);
  const PlotArea area{60, 20, 690, 30, 0, x1, 1};

  std::string svg = "<svg viewBox=\"0 0 900 88\" width=\"900\" height=\"88\" role=\"img\" "
                    "aria-label=\"median milliseconds per pipeline stage\">";
  double x = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double width = area.x(x + medians[i]) - area.x(x);
    svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.2f}\" height=\"{:.1f}\" fill=\"{}\"><title>{}: "
                       "median {:.2f} ms</title></rect>",
                       area.x(x), area.top, width, area.height, kPartColours[i], rows[i].label, medians[i]);
    if (width > 36) {
      svg += fmt::format("<text class=\"inside\" x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{:.1f}</text>",
                         area.x(x) + width / 2, area.top + area.height / 2 + 4, medians[i]);
    }
    x += medians[i];
  }
  svg += fmt::format("<line class=\"p50\" x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\"/>",
                     area.x(end_to_end), area.top - 4, area.bottom() + 4);
  const bool label_left = area.x(end_to_end) > area.right() - 140;
  svg += fmt::format("<text class=\"p50-label\" x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\">end to end p50 {:.1f} "
                     "ms</text>",
                     area.x(end_to_end) + (label_left ? -4 : 4), area.top - 8, label_left ? "end" : "start", end_to_end);
  svg += x_ticks(area, x_step);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">ms</text>", area.left - 20,
                     area.bottom() + 16);
  return svg + "</svg>\n";
}

// (2b) One stacked bar per frame (the mean of several frames when there are
// more frames than fit): the nodes and the waiting time, adding up to end to end.
std::string per_frame_bars(const RunReport& report) {
  constexpr std::size_t kMostBars = 400;
  const std::vector<FrameRecord>& frames = report.frames();
  const std::vector<LatencyRow> rows = parts();
  const std::size_t per_bar = std::max<std::size_t>(1, (frames.size() + kMostBars - 1) / kMostBars);
  const std::size_t bars = (frames.size() + per_bar - 1) / per_bar;

  std::vector<std::vector<double>> values(bars, std::vector<double>(rows.size(), 0));
  double highest = kFramePeriodMs;
  for (std::size_t bar = 0; bar < bars; ++bar) {
    const std::size_t begin = bar * per_bar, end = std::min(frames.size(), begin + per_bar);
    double total = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (std::size_t f = begin; f < end; ++f) values[bar][i] += rows[i].ms(frames[f]);
      values[bar][i] /= static_cast<double>(end - begin);
      total += values[bar][i];
    }
    highest = std::max(highest, total);
  }
  const double y_step = tick_step(highest * 1.05, 6);
  const PlotArea area{60, 12, 690, 250, 0, static_cast<double>(std::max<std::size_t>(bars, 1)),
                      std::ceil(highest * 1.05 / y_step) * y_step};

  std::string svg = "<svg viewBox=\"0 0 900 310\" width=\"900\" height=\"310\" role=\"img\" "
                    "aria-label=\"milliseconds per pipeline stage, frame by frame\">";
  svg += axes(area, y_step, per_bar == 1 ? "frame (in order)" : fmt::format("frames, {} per bar (mean)", per_bar),
              "latency (ms)");
  const double slot = area.width / area.x1;
  const double gap = slot > 4 ? 1 : 0;
  for (std::size_t bar = 0; bar < bars; ++bar) {
    const FrameRecord& first = frames[bar * per_bar];
    const FrameRecord& last = frames[std::min(frames.size(), (bar + 1) * per_bar) - 1];
    std::string title = per_bar == 1 ? fmt::format("frame {}{}", first.index, first.failed ? " (failed)" : "")
                                     : fmt::format("frames {}-{} (mean)", first.index, last.index);
    double y = 0;
    std::string rects;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      title += fmt::format("&#10;{}: {:.2f} ms", rows[i].label, values[bar][i]);
      rects += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\"/>",
                           area.x(static_cast<double>(bar)) + gap / 2, area.y(y + values[bar][i]), slot - gap,
                           area.y(y) - area.y(y + values[bar][i]), kPartColours[i]);
      y += values[bar][i];
    }
    svg += "<g><title>" + title + "</title>" + rects + "</g>";
  }
  const double period_y = area.y(kFramePeriodMs);
  svg += fmt::format("<line class=\"period\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\"/>", area.left,
                     period_y, area.right(), period_y);
  svg += fmt::format("<text class=\"period-label\" x=\"{:.1f}\" y=\"{:.1f}\">frame period 33.3 ms</text>",
                     area.right() + 6, period_y + 4);
  // Frame numbers under the bars: the first frame of every bar at a round position.
  const double step = tick_step(static_cast<double>(bars), 8);
  for (double position = 0; position < static_cast<double>(bars); position += std::max(step, 1.0)) {
    const auto bar = static_cast<std::size_t>(position);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>",
                       area.x(static_cast<double>(bar)) + slot / 2, area.bottom() + 16, frames[bar * per_bar].index);
  }
  return svg + "</svg>\n";
}

std::string html_latency_table(const RunReport& report) {
  std::string html = "<table class=\"latency\"><tr><th>stage</th><th>p50</th><th>p95</th><th>p99</th><th>max</th></tr>\n";
  for (const LatencyRow& row : latency_rows()) {
    const Percentiles p = report.percentiles_of(row.ms);
    const char* css = row.kind == Kind::stage ? "stage" : row.kind == Kind::end_to_end ? "total" : "node";
    html += fmt::format("<tr class=\"{}\"><td>{}</td><td>{:.2f}</td><td>{:.2f}</td><td>{:.2f}</td><td>{:.2f}</td></tr>\n",
                        css, row.label, p.p50, p.p95, p.p99, p.max);
  }
  return html + "</table>\n";
}

std::string html_summary_table(const ProfileSetup& setup, const RunReport& report) {
  const PipelineStats& stats = report.stats();
  const CpuUse& cpu = report.cpu();
  const std::vector<std::pair<std::string, std::string>> rows{
      {"source", html_escape(setup.source) + " (" + to_string(setup.kind) + (setup.realtime ? ", real time" : "") + ")"},
      {"config", html_escape(config_line(setup))},
      {"threads / cores", fmt::format("{} / {}", setup.threads, cpu.cores)},
      {"frames in flight (K)", fmt::format("{}, {}", setup.frames_in_flight, policy_name(setup.drop_policy))},
      {"frames", counts_text(stats)},
      {"throughput", fmt::format("{:.1f} frames/s ({} frames in {:.2f} s)", report.frames_per_second(),
                                 stats.frames_completed, stats.wall_seconds)},
      {"CPU use", fmt::format("{:.0f}% of one core, {:.0f}% of {} cores (user {:.2f} s, system {:.2f} s)",
                              cpu.percent_of_one_core(), cpu.percent_of_cores(), cpu.cores, cpu.user_s, cpu.system_s)},
  };
  std::string html = "<table class=\"summary\">\n";
  for (const auto& [name, value] : rows) html += "<tr><th>" + name + "</th><td>" + value + "</td></tr>\n";
  return html + "</table>\n";
}

constexpr const char* kStyle = R"(body{font:14px/1.45 system-ui,sans-serif;color:#222;max-width:960px;margin:24px auto;padding:0 12px}
h1{font-size:20px;margin-bottom:4px}h2{font-size:16px;margin:28px 0 6px}
p.note{color:#555;font-size:13px;margin:4px 0}
table{border-collapse:collapse;margin:6px 0}th,td{padding:2px 12px;border-bottom:1px solid #eee}
table.summary th{text-align:left;font-weight:600}table.summary td{text-align:left}
table.latency td,table.latency th{text-align:right}table.latency td:first-child,table.latency th:first-child{text-align:left}
tr.node td{font-weight:600}tr.stage td{color:#555}tr.stage td:first-child{padding-left:30px}
tr.total td{font-weight:700;border-top:1px solid #888}
svg{display:block}svg text{font:11px system-ui,sans-serif;fill:#333}
.grid{stroke:#e8e8e8}.axis{stroke:#555}.frame{fill:none;stroke:#999}
.latency{fill:none;stroke:#444;stroke-width:1.2}.point{fill:#444}.failed{fill:#d62728}
.p50{stroke:#1f77b4;stroke-width:1.5;stroke-dasharray:6 3}.p99{stroke:#ff7f0e;stroke-width:1.5;stroke-dasharray:6 3}
.period{stroke:#d62728;stroke-width:1.5}
svg text.p50-label{fill:#1f77b4}svg text.p99-label{fill:#c45f00}svg text.period-label{fill:#d62728}svg text.inside{fill:#fff}
.legend .key{display:inline-block;width:11px;height:11px;margin:0 5px 0 14px;vertical-align:-1px}
)";

}  // namespace

// "voxelize + normals": the stages a pipeline node runs.
std::string node_label(const PipelineNode& node) {
  std::string label;
  for (const StageInfo& info : kStages) {
    if (node.contains(info.stage)) label += (label.empty() ? "" : " + ") + std::string(info.name);
  }
  return label;
}

const std::vector<LatencyRow>& latency_rows() {
  static const std::vector<LatencyRow> rows = [] {
    std::vector<LatencyRow> all{
        {"back_projection", "back-projection", Kind::node, [](const FrameRecord& f) { return f.back_projection_ms; }}};
    for (const PipelineNode& node : kPipelineNodes) {
      all.push_back({std::string(node.name), node_label(node), Kind::node,
                     [&node](const FrameRecord& f) { return node.ms(f.stages); }});
      for (const StageInfo& info : kStages) {
        if (!node.contains(info.stage)) continue;
        all.push_back({std::string(info.name), std::string(info.name), Kind::stage,
                       [stage = info.stage](const FrameRecord& f) { return f.stages[stage]; }});
      }
    }
    all.push_back({"waiting", "waiting", Kind::waiting, [](const FrameRecord& f) { return f.waiting_ms(); }});
    all.push_back({"end_to_end", "end to end", Kind::end_to_end, [](const FrameRecord& f) { return f.end_to_end_ms; }});
    return all;
  }();
  return rows;
}

std::string profile_table(const ProfileSetup& setup, const RunReport& report) {
  const PipelineStats& stats = report.stats();
  const CpuUse& cpu = report.cpu();
  std::string table = fmt::format("profile {} ({}{}): {}, K = {} ({}), config {}\n", setup.source,
                                  to_string(setup.kind), setup.realtime ? ", real time" : "", counted(setup.threads, "thread"),
                                  setup.frames_in_flight, policy_name(setup.drop_policy), config_line(setup));
  const std::uint64_t succeeded = stats.frames_completed;
  table += fmt::format("{:<28}{:>9}{:>9}{:>9}{:>9}   (ms, {})\n", "stage", "p50", "p95", "p99", "max",
                       stats.frames_failed > 0 ? fmt::format("the {} of {} frames that succeeded", succeeded,
                                                             stats.frames_completed + stats.frames_failed)
                                                  : counted(succeeded, "frame"));
  for (const LatencyRow& row : latency_rows()) {
    const Percentiles p = report.percentiles_of(row.ms);
    const std::string label = (row.kind == Kind::stage ? "  " : "") + std::string(row.label);
    table += fmt::format("{:<28}{:>9.2f}{:>9.2f}{:>9.2f}{:>9.2f}\n", label, p.p50, p.p95, p.p99, p.max);
  }
  table += fmt::format("throughput  {:.1f} frames/s ({} frames in {:.2f} s)\n", report.frames_per_second(),
                       stats.frames_completed, stats.wall_seconds);
  table += "frames      " + counts_text(stats) + "\n";
  table += fmt::format("CPU use     {:.0f}% of one core, {:.0f}% of {} cores (user {:.2f} s, system {:.2f} s)\n",
                       cpu.percent_of_one_core(), cpu.percent_of_cores(), cpu.cores, cpu.user_s, cpu.system_s);
  return table;
}

// The run's setup: source, config, threads, frames in flight, drop policy.
Json setup_json(const ProfileSetup& setup, const CpuUse& cpu) {
  Json config = Json::object();
  for (const auto& [key, value] : config_entries(setup.config)) config[key] = config_value_json(value);
  return {{"source", setup.source},
          {"source_kind", to_string(setup.kind)},
          {"realtime", setup.realtime},
          {"config_file", setup.config_file},
          {"settings", setup.settings},
          {"config", std::move(config)},
          {"threads", setup.threads},
          {"cores", cpu.cores},
          {"frames_in_flight", setup.frames_in_flight},
          {"drop_policy", policy_name(setup.drop_policy)}};
}

void write_profile_json(const std::filesystem::path& path, const ProfileSetup& setup, const RunReport& report) {
  const PipelineStats& stats = report.stats();
  const CpuUse& cpu = report.cpu();
  Json document = setup_json(setup, cpu);
  document.update(counts_json(stats));
  document["wall_seconds"] = stats.wall_seconds;
  document["frames_per_second"] = report.frames_per_second();
  document["cpu_user_seconds"] = cpu.user_s;
  document["cpu_system_seconds"] = cpu.system_s;
  document["cpu_percent_of_one_core"] = cpu.percent_of_one_core();
  document["cpu_percent_of_cores"] = cpu.percent_of_cores();
  document["frame_period_ms"] = kFramePeriodMs;
  Json& stages = document["pipeline_stages"] = Json::array();
  Json& latency = document["latency_ms"] = Json::object();
  for (const LatencyRow& row : latency_rows()) {
    if (row.kind == Kind::node) stages.push_back(row.key);
    latency[row.key] = percentiles_json(report.percentiles_of(row.ms));
  }
  write_file_atomically(path, std::string_view(json_text(document)));
}

void write_frames_csv(const std::filesystem::path& path, const RunReport& report) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "index,timestamp_us,captured_s,back_projection_ms";
    for (const StageInfo& info : kStages) out << "," << info.name << "_ms";
    out << ",end_to_end_ms,segments,failed\n";
    for (const FrameRecord& f : report.frames()) {
      out << fmt::format("{},{},{:.6f},{:.3f}", f.index, f.timestamp_us, f.captured_s, f.back_projection_ms);
      for (const double ms : f.stages.ms) out << fmt::format(",{:.3f}", ms);
      out << fmt::format(",{:.3f},{},{}\n", f.end_to_end_ms, f.segments, f.failed ? 1 : 0);
    }
  });
}

void write_profile_html(const std::filesystem::path& path, const ProfileSetup& setup, const RunReport& report) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>LCCP profile: "
        << html_escape(setup.source) << "</title>\n<style>\n" << kStyle << "</style>\n</head>\n<body>\n"
        << "<h1>LCCP profile</h1>\n" << html_summary_table(setup, report) << "<h2>Latency (ms)</h2>\n"
        << "<p class=\"note\">Percentiles over the frames that succeeded. Waiting: end to end minus the stages "
           "(for one of the K slots, between nodes, for earlier frames to finish).</p>\n"
        << html_latency_table(report);
    if (report.frames().empty()) {
      out << "<p>No frame completed: nothing to plot.</p>\n</body>\n</html>\n";
      return;
    }
    out << "<h2>End-to-end latency over time</h2>\n"
        << "<p class=\"note\">Per frame, from capture to labels ready; red dots: failed frames.</p>\n"
        << latency_plot(report) << "<h2>Where the time goes</h2>\n"
        << "<p class=\"note\">Median per pipeline stage (the medians need not add up to the median end to end).</p>\n"
        << median_bar(report) << parts_legend() << "<p class=\"note\">Frame by frame.</p>\n" << per_frame_bars(report)
        << parts_legend() << "</body>\n</html>\n";
  });
}

void write_profile_reports(const std::filesystem::path& directory, const ProfileSetup& setup, const RunReport& report) {
  write_frames_csv(directory / "frames.csv", report);
  write_profile_html(directory / "report.html", setup, report);
  write_profile_json(directory / "report.json", setup, report);
}

}  // namespace lccp::app
