// lccp truth RECORDING.oni -o DIR: the ground truth of a recording of the
// virtual sensor's synthetic scene, regenerated frame by frame.
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "frame_outputs.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/synthetic/tabletop_scene.hpp"
#include "stop_signal.hpp"

namespace lccp::app {
namespace {

struct TruthOptions {
  std::string recording;
  std::string directory;
  std::uint64_t seed = 1;
};

int run_truth(const TruthOptions& options) {
  const auto source = open_recording(options.recording);
  const synthetic::TabletopScene scene(synthetic::Camera{}, options.seed);
  std::filesystem::create_directories(options.directory);
  std::uint64_t frames = 0;
  const StopOnSignal stop;
  while (std::optional<Frame> frame = stop.requested() ? std::nullopt : source->next()) {
    // The recorder starts its clock at the first frame, which `lccp record`
    // takes at the stream's start: the timestamp names the synthetic frame.
    const synthetic::SyntheticFrame truth = scene.render(synthetic::frame_of_timestamp_us(frame->timestamp_us));
    const DepthImage& recorded = *frame->depth;
    if (truth.depth.width != recorded.width || truth.depth.height != recorded.height) {
      throw Error(options.recording + " is " + std::to_string(recorded.width) + "x" + std::to_string(recorded.height) +
                  ", not the synthetic scene's " + std::to_string(truth.depth.width) + "x" +
                  std::to_string(truth.depth.height));
    }
    Labels labels = truth.labels;
    for (std::size_t i = 0; i < labels.size(); ++i) {
      if (recorded.depth_mm[i] == 0) labels[i] = synthetic::kNoReturnLabel;
    }
    const std::filesystem::path path = std::filesystem::path(options.directory) / (frame_output_stem(*frame) + ".pcd");
    write_labelled_pcd(path, back_project(recorded), labels);
    ++frames;
  }
  std::printf("wrote the ground truth of %llu frames to %s\n", static_cast<unsigned long long>(frames),
              options.directory.c_str());
  return stop.requested() ? 130 : 0;
}

}  // namespace

Subcommand add_truth_command(CLI::App& cli) {
  auto options = std::make_shared<TruthOptions>();
  CLI::App* command = cli.add_subcommand(
      "truth", "regenerate the ground truth of a recording of the virtual sensor's synthetic scene (for lccp eval)");
  command->add_option("recording", options->recording, "an .oni made with lccp record --uri virtual://synthetic")
      ->required();
  command->add_option("-o,--output-dir", options->directory, "folder for one labelled .pcd per frame")->required();
  command->add_option("--seed", options->seed, "the scene's seed (the URI's seed=, default 1)")->capture_default_str();
  return {command, [options] { return run_truth(*options); }};
}

}  // namespace lccp::app
