#pragma once
// Runs a frame source through the pipeline: per-frame outputs, progress,
// summary, exit code. Shared by replay, live and profile.
#include <functional>
#include <stop_token>
#include <string>

#include "commands.hpp"
#include "frame_outputs.hpp"
#include "lccp/capture/open_source.hpp"
#include "lccp/frame_source.hpp"
#include "lccp/view/view_server.hpp"
#include "run_report.hpp"

namespace lccp::app {

// --inflight K (1..16).
void add_inflight_option(CLI::App& command, unsigned& frames_in_flight);

// --frames N and --seconds S (each optional, N >= 1, S > 0).
struct LimitOptions {
  std::uint64_t frames = 0;  // 0: not given
  double seconds = 0;        // 0: not given

  void add_to(CLI::App& command);
  SourceLimits limits() const;
};

// --view [HOST:]PORT and --view-hold: the run in a browser (lccp/view/view_server.hpp).
struct ViewOptions {
  std::string address;  // empty: no view
  bool hold = false;

  void add_to(CLI::App& command);
  // The server, or none without --view. Prints its URL; with --view-hold,
  // returns once a page has opened the stream (or a stop was requested).
  std::unique_ptr<view::ViewServer> start(std::stop_token stop) const;
  // With --view-hold, after the run's outputs: serves until a stop (Ctrl-C).
  void hold_until_stopped(const view::ViewServer* server, std::stop_token stop) const;
};

struct PipelineRunOptions {
  unsigned frames_in_flight = 2;       // K
  bool progress = true;                // progress line on stderr, if it is a terminal
  view::ViewServer* view = nullptr;    // watches the run (PipelineConfig::observer)
};

// How one pipeline run ended and what it measured.
struct PipelineRun {
  RunReport report;          // every frame handed over, the pipeline's counts, CPU use
  std::string error;         // the source or on_frame failed (device lost, corrupt recording, disk full)
  bool interrupted = false;  // a stop was requested (Ctrl-C, SIGTERM)
};

// Segments the frames of `source` on the pipeline and records each frame
// handed over; `on_frame`, if given, sees each in order before it is recorded.
PipelineRun run_pipeline(FrameSource& source, const SceneSegmenter& segmenter, const PipelineRunOptions& options,
                         std::stop_token stop, const std::function<void(const FrameResult&)>& on_frame = {});

// The exit code of a run whose outputs are written: throws lccp::Error for its
// error; 1 if a batch of files (not a stream) had inputs that failed, each
// already named in an error line; 130, after a warning "interrupted after N
// [of T] frames", if a stop (Ctrl-C, SIGTERM) ended it, live sources
// included; else 0.
int exit_code(const PipelineRun& run, const FrameSource& source);

// replay and live: config, per-frame outputs, K, limits, --quiet.
struct StreamOptions {
  ConfigOptions config;
  FrameOutputOptions outputs;
  unsigned frames_in_flight = 2;
  LimitOptions limits;
  bool quiet = false;
  ViewOptions view;

  void add_to(CLI::App& command);
};

// replay and live: run_pipeline, writing the per-frame outputs and
// DIR/summary.json, then the summary line on stdout; exit_code().
int run_stream(FrameSource& source, const StreamOptions& options, const std::string& description,
               std::stop_token stop);

}  // namespace lccp::app
