#include "stream_run.hpp"

#include <unistd.h>

#include <cstdio>
#include <thread>

#include <spdlog/spdlog.h>

#include "lccp/error.hpp"
#include "run_report.hpp"

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

}  // namespace

void StreamOptions::add_to(CLI::App& command) {
  config.add_to(command);
  outputs.add_to(command);
  command.add_option("--inflight", frames_in_flight, "frames processed at once (K)")
      ->check(CLI::Range(1u, 16u))
      ->capture_default_str();
  command.add_flag("-q,--quiet", quiet, "no progress line");
}

int run_stream(FrameSource& source, const StreamOptions& options, const std::string& description,
               const StopOnSignal& stop) {
  const LccpSegmenter segmenter(options.config.resolve());
  FrameWriter writer(options.outputs);
  PipelineConfig pipeline_config;
  pipeline_config.frames_in_flight = options.frames_in_flight;
  pipeline_config.drop_policy = source.is_live() ? DropPolicy::drop_oldest : DropPolicy::block;
  Pipeline pipeline(segmenter, pipeline_config);

  const Clock::time_point start = Clock::now();
  RunReport report(start);
  ProgressLine progress(!options.quiet, source.frame_count(), start);
  std::string source_error;
  {
    StopWatcher watcher(stop.flag(), pipeline);
    try {
      report.finish(pipeline.run(source, [&](FrameResult& result) {
        if (!result.error.empty()) spdlog::warn("frame {}: {}", result.frame.index, result.error);
        writer.write(result);
        report.add(result);
        progress.update(report.frames().size());
      }));
    } catch (const Error& e) {
      source_error = e.what();
    }
  }
  if (!source_error.empty()) {
    PipelineStats stats = report.stats();
    stats.frames_completed = report.frames().size();
    stats.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    report.finish(stats);
  }
  if (!options.outputs.directory.empty()) {
    report.write_json(std::filesystem::path(options.outputs.directory) / "summary.json", description);
  }
  std::printf("%s: %s\n", description.c_str(), report.summary_line().c_str());
  if (!source_error.empty()) throw Error(source_error);
  if (stop.requested() && !source.is_live()) {
    const auto total = source.frame_count();
    spdlog::warn("interrupted after {} of {} frames", report.frames().size(), total ? std::to_string(*total) : "?");
    return 130;
  }
  return 0;
}

}  // namespace lccp::app
