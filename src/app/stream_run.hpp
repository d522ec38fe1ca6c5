#pragma once
// Runs a frame source through the pipeline: per-frame outputs, progress, summary.
#include <functional>
#include <string>

#include "commands.hpp"
#include "frame_outputs.hpp"
#include "lccp/capture/frame_source.hpp"
#include "run_report.hpp"
#include "stop_signal.hpp"

namespace lccp::app {

// --inflight K (1..16), shared by the commands that run the pipeline.
void add_inflight_option(CLI::App& command, unsigned& frames_in_flight);

// Live sources (a device, --realtime replay) drop the oldest waiting frame; others block.
DropPolicy drop_policy_for(const FrameSource& source);

struct PipelineRunOptions {
  unsigned frames_in_flight = 2;  // K
  bool progress = true;           // progress line on stderr, if it is a terminal
};

// How one pipeline run ended and what it measured.
struct PipelineRun {
  RunReport report;          // every completed frame, the pipeline's counts, CPU use
  std::string source_error;  // the source failed mid-stream (device lost, corrupt recording); empty if it ended
  bool interrupted = false;  // Ctrl-C / SIGTERM stopped it
};

// Segments the frames of `source` on the pipeline (drop_policy_for(source))
// and records each completed frame; `on_frame`, if given, sees every completed
// frame in order, before it is recorded. Ctrl-C stops cleanly: frames in flight
// complete. An lccp::Error of the source (device lost, corrupt recording) or of
// `on_frame` ends the run after the frames in flight complete and is returned,
// not thrown; the counts then come from the frames the source delivered.
PipelineRun run_pipeline(FrameSource& source, const LccpSegmenter& segmenter, const PipelineRunOptions& options,
                         const StopOnSignal& stop, const std::function<void(const FrameResult&)>& on_frame = {});

struct StreamOptions {
  ConfigOptions config;
  FrameOutputOptions outputs;
  unsigned frames_in_flight = 2;
  bool quiet = false;

  void add_to(CLI::App& command);
};

// replay and live: run_pipeline, writing the per-frame outputs and
// DIR/summary.json, then the summary line. A source error is rethrown after
// the frames before it are written. Returns 0, or 130 if a non-live run was
// interrupted.
int run_stream(FrameSource& source, const StreamOptions& options, const std::string& description,
               const StopOnSignal& stop);

}  // namespace lccp::app
