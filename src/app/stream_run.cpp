#include "stream_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <mutex>

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include "lccp/error.hpp"

namespace lccp::app {
namespace {

// "\r[ 42/120] 29.8 frames/s, ETA 3 s" on a terminal's stderr.
class ProgressLine {
 public:
  ProgressLine(bool enabled, std::optional<std::uint64_t> total, Clock::time_point start)
      : enabled_(enabled && ::isatty(STDERR_FILENO)), total_(total), start_(start) {}
  ~ProgressLine() {
    if (shown_) std::fputc('\n', stderr);
  }
  void update(std::uint64_t done) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (shown_ && now - last_ < std::chrono::milliseconds(200) && (!total_ || done < *total_)) return;
    last_ = now;
    const double seconds = std::chrono::duration<double>(now - start_).count();
    const double fps = seconds > 0 ? static_cast<double>(done) / seconds : 0;
    if (total_ && fps > 0) {
      std::fprintf(stderr, "\r[%llu/%llu] %.1f frames/s, ETA %.0f s   ", static_cast<unsigned long long>(done),
                   static_cast<unsigned long long>(*total_), fps, static_cast<double>(*total_ - std::min(done, *total_)) / fps);
    } else {
      std::fprintf(stderr, "\r[%llu] %.1f frames/s   ", static_cast<unsigned long long>(done), fps);
    }
    shown_ = true;
  }

 private:
  bool enabled_;
  std::optional<std::uint64_t> total_;
  Clock::time_point start_;
  Clock::time_point last_{};
  bool shown_ = false;
};

CpuUse cpu_use_since(const CpuTimes& start, double wall_s) {
  const CpuTimes end = process_cpu_times();
  CpuUse cpu;
  cpu.user_s = end.user_s - start.user_s;
  cpu.system_s = end.system_s - start.system_s;
  cpu.wall_s = wall_s;
  cpu.cores = static_cast<unsigned>(std::max(1, tbb::this_task_arena::max_concurrency()));
  return cpu;
}

}  // namespace

namespace {

CLI::Validator lower_bound(bool inclusive, const std::string& message) {
  return CLI::Validator(
      [inclusive, message](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool number = end != text.c_str() && *end == '\0';
        return number && (inclusive ? value >= 1 : value > 0) ? std::string() : message;
      },
      "");
}

// A stream goes on past a frame that failed (a warning); in a batch of files
// each input is a result of its own, so a failure is an error line naming it.
void report_failed_frame(const FrameResult& result, const FrameSource& source) {
  if (source.is_stream()) {
    spdlog::warn("frame {}: {}", result.frame.index, result.error);
  } else {
    const std::string& name = result.frame.file.empty() ? result.frame.name : result.frame.file;
    std::fprintf(stderr, "lccp: error: %s: %s\n", name.c_str(), result.error.c_str());
  }
}

}  // namespace

CLI::Validator at_least_one() { return lower_bound(true, "must be at least 1"); }
CLI::Validator more_than_zero() { return lower_bound(false, "must be more than 0"); }

void add_inflight_option(CLI::App& command, unsigned& frames_in_flight) {
  command.add_option("--inflight", frames_in_flight, "frames processed at once (K, 1 to 16)")
      ->check(CLI::Range(1u, 16u))
      ->capture_default_str();
}

void LimitOptions::add_to(CLI::App& command) {
  command.add_option("--frames", frames, "stop after N frames (N >= 1; default: all)")->check(at_least_one());
  command.add_option("--seconds", seconds, "stop after S seconds (S > 0)")->check(more_than_zero());
}

SourceLimits LimitOptions::limits() const {
  SourceLimits limits;
  if (frames > 0) limits.max_frames = frames;
  if (seconds > 0) limits.max_seconds = seconds;
  return limits;
}

void ViewOptions::add_to(CLI::App& command) {
  command.add_option("--view", address,
                     "show the run in a browser: serve the live view on [HOST:]PORT (HOST 127.0.0.1 unless given; "
                     "PORT 0 picks a free one); the URL is printed");
  command.add_flag("--view-hold", hold,
                   "with --view: start when a page has opened the view, and keep serving it after the run until Ctrl-C");
}

std::unique_ptr<view::ViewServer> ViewOptions::start(std::stop_token stop) const {
  if (address.empty()) {
    if (hold) throw UsageError("--view-hold needs --view [HOST:]PORT");
    return nullptr;
  }
  auto server = std::make_unique<view::ViewServer>(view::parse_view_address(address));
  std::printf("view: %s\n", server->url().c_str());
  std::fflush(stdout);
  if (hold) {
    spdlog::info("view: waiting for a page to open {}", server->url());
    server->wait_for_viewer(stop);
  }
  return server;
}

void ViewOptions::hold_until_stopped(const view::ViewServer* server, std::stop_token stop) const {
  if (server == nullptr || !hold || stop.stop_requested()) return;
  spdlog::info("view: serving {} until Ctrl-C", server->url());
  std::mutex mutex;
  std::condition_variable_any stopped;
  std::unique_lock lock(mutex);
  stopped.wait(lock, stop, [] { return false; });
}

PipelineRun run_pipeline(FrameSource& source, const SceneSegmenter& segmenter, const PipelineRunOptions& options,
                         std::stop_token stop, const std::function<void(const FrameResult&)>& on_frame) {
  const Pipeline pipeline(segmenter, PipelineConfig{options.frames_in_flight, options.view});
  const Clock::time_point start = Clock::now();
  const CpuTimes cpu_start = process_cpu_times();
  PipelineRun run{RunReport(start), {}, false};
  ProgressLine progress(options.progress, source.frame_count(), start);
  const PipelineOutcome outcome = pipeline.run(
      source,
      [&](FrameResult& result) {
        if (!result.error.empty()) report_failed_frame(result, source);
        if (on_frame) on_frame(result);
        run.report.add(result);
        progress.update(run.report.frames().size());
      },
      stop);
  run.report.finish(outcome.stats, cpu_use_since(cpu_start, outcome.stats.wall_seconds));
  run.error = outcome.error;
  run.interrupted = stop.stop_requested();
  return run;
}

int exit_code(const PipelineRun& run, const FrameSource& source) {
  if (!run.error.empty()) throw Error(run.error);
  if (!source.is_stream() && run.report.stats().frames_failed > 0) return kExitError;  // each named on its own line
  if (!run.interrupted) return kExitDone;
  // Live sources too: a stop before the end (or before N frames or S seconds) is 130.
  const auto total = source.frame_count();
  const std::string done = std::to_string(run.report.frames().size());
  spdlog::warn("interrupted after {} frames", total ? done + " of " + std::to_string(*total) : done);
  return kExitInterrupted;
}

void StreamOptions::add_to(CLI::App& command) {
  config.add_to(command);
  outputs.add_to(command);
  add_inflight_option(command, frames_in_flight);
  limits.add_to(command);
  command.add_flag("-q,--quiet", quiet, "no progress line");
  view.add_to(command);
}

int run_stream(FrameSource& source, const StreamOptions& options, const std::string& description,
               std::stop_token stop) {
  const SceneSegmenter segmenter(options.config.resolve());
  FrameWriter writer(options.outputs);
  const auto view = options.view.start(stop);
  const PipelineRun run = run_pipeline(source, segmenter, {options.frames_in_flight, !options.quiet, view.get()}, stop,
                                       [&](const FrameResult& result) { writer.write(result); });
  if (!options.outputs.directory.empty()) {
    run.report.write_json(std::filesystem::path(options.outputs.directory) / "summary.json", description);
  }
  std::printf("%s: %s\n", description.c_str(), run.report.summary_line().c_str());
  std::fflush(stdout);
  options.view.hold_until_stopped(view.get(), stop);
  return exit_code(run, source);
}

}  // namespace lccp::app
