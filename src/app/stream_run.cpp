#include "stream_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <thread>

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

// Calls pipeline.stop() once the stop flag is set, until the run ends.
class StopWatcher {
 public:
  StopWatcher(const std::atomic<bool>& flag, Pipeline& pipeline)
      : thread_([&flag, &pipeline, this] {
          while (!done_.load()) {
            if (flag.load()) {
              pipeline.stop();
              return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
        }) {}
  ~StopWatcher() {
    done_.store(true);
    thread_.join();
  }

 private:
  std::atomic<bool> done_{false};
  std::thread thread_;
};

// Forwards a source and counts what it delivers the way the pipeline does
// (frames taken; index gaps as lost frames), because the pipeline's own counts
// are lost when the source throws.
class CountedSource final : public FrameSource {
 public:
  explicit CountedSource(FrameSource& source) : source_(source) {}

  std::optional<Frame> next() override {
    std::optional<Frame> frame = source_.next();
    if (!frame) return frame;
    if (last_index_ && frame->index > *last_index_ + 1) lost_ += frame->index - *last_index_ - 1;
    last_index_ = frame->index;
    ++received_;
    return frame;
  }
  std::optional<std::uint64_t> frame_count() const override { return source_.frame_count(); }
  bool is_live() const override { return source_.is_live(); }
  void request_stop() override { source_.request_stop(); }

  // After a run that ended early: every frame taken and not completed counts as dropped.
  PipelineStats stats(std::uint64_t completed) const {
    PipelineStats stats;
    stats.frames_received = received_;
    stats.frames_completed = completed;
    stats.frames_dropped = received_ + lost_ - std::min(completed, received_ + lost_);
    return stats;
  }

 private:
  FrameSource& source_;
  std::optional<std::uint64_t> last_index_;
  std::uint64_t received_ = 0;
  std::uint64_t lost_ = 0;
};

}  // namespace

void add_inflight_option(CLI::App& command, unsigned& frames_in_flight) {
  command.add_option("--inflight", frames_in_flight, "frames processed at once (K)")
      ->check(CLI::Range(1u, 16u))
      ->capture_default_str();
}

DropPolicy drop_policy_for(const FrameSource& source) {
  return source.is_live() ? DropPolicy::drop_oldest : DropPolicy::block;
}

PipelineRun run_pipeline(FrameSource& source, const LccpSegmenter& segmenter, const PipelineRunOptions& options,
                         const StopOnSignal& stop, const std::function<void(const FrameResult&)>& on_frame) {
  PipelineConfig pipeline_config;
  pipeline_config.frames_in_flight = options.frames_in_flight;
  pipeline_config.drop_policy = drop_policy_for(source);
  Pipeline pipeline(segmenter, pipeline_config);
  CountedSource counted(source);

  const Clock::time_point start = Clock::now();
  const CpuTimes cpu_start = process_cpu_times();
  PipelineRun run{RunReport(start), {}, false};
  ProgressLine progress(options.progress, source.frame_count(), start);
  PipelineStats stats;
  {
    StopWatcher watcher(stop.flag(), pipeline);
    try {
      stats = pipeline.run(counted, [&](FrameResult& result) {
        if (!result.error.empty()) spdlog::warn("frame {}: {}", result.frame.index, result.error);
        if (on_frame) on_frame(result);
        run.report.add(result);
        progress.update(run.report.frames().size());
      });
    } catch (const Error& e) {
      run.source_error = e.what();
      stats = counted.stats(run.report.frames().size());
    }
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  if (!run.source_error.empty()) stats.wall_seconds = wall_s;
  const CpuTimes cpu_end = process_cpu_times();
  CpuUse cpu;
  cpu.user_s = cpu_end.user_s - cpu_start.user_s;
  cpu.system_s = cpu_end.system_s - cpu_start.system_s;
  cpu.wall_s = wall_s;
  cpu.cores = static_cast<unsigned>(std::max(1, tbb::this_task_arena::max_concurrency()));
  run.report.finish(stats, cpu);
  run.interrupted = stop.requested();
  return run;
}

void StreamOptions::add_to(CLI::App& command) {
  config.add_to(command);
  outputs.add_to(command);
  add_inflight_option(command, frames_in_flight);
  command.add_flag("-q,--quiet", quiet, "no progress line");
}

int run_stream(FrameSource& source, const StreamOptions& options, const std::string& description,
               const StopOnSignal& stop) {
  const LccpSegmenter segmenter(options.config.resolve());
  FrameWriter writer(options.outputs);
  const PipelineRun run = run_pipeline(source, segmenter, {options.frames_in_flight, !options.quiet}, stop,
                                       [&](const FrameResult& result) { writer.write(result); });
  if (!options.outputs.directory.empty()) {
    run.report.write_json(std::filesystem::path(options.outputs.directory) / "summary.json", description);
  }
  std::printf("%s: %s\n", description.c_str(), run.report.summary_line().c_str());
  if (!run.source_error.empty()) throw Error(run.source_error);
  if (run.interrupted && !source.is_live()) {
    const auto total = source.frame_count();
    spdlog::warn("interrupted after {} of {} frames", run.report.frames().size(), total ? std::to_string(*total) : "?");
    return 130;
  }
  return 0;
}

}  // namespace lccp::app
