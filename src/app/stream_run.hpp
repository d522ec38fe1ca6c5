#pragma once
// Runs a frame source through the pipeline: per-frame outputs, progress, summary.
#include <string>

#include "commands.hpp"
#include "frame_outputs.hpp"
#include "lccp/capture/frame_source.hpp"
#include "stop_signal.hpp"

namespace lccp::app {

struct StreamOptions {
  ConfigOptions config;
  FrameOutputOptions outputs;
  unsigned frames_in_flight = 2;
  bool quiet = false;

  void add_to(CLI::App& command);
};

// Segments every frame of `source` on the pipeline (drop policy by source:
// live sources drop the oldest waiting frame, others block), writes outputs
// and DIR/summary.json, prints the summary line. Ctrl-C stops cleanly: frames
// in flight complete and are written. A source error (device lost, corrupt
// recording) is rethrown after the frames before it are written.
// Returns 0, or 130 if a non-live run was interrupted.
int run_stream(FrameSource& source, const StreamOptions& options, const std::string& description,
               const StopOnSignal& stop);

}  // namespace lccp::app
