// lccp truth RECORDING.oni -o DIR: the ground truth of a recording of the
// virtual sensor's synthetic scene, regenerated frame by frame, as labelled PCDs
// in the OSD / mOSD convention (lccp/synthetic/tabletop_scene.hpp): 0 no
// return, 1 table, 2 floor and wall, object n's parts n * 10 + k (the mug's
// handle its own part), so label / 10 is an object id that holds over frames.
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "frame_outputs.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/synthetic/tabletop_scene.hpp"

namespace lccp::app {
namespace {

struct TruthOptions {
  std::string recording;
  std::string directory;
  std::uint64_t seed = 1;
};

// The most pixels in which a frame may differ from the scene's rendering:
// OpenNI2's 16zT encoder may give up to 28 pixels before a frame's last one the
// last pixel's value (recordings/README.md).
constexpr std::size_t kCodecTailPixels = 28;

// The scene's frame, after checking that the recorded one is it: a recording of
// anything else has no ground truth here.
synthetic::SyntheticFrame matching_truth(const synthetic::TabletopScene& scene, const Frame& frame,
                                         const TruthOptions& options) {
  // The recorder starts its clock at the first frame, which `lccp record` takes
  // at the stream's start: the timestamp names the synthetic frame.
  synthetic::SyntheticFrame truth = scene.render(synthetic::frame_of_timestamp_us(frame.timestamp_us));
  const DepthImage& recorded = *frame.depth;
  std::size_t differing = 0;
  if (truth.depth.width == recorded.width && truth.depth.height == recorded.height) {
    for (std::size_t i = 0; i < recorded.depth_mm.size(); ++i) differing += recorded.depth_mm[i] != truth.depth.depth_mm[i];
  }
  if (truth.depth.width != recorded.width || truth.depth.height != recorded.height || differing > kCodecTailPixels) {
    throw Error(options.recording + " is not a recording of the synthetic scene (virtual://synthetic, seed " +
                std::to_string(options.seed) + "): frame " + std::to_string(frame.index) +
                " differs from it; truth exists only for such recordings");
  }
  return truth;
}

int run_truth(const TruthOptions& options, std::stop_token stop) {
  const auto source = open_recording(options.recording);
  const synthetic::TabletopScene scene(synthetic::Camera{}, options.seed);
  std::uint64_t frames = 0;
  while (std::optional<Frame> frame = source->next(stop)) {
    const synthetic::SyntheticFrame truth = matching_truth(scene, *frame, options);
    Labels labels = truth.labels;
    for (std::size_t i = 0; i < labels.size(); ++i) {
      if (frame->depth->depth_mm[i] == 0) labels[i] = synthetic::kNoReturnLabel;
    }
    if (frames == 0) create_output_folder(options.directory);  // only once the recording is known to match
    const std::filesystem::path path = std::filesystem::path(options.directory) / (frame_output_stem(*frame) + ".pcd");
    write_labelled_pcd(path, back_project(*frame->depth), labels, PcdEncoding::binary_compressed);
    ++frames;
  }
  std::printf("wrote the ground truth of %llu frames to %s\n", static_cast<unsigned long long>(frames),
              options.directory.c_str());
  return stop.stop_requested() ? kExitInterrupted : kExitDone;
}

}  // namespace

Subcommand add_truth_command(CLI::App& cli) {
  auto options = std::make_shared<TruthOptions>();
  CLI::App* command = cli.add_subcommand(
      "truth", "regenerate the ground truth of a recording of the virtual sensor's synthetic scene (for lccp eval)");
  command->add_option("recording", options->recording, "an .oni made with lccp record --uri virtual://synthetic")
      ->required();
  command->add_option("-o,--output-dir", options->directory,
                      "folder for one labelled .pcd per frame (0 no return, 1 table, 2 floor and wall, object n's "
                      "parts n*10+k: the mug's body 50, its handle 51)")
      ->required();
  command->add_option("--seed", options->seed, "the scene's seed (the URI's seed=, default 1)")->capture_default_str();
  return {command, [options](std::stop_token stop) { return run_truth(*options, stop); }};
}

}  // namespace lccp::app
