// lccp record-bag SOURCE -o OUT.bag: a recording's (or device's) depth frames as a
// rosbag, as openni2_camera publishes them (depth/image_raw + depth/camera_info).
#include <cstdio>

#include "commands.hpp"
#include "lccp/capture/open_source.hpp"
#include "lccp/capture/rosbag.hpp"

namespace lccp::app {
namespace {

struct RecordBagCommandOptions {
  std::string source;
  std::string output;
  std::uint64_t frames = 0;
};

int run_record_bag(const RecordBagCommandOptions& options, std::stop_token stop) {
  if (!rosbag_supported()) throw Error("record-bag: this build of lccp has no ROS (rosbag) support");
  SourceLimits limits;
  if (options.frames > 0) limits.max_frames = options.frames;
  const auto source = open_source({options.source}, {limits});
  const std::uint64_t frames = record_bag(*source, options.output, stop);
  std::printf("wrote %llu depth frames of %s to %s (/depth/image_raw, /depth/camera_info)\n",
              static_cast<unsigned long long>(frames), options.source.c_str(), options.output.c_str());
  return stop.stop_requested() && !source->is_live() ? kExitInterrupted : kExitDone;
}

}  // namespace

Subcommand add_record_bag_command(CLI::App& cli) {
  auto options = std::make_shared<RecordBagCommandOptions>();
  CLI::App* command = cli.add_subcommand(
      "record-bag", "write a recording's or device's depth frames to a rosbag: 16UC1 /depth/image_raw and "
                    "/depth/camera_info, stamped from the time of writing plus each frame's offset from the first; lccp replay gives the same labels");
  command->add_option("source", options->source, "an .oni recording or a device URI")->required();
  command->add_option("-o,--output", options->output, "the .bag file to write")->required();
  command->add_option("--frames", options->frames, "stop after N frames (default: all; a device: until Ctrl-C)")
      ->check(at_least_one());
  return {command, [options](std::stop_token stop) { return run_record_bag(*options, stop); }};
}

}  // namespace lccp::app
