// lccp replay FILE.oni: every depth frame of a recording, in order, segmented.
#include "commands.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "stream_run.hpp"

namespace lccp::app {
namespace {

struct ReplayCommandOptions {
  std::string recording;
  std::uint64_t frames = 0;  // 0: all
  bool realtime = false;
  StreamOptions stream;
};

int run_replay(const ReplayCommandOptions& options) {
  const StopOnSignal stop;
  ReplayOptions replay;
  replay.realtime = options.realtime;
  if (options.frames > 0) replay.max_frames = options.frames;
  const auto source = open_recording(options.recording, replay);
  return run_stream(*source, options.stream, "replay " + options.recording, stop);
}

}  // namespace

Subcommand add_replay_command(CLI::App& cli) {
  auto options = std::make_shared<ReplayCommandOptions>();
  CLI::App* command = cli.add_subcommand("replay", "segment every depth frame of an .oni recording, headless");
  command->add_option("recording", options->recording, "the .oni file")->required();
  command->add_option("--frames", options->frames, "stop after N frames (default: all)");
  command->add_flag("--realtime", options->realtime,
                    "pace frames by the recording's timestamps, as a live sensor would (late frames are dropped)");
  options->stream.add_to(*command);
  return {command, [options] { return run_replay(*options); }};
}

}  // namespace lccp::app
