// lccp record --uri URI -o FILE.oni --frames N: a device's depth stream to an .oni file.
#include <cstdio>

#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "lccp/capture/openni_sources.hpp"

namespace lccp::app {
namespace {

struct RecordCommandOptions {
  std::string uri;
  std::string output;
  std::uint64_t frames = 0;
};

int run_record(const RecordCommandOptions& options, std::stop_token stop) {
  LiveOptions live;
  live.uri = options.uri;
  const RecordStats stats = record_device(live, options.output, options.frames, stop);
  if (stats.frames != options.frames && !stop.stop_requested()) {
    spdlog::warn("the recording holds {} frames, not the {} asked for", stats.frames, options.frames);
  }
  std::printf("recorded %llu depth frames (%dx%d @ %d Hz) from %s to %s\n",
              static_cast<unsigned long long>(stats.frames), stats.mode.width, stats.mode.height, stats.mode.fps,
              options.uri.c_str(), options.output.c_str());
  return stats.frames == options.frames ? kExitDone : kExitInterrupted;
}

}  // namespace

Subcommand add_record_command(CLI::App& cli) {
  auto options = std::make_shared<RecordCommandOptions>();
  CLI::App* command = cli.add_subcommand("record", "record an OpenNI2 device's depth stream to an .oni file");
  command->add_option("--uri", options->uri, "OpenNI2 device URI, e.g. virtual://synthetic")->required();
  command->add_option("-o,--output", options->output, "the .oni file to write")->required();
  command->add_option("--frames", options->frames, "depth frames to record")->required()->check(CLI::Range(1, 1000000));
  return {command, [options](std::stop_token stop) { return run_record(*options, stop); }};
}

}  // namespace lccp::app
