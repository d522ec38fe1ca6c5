// lccp replay FILE.oni|FILE.bag: every frame of a recording, in order, segmented.
#include <filesystem>

#include "commands.hpp"
#include "lccp/capture/open_source.hpp"
#include "lccp/capture/rosbag.hpp"
#include "stream_run.hpp"

namespace lccp::app {
namespace {

struct ReplayCommandOptions {
  std::string recording;
  bool realtime = false;
  std::string topic;
  StreamOptions stream;
};

std::unique_ptr<FrameSource> open_bag_topic(const ReplayCommandOptions& options) {
  if (std::filesystem::path(options.recording).extension() != ".bag") {
    throw UsageError("--topic needs a .bag recording, not " + options.recording);
  }
  if (options.realtime) throw UsageError("--realtime needs an .oni recording");
  return limit_source(open_rosbag(options.recording, options.topic), options.stream.limits.limits());
}

int run_replay(const ReplayCommandOptions& options, std::stop_token stop) {
  options.stream.outputs.check();
  const auto source = options.topic.empty()
                          ? open_source({options.recording}, {options.stream.limits.limits(), options.realtime})
                          : open_bag_topic(options);
  return run_stream(*source, options.stream, "replay " + options.recording, stop);
}

}  // namespace

Subcommand add_replay_command(CLI::App& cli) {
  auto options = std::make_shared<ReplayCommandOptions>();
  CLI::App* command =
      cli.add_subcommand("replay", "segment every depth frame of an .oni recording or a rosbag (.bag), headless");
  command->add_option("recording", options->recording, "the .oni or .bag file")->required();
  command->add_option("--topic", options->topic,
                      ".bag only: the topic to read (default: the first depth image topic, sensor_msgs/Image with "
                      "the camera_info beside it, else the first sensor_msgs/PointCloud2 topic)");
  command->add_flag("--realtime", options->realtime,
                    ".oni only: pace frames by the recording's timestamps, as a live sensor would (late frames are "
                    "dropped)");
  options->stream.add_to(*command);
  return {command, [options](std::stop_token stop) { return run_replay(*options, stop); }};
}

}  // namespace lccp::app
