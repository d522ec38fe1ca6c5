// The view's messages: a frame sampled on the sink thread, encoded on the
// server's thread (format: view_message.hpp).
#include "view_message.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <Eigen/Geometry>  // cross
#include <nlohmann/json.hpp>

#include "lccp/io/cloud_io.hpp"  // label_color, part_color: the colours of the label images

namespace lccp::view {
namespace {

using Json = nlohmann::json;

constexpr double kWindowSeconds = 60;  // the latency chart's span
constexpr double kRateSeconds = 2;     // frames per second over the last two seconds

void sample_image(const PointCloud& cloud, const Labels& labels, FrameSample& sample) {
  const std::uint32_t step =
      std::max({1u, (cloud.width + kImageWidth - 1) / kImageWidth, (cloud.height + kImageHeight - 1) / kImageHeight});
  sample.width = (cloud.width + step - 1) / step;
  sample.height = (cloud.height + step - 1) / step;
  sample.points.reserve(std::size_t{sample.width} * sample.height);
  sample.labels.reserve(sample.points.capacity());
  for (std::uint32_t y = 0; y < cloud.height; y += step) {
    for (std::uint32_t x = 0; x < cloud.width; x += step) {
      const std::size_t i = std::size_t{y} * cloud.width + x;
      sample.points.push_back(cloud.points[i]);
      sample.labels.push_back(labels[i]);
    }
  }
}

void sample_points(const PointCloud& cloud, const Labels& labels, FrameSample& sample) {
  const std::size_t step = std::max<std::size_t>(1, (cloud.size() + kMaxPoints3d - 1) / kMaxPoints3d);
  for (std::size_t i = 0; i < cloud.size(); i += step) {
    sample.points.push_back(cloud.points[i]);
    sample.labels.push_back(labels[i]);
  }
}

SegmentSample segment_sample(const SegmentGeometry& geometry, std::uint32_t object, bool part) {
  return {geometry.id, object, geometry.points, geometry.obb.extents, geometry.centroid, geometry.grasp == Grasp::top,
          part};
}

std::vector<SegmentSample> segment_samples(const SceneSegmentation& scene) {
  std::vector<SegmentSample> segments;
  for (const ObjectSegments& object : scene.segments) {
    if (object.parts.empty()) segments.push_back(segment_sample(object.object, object.object.id, false));
    for (const SegmentGeometry& part : object.parts) segments.push_back(segment_sample(part, object.object.id, true));
  }
  return segments;
}

// Segment index + 1 per label id (0 for none), through a sorted table; the
// last answer is kept, as neighbouring points mostly share their label.
class SegmentIndex {
 public:
  SegmentIndex(const std::vector<SegmentSample>& segments, std::uint32_t support_id) {
    for (std::size_t i = 0; i < segments.size(); ++i) table_.emplace_back(segments[i].id, i + 1);
    if (support_id != 0) table_.emplace_back(support_id, segments.size() + 1);
    std::sort(table_.begin(), table_.end());
  }
  std::uint16_t operator()(std::uint32_t id) {
    if (id == last_id_) return last_index_;
    const auto found = std::lower_bound(table_.begin(), table_.end(), std::pair<std::uint32_t, std::size_t>{id, 0});
    const bool known = id != 0 && found != table_.end() && found->first == id && found->second <= 0xFFFF;
    last_id_ = id;
    last_index_ = known ? static_cast<std::uint16_t>(found->second) : 0;
    return last_index_;
  }

 private:
  std::vector<std::pair<std::uint32_t, std::size_t>> table_;
  std::uint32_t last_id_ = 0;
  std::uint16_t last_index_ = 0;
};

// Lambert shading, light at the camera, the normal from the neighbouring
// pixels' points (as the overlay PNGs: src/io/label_image.cpp); black where
// the sensor saw nothing.
void append_shade(std::string& out, const FrameSample& frame) {
  const std::size_t width = frame.width, height = frame.height;
  const auto& points = frame.points;
  const auto seen = [&](std::size_t i) { return std::isfinite(points[i].z()); };
  for (std::size_t y = 0; y < height; ++y) {
    for (std::size_t x = 0; x < width; ++x) {
      const std::size_t i = y * width + x;
      if (!seen(i)) {
        out.push_back(0);
        continue;
      }
      const Eigen::Vector3f& centre = points[i];
      const auto at = [&](bool inside, std::size_t j) -> const Eigen::Vector3f& {
        return inside && seen(j) ? points[j] : centre;
      };
      const Eigen::Vector3f dx = at(x + 1 < width, i + 1) - at(x > 0, i - 1);
      const Eigen::Vector3f dy = at(y + 1 < height, i + width) - at(y > 0, i - width);
      const Eigen::Vector3f normal = dx.cross(dy);
      const float norms = normal.squaredNorm() * centre.squaredNorm();
      const float lambert = norms > 0 ? std::abs(normal.dot(centre)) / std::sqrt(norms) : 0.6f;
      out.push_back(static_cast<char>(static_cast<std::uint8_t>(50 + 200 * std::min(lambert, 1.0f))));
    }
  }
}

template <typename T>
void append(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // little-endian hosts (x86-64, arm64)
  out.append(bytes, sizeof(T));
}

void pad_to_4(std::string& out) { out.append((4 - out.size() % 4) % 4, '\0'); }

std::int16_t millimetres(float metres) {
  return static_cast<std::int16_t>(std::clamp(std::lrint(metres * 1000.0f), -32767L, 32767L));
}

// The finite sample points, thinned to kMaxPoints3d at most: every n-th row
// and column of an image (an even grid on the surfaces), every n-th point else.
std::vector<std::size_t> points_3d(const FrameSample& frame) {
  const std::size_t count = frame.points.size();
  const bool image = frame.width > 0;
  std::size_t step = 1;
  while (count / (image ? step * step : step) > kMaxPoints3d) ++step;
  const std::size_t width = image ? frame.width : count, rows = image ? frame.height : 1;
  const std::size_t row_step = image ? step : 1, column_step = step;
  std::vector<std::size_t> kept;
  kept.reserve(kMaxPoints3d + 1);
  for (std::size_t y = 0; y < rows; y += row_step) {
    for (std::size_t x = 0; x < width; x += column_step) {
      if (std::isfinite(frame.points[y * width + x].z())) kept.push_back(y * width + x);
    }
  }
  return kept;
}

Json segment_json(const SegmentSample& segment) {
  const auto rgb = segment.part ? part_color(segment.object, segment.id) : label_color(segment.id);
  return {{"id", segment.id},
          {"object", segment.object},
          {"points", segment.points},
          {"size", {segment.size.x(), segment.size.y(), segment.size.z()}},
          {"centroid", {segment.centroid.x(), segment.centroid.y(), segment.centroid.z()}},
          {"grasp", segment.top_grasp ? "top" : "side"},
          {"part", segment.part},
          {"color", {rgb[0], rgb[1], rgb[2]}}};
}

// As summary.json names them (src/app/run_report.cpp).
Json counts_json(const PipelineStats& stats) {
  return {{"frames_received", stats.frames_received}, {"sensor_gaps", stats.sensor_gaps},
          {"frames_completed", stats.frames_completed}, {"frames_failed", stats.frames_failed},
          {"frames_dropped", stats.frames_dropped}};
}

Json p50_p99(const Percentiles& p) { return {{"p50", p.p50}, {"p99", p.p99}}; }

Json latency_json(const WindowFigures& figures) {
  Json stages = Json::array();
  for (const StageInfo& info : kStages) {
    Json stage = p50_p99(figures.stages[static_cast<std::size_t>(info.stage)]);
    stage["name"] = info.name;
    stages.push_back(std::move(stage));
  }
  return {{"end_to_end", p50_p99(figures.end_to_end)}, {"stages", std::move(stages)}, {"frames", figures.frames}};
}

double frames_per_second(const std::deque<FrameTimes>& window) {
  if (window.size() < 2) return 0;
  const double last = window.back().at_s;
  auto first = window.end() - 1;
  while (first != window.begin() && last - (first - 1)->at_s <= kRateSeconds) --first;
  const double span = last - first->at_s;
  return span > 0 ? static_cast<double>(window.end() - 1 - first) / span : 0;
}

WindowFigures window_figures(const std::deque<FrameTimes>& window) {
  WindowFigures figures;
  std::vector<double> ms;
  for (const FrameTimes& times : window) ms.push_back(times.end_to_end_ms);
  figures.end_to_end = percentiles(ms);
  for (std::size_t stage = 0; stage < kStageCount; ++stage) {
    for (std::size_t i = 0; i < window.size(); ++i) ms[i] = window[i].stages.ms[stage];
    figures.stages[stage] = percentiles(ms);
  }
  figures.frames = window.size();
  figures.frames_per_second = frames_per_second(window);
  figures.at_s = window.empty() ? 0 : window.back().at_s;
  return figures;
}

Json header_json(const FrameSample* frame, const RunFigures& figures, std::size_t points) {
  Json header = {{"type", frame ? "frame" : "end"},
                 {"ended", figures.ended},
                 {"counts", counts_json(figures.stats)},
                 {"fps", figures.figures.frames_per_second},
                 {"latency", latency_json(figures.figures)}};
  if (frame == nullptr) return header;
  Json segments = Json::array();
  for (const SegmentSample& segment : frame->segments) segments.push_back(segment_json(segment));
  header.update({{"index", frame->index},     {"width", frame->width},       {"height", frame->height},
                 {"points", points},          {"segments", std::move(segments)},
                 {"support", frame->support_id ? frame->segments.size() + 1 : 0}, {"support_id", frame->support_id},
                 {"error", frame->error}});
  return header;
}

// The pixels' segment indices as runs: a segment covers whole stretches of a
// row, so a frame takes a few thousand runs instead of one value per pixel.
void append_label_runs(std::string& out, const FrameSample& frame, SegmentIndex& index) {
  const std::size_t count_at = out.size();
  append<std::uint32_t>(out, 0);
  std::uint32_t runs = 0;
  const std::size_t pixels = std::size_t{frame.width} * frame.height;
  for (std::size_t i = 0; i < pixels;) {
    const std::uint32_t label = frame.labels[i];
    std::size_t length = 1;
    while (i + length < pixels && length < 0xFFFF && frame.labels[i + length] == label) ++length;
    append(out, index(label));
    append(out, static_cast<std::uint16_t>(length));
    ++runs;
    i += length;
  }
  std::memcpy(out.data() + count_at, &runs, sizeof runs);
}

void append_image(std::string& out, const FrameSample& frame, SegmentIndex& index) {
  append_label_runs(out, frame, index);
  append_shade(out, frame);
  pad_to_4(out);
}

}  // namespace

FrameSample sample_frame(const FrameResult& result) {
  const PointCloud& cloud = result.frame.cloud;
  const Labels& labels = result.segmentation.labels;
  FrameSample sample;
  sample.index = result.frame.index;
  sample.error = result.error;
  if (labels.size() == cloud.size()) {
    if (cloud.organized()) {
      sample_image(cloud, labels, sample);
    } else {
      sample_points(cloud, labels, sample);
    }
  }
  sample.segments = segment_samples(result.segmentation);
  sample.support_id = result.segmentation.support_id;
  return sample;
}

FrameTimes frame_times(const FrameResult& result, double at_s) {
  return {at_s, result.end_to_end_ms(), result.segmentation.times};
}

void add_frame_times(RunFigures& run, const std::vector<FrameTimes>& times) {
  std::deque<FrameTimes>& window = run.window;
  window.insert(window.end(), times.begin(), times.end());
  if (window.empty()) return;
  const double now_s = window.back().at_s;
  while (now_s - window.front().at_s > kWindowSeconds) window.pop_front();
  if (run.ended || now_s - run.figures.at_s >= 1.0) run.figures = window_figures(window);
}

std::string encode_frame(const FrameSample* frame, const RunFigures& figures) {
  const std::vector<std::size_t> kept = frame ? points_3d(*frame) : std::vector<std::size_t>{};
  const std::string header = header_json(frame, figures, kept.size()).dump(-1, ' ', false, Json::error_handler_t::replace);
  std::string out;
  out.reserve(header.size() + 8 + (frame ? 3 * frame->points.size() + 8 * kept.size() : 0));
  append<std::uint32_t>(out, static_cast<std::uint32_t>(header.size()));
  out += header;
  pad_to_4(out);
  if (frame == nullptr) return out;
  SegmentIndex index(frame->segments, frame->support_id);
  append_image(out, *frame, index);
  std::vector<std::uint16_t> points;  // x, y, z (as i16), segment, per point
  points.reserve(4 * kept.size());
  for (const std::size_t i : kept) {
    const Eigen::Vector3f& p = frame->points[i];
    for (const float metres : {p.x(), p.y(), p.z()}) points.push_back(static_cast<std::uint16_t>(millimetres(metres)));
    points.push_back(index(frame->labels[i]));
  }
  out.append(reinterpret_cast<const char*>(points.data()), points.size() * sizeof(std::uint16_t));  // little-endian
  return out;
}

}  // namespace lccp::view
