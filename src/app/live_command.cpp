// lccp live: segment a live OpenNI2 depth stream until N frames, S seconds or Ctrl-C.
#include "commands.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "stream_run.hpp"

namespace lccp::app {
namespace {

struct LiveCommandOptions {
  std::string uri;
  StreamOptions stream;
};

int run_live(const LiveCommandOptions& options, std::stop_token stop) {
  options.stream.outputs.check();
  const std::string uri = options.uri.empty() ? first_sensor_uri() : options.uri;
  if (source_kind({uri}) != SourceKind::device) {
    throw UsageError("--uri " + uri + " is not a device URI (e.g. virtual://synthetic); lccp replay plays .oni files");
  }
  const auto source = open_source({uri}, {options.stream.limits.limits(), false});
  return run_stream(*source, options.stream, "live " + uri, stop);
}

}  // namespace

Subcommand add_live_command(CLI::App& cli) {
  auto options = std::make_shared<LiveCommandOptions>();
  CLI::App* command = cli.add_subcommand("live", "segment a live OpenNI2 depth sensor until N frames, S seconds or Ctrl-C");
  command->add_option("--uri", options->uri,
                      "OpenNI2 device URI (default: the first attached sensor; lccp devices lists them), "
                      "e.g. virtual://synthetic for the built-in virtual sensor");
  options->stream.add_to(*command);
  return {command, [options](std::stop_token stop) { return run_live(*options, stop); }};
}

}  // namespace lccp::app
