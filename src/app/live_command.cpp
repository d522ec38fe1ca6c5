// lccp live: segment a live OpenNI2 depth stream until N frames, S seconds or Ctrl-C.
#include "commands.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "stream_run.hpp"

namespace lccp::app {
namespace {

struct LiveCommandOptions {
  std::string uri;
  std::uint64_t frames = 0;  // 0: no limit
  double seconds = 0;        // 0: no limit
  StreamOptions stream;
};

int run_live(const LiveCommandOptions& options) {
  const StopOnSignal stop;
  LiveOptions live;
  live.uri = options.uri;
  if (options.frames > 0) live.max_frames = options.frames;
  if (options.seconds > 0) live.max_seconds = options.seconds;
  const auto source = open_device(live);
  return run_stream(*source, options.stream, "live " + (options.uri.empty() ? std::string("first device") : options.uri),
                    stop);
}

}  // namespace

Subcommand add_live_command(CLI::App& cli) {
  auto options = std::make_shared<LiveCommandOptions>();
  CLI::App* command = cli.add_subcommand("live", "segment a live OpenNI2 depth sensor until N frames, S seconds or Ctrl-C");
  command->add_option("--uri", options->uri, "OpenNI2 device URI (default: the first device), e.g. virtual://synthetic");
  auto* frames = command->add_option("--frames", options->frames, "stop after N frames");
  auto* seconds = command->add_option("--seconds", options->seconds, "stop after S seconds")->check(CLI::PositiveNumber);
  frames->excludes(seconds);
  options->stream.add_to(*command);
  return {command, [options] { return run_live(*options); }};
}

}  // namespace lccp::app
