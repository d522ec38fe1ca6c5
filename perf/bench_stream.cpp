// bench_stream: the streaming pipeline (lccp::Pipeline) on a 640x480 .oni recording at P1,
// against PCL 1.13's LCCP on the same back-projected clouds, in one process.
//
// Every depth frame of the recording is read once and kept in memory; an in-memory
// FrameSource then replays them as depth images, so back-projection is part of what is
// measured. For each TBB thread count T and frames in flight K:
//   throughput - the source hands out frames as fast as the pipeline takes them
//                (DropPolicy::block), `rounds` passes over the recording;
//                frames/s = frames completed / PipelineStats::wall_seconds.
//   paced      - like a live sensor: frame i is released at start + i / fps
//                (Frame::captured = that instant), DropPolicy::drop_oldest; latency is
//                FrameResult::end_to_end_ms() (captured -> labels ready).
// Then the references: LccpSegmenter::segment one frame at a time, and PCL one frame at a
// time (PCL is sequential), on the same clouds. Prints markdown; --json writes the figures.
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "lccp/process.hpp"

#include "lccp/frame_source.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/config.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/error.hpp"
#include "lccp/frame.hpp"
#include "lccp/pipeline/pipeline.hpp"
#include "pcl_reference.hpp"
#include "statistics.hpp"

namespace {

namespace fs = std::filesystem;
using lccp::Clock;

struct Options {
  std::string recording = LCCP_DEFAULT_RECORDING;
  std::size_t rounds = 5;      // passes over the recording per pipeline run
  std::size_t pcl_rounds = 1;  // passes for PCL and for our single-frame reference
  std::vector<unsigned> threads{1, 2};
  std::vector<unsigned> inflight{1, 2, 3};
  double fps = 30;            // release rate of the paced runs
  std::size_t warmup = 10;    // untimed frames through the pipeline before each (T, K)
  unsigned reference_threads = 2;  // T for our single-frame reference
  bool no_pcl = false;
  std::string json;
};

// ---------------------------------------------------------------------------------------
// The source

// The recording's depth images, replayed `count` frames long (looping over the images),
// either as fast as they are asked for or released on a fixed clock like a live sensor.
class MemorySource final : public lccp::FrameSource {
 public:
  MemorySource(const std::vector<lccp::DepthImage>& images, std::uint64_t count, std::optional<double> fps)
      : images_(images), count_(count), fps_(fps) {}

  std::optional<lccp::Frame> next(std::stop_token stop) override {
    if (stop.stop_requested() || delivered_ >= count_) return std::nullopt;
    lccp::Frame frame;
    frame.index = delivered_;
    frame.timestamp_us = fps_ ? static_cast<std::uint64_t>(std::llround(1e6 * static_cast<double>(delivered_) / *fps_)) : 0;
    frame.depth = images_[delivered_ % images_.size()];  // the copy is made before the release time
    if (fps_) {
      if (delivered_ == 0) start_ = Clock::now();
      const auto release =
          start_ + std::chrono::duration_cast<Clock::duration>(
                       std::chrono::duration<double>(static_cast<double>(delivered_) / *fps_));
      std::this_thread::sleep_until(release);  // the benchmark never stops a run early
      frame.captured = release;  // a sensor's frame exists from this instant, whenever we read it
    } else {
      frame.captured = Clock::now();
    }
    ++delivered_;
    return frame;
  }

  std::optional<std::uint64_t> frame_count() const override { return count_; }
  bool is_live() const override { return fps_.has_value(); }

 private:
  const std::vector<lccp::DepthImage>& images_;
  std::uint64_t count_;
  std::optional<double> fps_;
  std::uint64_t delivered_ = 0;
  Clock::time_point start_{};
};

// ---------------------------------------------------------------------------------------
// Statistics

using lccp::perf::mean;
using lccp::perf::median;
using lccp::perf::ms_since;

// User + system CPU seconds of this process so far.
double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  if (!(in >> one >> five >> fifteen)) return "unknown";
  return one + " " + five + " " + fifteen;
}

std::string now_string() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S %Z", std::localtime(&t));
  return buf;
}

// Median per stage over a run's frames, ms.
struct StageMedians {
  // "waiting": end-to-end minus back-projection minus segment, i.e. time spent waiting
  // for a slot (paced: in the admission gate) or between stages.
  static constexpr std::size_t kCount = 15;
  static constexpr const char* kNames[kCount] = {"back_projection", "support",    "voxelize", "normals", "seeds",
                                                 "growth",          "adjacency",  "classify", "components",
                                                 "filter",          "parts",      "geometry", "ids",     "segment",
                                                 "waiting"};
  double ms[kCount] = {};
};

struct FrameRecord {
  double end_to_end_ms = 0;
  double stages_ms[StageMedians::kCount] = {};
};

// ---------------------------------------------------------------------------------------
// Pipeline runs

enum class Mode { throughput, paced };
const char* mode_name(Mode m) { return m == Mode::throughput ? "throughput" : "paced"; }

struct RunResult {
  Mode mode = Mode::throughput;
  unsigned threads = 0;
  unsigned inflight = 0;
  lccp::PipelineStats stats;
  std::uint64_t frame_errors = 0;
  double frames_per_s = 0;
  double cpu_per_wall = 0;  // mean busy cores of this process over the run
  double p50 = 0, p95 = 0, p99 = 0, max = 0;  // end-to-end ms
  StageMedians stages;
};

RunResult run_pipeline(const lccp::SceneSegmenter& segmenter, const std::vector<lccp::DepthImage>& images,
                       Mode mode, unsigned threads, unsigned inflight, std::uint64_t frames, double fps) {
  lccp::PipelineConfig config;
  config.frames_in_flight = inflight;
  // A paced source is live (MemorySource::is_live): the pipeline drops the oldest.
  lccp::Pipeline pipeline(segmenter, config);
  MemorySource source(images, frames, mode == Mode::paced ? std::optional<double>(fps) : std::nullopt);

  std::vector<FrameRecord> records;
  records.reserve(frames);
  std::uint64_t errors = 0;
  const double cpu_start = cpu_seconds();
  const lccp::PipelineStats stats = pipeline.run(source, [&](lccp::FrameResult& r) {
    if (!r.error.empty()) {
      ++errors;
      return;
    }
    const lccp::StageTimes& t = r.segmentation.times;
    FrameRecord record;
    record.end_to_end_ms = r.end_to_end_ms();
    // back_projection, the stages of lccp::kStages, segment, waiting (StageMedians::kNames)
    static_assert(StageMedians::kCount == lccp::kStageCount + 3);
    record.stages_ms[0] = r.back_projection_ms;
    std::copy(t.ms.begin(), t.ms.end(), record.stages_ms + 1);
    record.stages_ms[lccp::kStageCount + 1] = t.total_ms();
    record.stages_ms[lccp::kStageCount + 2] = record.end_to_end_ms - r.back_projection_ms - t.total_ms();
    records.push_back(record);
  }).stats;
  const double cpu = cpu_seconds() - cpu_start;

  RunResult result;
  result.mode = mode;
  result.threads = threads;
  result.inflight = inflight;
  result.stats = stats;
  result.frame_errors = errors;
  result.frames_per_s = stats.wall_seconds > 0 ? static_cast<double>(stats.frames_completed) / stats.wall_seconds : 0;
  result.cpu_per_wall = stats.wall_seconds > 0 ? cpu / stats.wall_seconds : 0;
  std::vector<double> latency;
  latency.reserve(records.size());
  for (const FrameRecord& r : records) latency.push_back(r.end_to_end_ms);
  result.p50 = lccp::percentile(latency, 0.50);
  result.p95 = lccp::percentile(latency, 0.95);
  result.p99 = lccp::percentile(latency, 0.99);
  result.max = latency.empty() ? 0 : *std::max_element(latency.begin(), latency.end());
  for (std::size_t s = 0; s < StageMedians::kCount; ++s) {
    std::vector<double> values;
    values.reserve(records.size());
    for (const FrameRecord& r : records) values.push_back(r.stages_ms[s]);
    result.stages.ms[s] = median(std::move(values));
  }
  return result;
}

// ---------------------------------------------------------------------------------------
// References: one frame at a time

struct Reference {
  bool ran = false;
  std::size_t frames = 0;
  double median_ms = 0;
  double mean_ms = 0;
  double p95_ms = 0;
  double frames_per_s = 0;  // 1000 / mean
  double convert_median_ms = 0;      // PCL only: lccp::PointCloud -> pcl::PointXYZRGBA, not in median_ms
  double supervoxels_median_ms = 0;  // PCL only
  double lccp_median_ms = 0;         // PCL only
};

Reference summarize(const std::vector<double>& ms) {
  Reference r;
  r.ran = true;
  r.frames = ms.size();
  r.median_ms = median(ms);
  r.mean_ms = mean(ms);
  r.p95_ms = lccp::percentile(ms, 0.95);
  r.frames_per_s = r.mean_ms > 0 ? 1000.0 / r.mean_ms : 0;
  return r;
}

Reference ours_single_frame(const lccp::LccpSegmenter& segmenter, const std::vector<lccp::PointCloud>& clouds,
                            std::size_t rounds) {
  (void)segmenter.segment(clouds.front());  // warm-up: TBB start-up, first-touch of the allocator's pages
  std::vector<double> ms;
  for (std::size_t round = 0; round < rounds; ++round) {
    for (const lccp::PointCloud& cloud : clouds) {
      const auto start = Clock::now();
      const lccp::SegmentationResult r = segmenter.segment(cloud);
      ms.push_back(ms_since(start));
      if (r.labels.size() != cloud.size()) throw lccp::Error("segment returned the wrong number of labels");
    }
  }
  return summarize(ms);
}

// PCL's time is supervoxels + LCCP + per-point labels, as in bench_segment: a PCL user
// already holds a pcl::PointCloud, so the conversion is reported apart.
Reference pcl_single_frame(const lccp::LccpConfig& config, const std::vector<lccp::PointCloud>& clouds,
                           std::size_t rounds) {
  (void)lccp::perf::run_pcl_lccp(clouds.front(), config);  // warm-up
  std::vector<double> ms, convert, supervoxels, lccp_ms;
  for (std::size_t round = 0; round < rounds; ++round) {
    for (const lccp::PointCloud& cloud : clouds) {
      const lccp::perf::PclLccpResult r = lccp::perf::run_pcl_lccp(cloud, config);
      ms.push_back(r.supervoxels_ms + r.lccp_ms + r.labels_ms);
      convert.push_back(r.convert_ms);
      supervoxels.push_back(r.supervoxels_ms);
      lccp_ms.push_back(r.lccp_ms);
    }
  }
  Reference result = summarize(ms);
  result.convert_median_ms = median(convert);
  result.supervoxels_median_ms = median(supervoxels);
  result.lccp_median_ms = median(lccp_ms);
  return result;
}

// ---------------------------------------------------------------------------------------
// Output

const RunResult* find_run(const std::vector<RunResult>& runs, Mode mode, unsigned threads, unsigned inflight) {
  for (const RunResult& r : runs)
    if (r.mode == mode && r.threads == threads && r.inflight == inflight) return &r;
  return nullptr;
}

// The throughput run with the most frames/s at `threads`.
const RunResult* best_throughput(const std::vector<RunResult>& runs, unsigned threads) {
  const RunResult* best = nullptr;
  for (const RunResult& r : runs)
    if (r.mode == Mode::throughput && r.threads == threads && (best == nullptr || r.frames_per_s > best->frames_per_s))
      best = &r;
  return best;
}

unsigned long long ull(std::uint64_t v) { return static_cast<unsigned long long>(v); }

struct Targets {
  double min_frames_per_s = 30;
  double max_p99_ms = 66;
  unsigned threads = 2;
};

// Both targets for one K: the throughput run sustains the rate, and the paced run keeps
// up (nothing dropped) with p99 within the bound.
bool meets_targets(const RunResult& throughput, const RunResult& paced, const Targets& t) {
  return throughput.frames_per_s >= t.min_frames_per_s && paced.stats.frames_dropped == 0 && paced.p99 <= t.max_p99_ms;
}

void print_report(const Options& options, const std::string& command, const std::string& date,
                  const std::string& load_before, const std::string& load_after, std::size_t frame_count,
                  const lccp::DepthImage& first, const std::vector<RunResult>& runs, const Reference& ours,
                  const Reference& pcl, const Targets& targets) {
  std::printf("# bench_stream: streaming pipeline vs PCL 1.13, P1\n\n");
  std::printf("- date: %s\n- command: `%s`\n", date.c_str(), command.c_str());
  std::printf("- load average (1/5/15 min) before: %s; after: %s\n", load_before.c_str(), load_after.c_str());
  std::printf("- recording: %s, %zu frames %ux%u; pipeline runs: %zu round(s) = %zu frames each; paced at %.1f frames/s\n",
              options.recording.c_str(), frame_count, first.width, first.height, options.rounds,
              frame_count * options.rounds, options.fps);
  std::printf("- config: LccpConfig defaults (P1: v 5 mm, s 2 cm, w_n 4, w_s 1, w_c 0, beta_thresh 10 deg, SC on, "
              "n_filter 3)\n");
  std::printf("- %zu untimed warm-up frames before each (T, K); cpu = process CPU seconds / wall seconds\n\n",
              options.warmup);

  std::printf("## Pipeline: throughput (block) and paced latency (drop_oldest), end-to-end ms\n\n");
  std::printf("| T | K | throughput frames/s | cpu (throughput) | paced p50 | p95 | p99 | max | dropped / received | keeps up | cpu (paced) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (unsigned t : options.threads) {
    for (unsigned k : options.inflight) {
      const RunResult* tp = find_run(runs, Mode::throughput, t, k);
      const RunResult* pc = find_run(runs, Mode::paced, t, k);
      if (tp == nullptr || pc == nullptr) continue;
      std::printf("| %u | %u | %.1f | %.2f | %.1f | %.1f | %.1f | %.1f | %llu / %llu | %s | %.2f |\n", t, k,
                  tp->frames_per_s, tp->cpu_per_wall, pc->p50, pc->p95, pc->p99, pc->max,
                  ull(pc->stats.frames_dropped), ull(pc->stats.frames_received),
                  pc->stats.frames_dropped == 0 ? "yes" : "no", pc->cpu_per_wall);
    }
  }
  std::uint64_t errors = 0;
  for (const RunResult& r : runs) errors += r.frame_errors;
  if (errors != 0) std::printf("\n**%llu frame(s) failed in a stage** (left out of the statistics)\n", ull(errors));

  std::printf("\n## Median ms per stage (per frame; back_projection is the pipeline's first stage)\n\n");
  std::printf("| run | T | K |");
  for (const char* name : StageMedians::kNames) std::printf(" %s |", name);
  std::printf(" e2e p50 |\n|---|---|---|");
  for (std::size_t s = 0; s < StageMedians::kCount; ++s) std::printf("---|");
  std::printf("---|\n");
  for (const RunResult& r : runs) {
    std::printf("| %s | %u | %u |", mode_name(r.mode), r.threads, r.inflight);
    for (double ms : r.stages.ms) std::printf(" %.2f |", ms);
    std::printf(" %.1f |\n", r.p50);
  }

  std::printf("\n## One frame at a time, same back-projected clouds\n\n");
  std::printf("| method | frames | median ms | mean ms | p95 ms | frames/s (1000 / mean) |\n|---|---|---|---|---|---|\n");
  if (ours.ran)
    std::printf("| ours, LccpSegmenter::segment, T=%u | %zu | %.1f | %.1f | %.1f | %.1f |\n", options.reference_threads,
                ours.frames, ours.median_ms, ours.mean_ms, ours.p95_ms, ours.frames_per_s);
  if (pcl.ran) {
    std::printf("| PCL 1.13 (supervoxels + LCCP + labels) | %zu | %.1f | %.1f | %.1f | %.1f |\n", pcl.frames,
                pcl.median_ms, pcl.mean_ms, pcl.p95_ms, pcl.frames_per_s);
    std::printf("\nPCL medians: supervoxels %.1f ms, LCCP %.1f ms; conversion to pcl::PointXYZRGBA %.1f ms (not "
                "counted).\n",
                pcl.supervoxels_median_ms, pcl.lccp_median_ms, pcl.convert_median_ms);
  }

  std::printf("\n## Ratios and targets (T=%u)\n\n", targets.threads);
  const RunResult* best = best_throughput(runs, targets.threads);
  const RunResult* paced_k2 = find_run(runs, Mode::paced, targets.threads, 2);
  if (pcl.ran && best != nullptr)
    std::printf("- throughput: ours %.1f frames/s (K=%u, best K) / PCL %.1f frames/s = %.2fx\n", best->frames_per_s,
                best->inflight, pcl.frames_per_s, best->frames_per_s / pcl.frames_per_s);
  if (pcl.ran && paced_k2 != nullptr)
    std::printf("- latency: PCL median %.1f ms / ours paced median end-to-end %.1f ms (K=2) = %.2fx\n", pcl.median_ms,
                paced_k2->p50, pcl.median_ms / paced_k2->p50);
  if (pcl.ran && ours.ran)
    std::printf("- single frame: PCL median %.1f ms / ours median %.1f ms = %.2fx\n", pcl.median_ms, ours.median_ms,
                pcl.median_ms / ours.median_ms);
  bool any = false;
  for (unsigned k : options.inflight) {
    const RunResult* tp = find_run(runs, Mode::throughput, targets.threads, k);
    const RunResult* pc = find_run(runs, Mode::paced, targets.threads, k);
    if (tp == nullptr || pc == nullptr) continue;
    const bool ok = meets_targets(*tp, *pc, targets);
    any = any || ok;
    std::printf("- K=%u: throughput %.1f frames/s (%s %.0f), paced p99 %.1f ms (%s %.0f), dropped %llu: %s\n", k,
                tp->frames_per_s, tp->frames_per_s >= targets.min_frames_per_s ? ">=" : "<", targets.min_frames_per_s,
                pc->p99, pc->p99 <= targets.max_p99_ms ? "<=" : ">", targets.max_p99_ms, ull(pc->stats.frames_dropped),
                ok ? "targets hold" : "targets missed");
  }
  std::printf("\n**Targets (>= %.0f frames/s sustained, p99 <= %.0f ms, T=%u): %s**\n", targets.min_frames_per_s,
              targets.max_p99_ms, targets.threads, any ? "hold for at least one K" : "missed for every K");
}

nlohmann::ordered_json run_json(const RunResult& r) {
  nlohmann::ordered_json stages = nlohmann::ordered_json::object();
  for (std::size_t s = 0; s < StageMedians::kCount; ++s) stages[StageMedians::kNames[s]] = r.stages.ms[s];
  return {{"mode", mode_name(r.mode)},
          {"threads", r.threads},
          {"inflight", r.inflight},
          {"received", r.stats.frames_received},
          {"completed", r.stats.frames_completed},
          {"dropped", r.stats.frames_dropped},
          {"frame_errors", r.frame_errors},
          {"wall_s", r.stats.wall_seconds},
          {"frames_per_s", r.frames_per_s},
          {"cpu_per_wall", r.cpu_per_wall},
          {"e2e_ms", {{"p50", r.p50}, {"p95", r.p95}, {"p99", r.p99}, {"max", r.max}}},
          {"stage_median_ms", std::move(stages)}};
}

// null when the reference did not run; PCL's has its parts' medians too.
nlohmann::ordered_json reference_json(const Reference& r, bool pcl) {
  if (!r.ran) return nullptr;
  nlohmann::ordered_json json = {{"frames", r.frames},   {"median_ms", r.median_ms},      {"mean_ms", r.mean_ms},
                                 {"p95_ms", r.p95_ms}, {"frames_per_s", r.frames_per_s}};
  if (pcl) {
    json.update({{"supervoxels_median_ms", r.supervoxels_median_ms},
                 {"lccp_median_ms", r.lccp_median_ms},
                 {"convert_median_ms", r.convert_median_ms}});
  }
  return json;
}

// The results as JSON (nlohmann/json, https://json.nlohmann.me/), indented by two spaces.
void write_json(const fs::path& path, const Options& options, const std::string& command, const std::string& date,
                const std::string& load_before, const std::string& load_after, std::size_t frame_count,
                const std::vector<RunResult>& runs, const Reference& ours, const Reference& pcl) {
  std::ofstream out(path);
  if (!out) throw lccp::Error("cannot write " + path.string());
  nlohmann::ordered_json json = {{"date", date},
                                 {"command", command},
                                 {"load_before", load_before},
                                 {"load_after", load_after},
                                 {"recording", options.recording},
                                 {"recording_frames", frame_count},
                                 {"rounds", options.rounds},
                                 {"paced_fps", options.fps},
                                 {"runs", nlohmann::ordered_json::array()}};
  for (const RunResult& r : runs) json["runs"].push_back(run_json(r));
  json["ours_single_frame_threads"] = options.reference_threads;
  json["ours_single_frame"] = reference_json(ours, false);
  json["pcl"] = reference_json(pcl, true);
  out << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The streaming pipeline on a recording at P1: throughput and paced latency, vs PCL 1.13's LCCP"};
  Options options;
  app.add_option("--recording", options.recording, ".oni recording (read once, replayed from memory)")
      ->capture_default_str();
  app.add_option("--rounds", options.rounds, "passes over the recording per pipeline run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--pcl-rounds", options.pcl_rounds, "passes over the recording for PCL and our single-frame reference")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--threads", options.threads, "TBB thread counts T to run (list)")
      ->check(CLI::Range(1u, 64u))
      ->capture_default_str();
  app.add_option("--inflight", options.inflight, "frames in flight K to run (list)")
      ->check(CLI::Range(1u, 16u))
      ->capture_default_str();
  app.add_option("--fps", options.fps, "release rate of the paced runs")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--warmup", options.warmup, "untimed frames through the pipeline before each (T, K)")
      ->capture_default_str();
  app.add_option("--reference-threads", options.reference_threads, "T for our single-frame reference")
      ->check(CLI::Range(1u, 64u))
      ->capture_default_str();
  app.add_flag("--no-pcl", options.no_pcl, "skip PCL (no ratios)");
  app.add_option("--json", options.json, "also write the figures as JSON to this file");
  CLI11_PARSE(app, argc, argv);

  try {
    lccp::keep_freed_memory_for_next_frames();  // as lccp's main does; applies to PCL too
    lccp::perf::quiet_pcl_console();
    std::string command;
    for (int i = 0; i < argc; ++i) command += (i > 0 ? " " : "") + std::string(argv[i]);
    const std::string date = now_string();
    const std::string load_before = load_average();

    // Every frame of the recording, as depth images, before anything is timed.
    std::vector<lccp::DepthImage> images;
    {
      const std::unique_ptr<lccp::FrameSource> recording = lccp::open_recording(options.recording);
      while (std::optional<lccp::Frame> frame = recording->next(std::stop_token{})) {
        if (!frame->depth) throw lccp::Error(options.recording + ": frame " + std::to_string(frame->index) + " has no depth");
        images.push_back(std::move(*frame->depth));
      }
    }
    if (images.empty()) throw lccp::Error(options.recording + " holds no frame");
    std::fprintf(stderr, "bench_stream: %zu frames %ux%u from %s; load %s\n", images.size(), images.front().width,
                 images.front().height, options.recording.c_str(), load_before.c_str());

    const lccp::LccpConfig config;  // defaults = P1
    const lccp::LccpSegmenter segmenter(config);
    const lccp::SceneSegmenter stream_segmenter(lccp::SceneConfig{config, std::nullopt});

    // References on the clouds the pipeline's first stage makes.
    Reference ours, pcl;
    {
      std::vector<lccp::PointCloud> clouds;
      clouds.reserve(images.size());
      for (const lccp::DepthImage& image : images) clouds.push_back(lccp::back_project(image));
      {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, options.reference_threads);
        ours = ours_single_frame(segmenter, clouds, options.pcl_rounds);
      }
      std::fprintf(stderr, "bench_stream: ours single frame (T=%u) median %.1f ms\n", options.reference_threads,
                   ours.median_ms);
      if (!options.no_pcl) {
        pcl = pcl_single_frame(config, clouds, options.pcl_rounds);
        std::fprintf(stderr, "bench_stream: PCL median %.1f ms\n", pcl.median_ms);
      }
    }

    std::vector<RunResult> runs;
    const std::uint64_t frames = images.size() * options.rounds;
    for (unsigned t : options.threads) {
      for (unsigned k : options.inflight) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, t);
        if (options.warmup > 0)
          (void)run_pipeline(stream_segmenter, images, Mode::throughput, t, k, options.warmup, options.fps);
        for (Mode mode : {Mode::throughput, Mode::paced}) {
          runs.push_back(run_pipeline(stream_segmenter, images, mode, t, k, frames, options.fps));
          const RunResult& r = runs.back();
          std::fprintf(stderr,
                       "bench_stream: T=%u K=%u %-10s %6.1f frames/s  e2e p50 %6.1f p99 %6.1f max %6.1f ms  dropped "
                       "%llu  cpu %.2f  load %s\n",
                       t, k, mode_name(mode), r.frames_per_s, r.p50, r.p99, r.max, ull(r.stats.frames_dropped),
                       r.cpu_per_wall, load_average().c_str());
        }
      }
    }

    const std::string load_after = load_average();
    const Targets targets;
    print_report(options, command, date, load_before, load_after, images.size(), images.front(), runs, ours, pcl,
                 targets);
    if (!options.json.empty())
      write_json(options.json, options, command, date, load_before, load_after, images.size(), runs, ours, pcl);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_stream: %s\n", e.what());
    return 1;
  }
}
