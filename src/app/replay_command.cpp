// lccp replay FILE.oni: every depth frame of a recording, in order, segmented.
#include "commands.hpp"
#include "stream_run.hpp"

namespace lccp::app {
namespace {

struct ReplayCommandOptions {
  std::string recording;
  bool realtime = false;
  StreamOptions stream;
};

int run_replay(const ReplayCommandOptions& options, std::stop_token stop) {
  options.stream.outputs.check();
  const auto source = open_source({options.recording}, {options.stream.limits.limits(), options.realtime});
  return run_stream(*source, options.stream, "replay " + options.recording, stop);
}

}  // namespace

Subcommand add_replay_command(CLI::App& cli) {
  auto options = std::make_shared<ReplayCommandOptions>();
  CLI::App* command = cli.add_subcommand("replay", "segment every depth frame of an .oni recording, headless");
  command->add_option("recording", options->recording, "the .oni file")->required();
  command->add_flag("--realtime", options->realtime,
                    "pace frames by the recording's timestamps, as a live sensor would (late frames are dropped)");
  options->stream.add_to(*command);
  return {command, [options](std::stop_token stop) { return run_replay(*options, stop); }};
}

}  // namespace lccp::app
