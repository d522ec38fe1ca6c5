// lccp segment IN -o OUT.pcd|OUT.ply [--png OUT.png]: one cloud in, labelled cloud out;
// lccp segment IN... -o DIR: every cloud of the files and folders, one output each.
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "lccp/capture/cloud_files.hpp"
#include "lccp/objects/scene.hpp"
#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/io/segments_json.hpp"
#include "stream_run.hpp"

namespace lccp::app {
namespace {

namespace fs = std::filesystem;

struct SegmentOptions {
  std::vector<std::string> inputs;
  std::string png;
  std::string segments;  // one input: per-segment geometry (JSON)
  StreamOptions stream;  // -o, --save, --overlay, --pcd-data, --config, --set, --inflight, --quiet
};

void print_summary(const PointCloud& cloud, const SceneSegmentation& r) {
  std::size_t finite = 0;
  for (const auto& p : cloud.points) finite += is_finite(p);
  std::string times;
  for (const StageInfo& info : kStages) {
    char time[32];
    std::snprintf(time, sizeof time, " %.1f", r.times[info.stage]);
    times += " " + std::string(info.name) + time;
  }
  const std::string parts = r.objects.empty() ? "" : ", parts " + std::to_string(r.segment_count);
  std::printf("points %zu (finite %zu), voxels %u, supervoxels %u, %s %u%s | ms:%s total %.1f\n", cloud.size(),
              finite, r.voxel_count, r.supervoxel_count, r.objects.empty() ? "segments" : "objects", r.object_count,
              parts.c_str(), times.c_str(), r.times.total_ms());
}

// -o or --png naming the input (or the same file by another path) would destroy it.
void refuse_overwriting_input(const std::string& input, const std::vector<std::string>& outputs) {
  for (const std::string& output : outputs) {
    std::error_code error;
    if (!output.empty() && fs::equivalent(input, output, error)) {
      throw Error(output + ": is the input file; choose another output name");
    }
  }
}

// One input file, one output file: its extension picks PCD or PLY.
int segment_one(const SegmentOptions& options, std::stop_token stop) {
  const std::string& input = options.inputs.front();
  const std::string& output = options.stream.outputs.directory;
  if (options.stream.outputs.save_option->count() > 0) {
    throw UsageError("--save is for several inputs; for one, -o's extension picks the format and --png adds the image");
  }
  if (!options.png.empty() && fs::path(options.png).extension() != ".png" && !written_in_place(options.png)) {
    throw UsageError("--png " + options.png + ": the image is written as PNG, so its name must end in .png");
  }
  const SceneSegmenter segmenter(options.stream.config.resolve());
  refuse_overwriting_input(input, {output, options.png, options.segments});
  const FrameOutputOptions& out = options.stream.outputs;
  const PointCloud cloud = read_cloud(input).cloud;
  if (!options.png.empty() && !cloud.organized()) throw Error(input + ": --png needs an organized (image-shaped) cloud");
  const SceneSegmentation result = segmenter.segment(cloud);
  if (stop.stop_requested()) return kExitInterrupted;  // interrupted: nothing written
  write_files_together(frame_files(cloud, result, 0, 0, {options.png, options.segments, {output}}, out));
  print_summary(cloud, result);
  return kExitDone;
}

// Several inputs or a folder: the clouds stream through the pipeline into the folder -o names.
int segment_many(const SegmentOptions& options, std::stop_token stop) {
  if (!options.png.empty()) throw UsageError("--png names one image: with several inputs use --save pcd,png");
  if (!options.segments.empty()) {
    throw UsageError("--segments names one file: with several inputs use --save pcd,segments");
  }
  const fs::path folder(options.stream.outputs.directory);
  if (folder.extension() == ".pcd" || folder.extension() == ".ply") {
    throw UsageError("-o " + folder.string() + ": with several inputs or a folder, -o must name a folder (each input "
                     "gets <stem>.pcd in it), not a " + folder.extension().string() + " file");
  }
  options.stream.outputs.check();
  const auto source = limit_source(open_cloud_files(std::vector<fs::path>(options.inputs.begin(), options.inputs.end())),
                                   options.stream.limits.limits());
  return run_stream(*source, options.stream, "segment", stop);
}

bool is_single(const SegmentOptions& options) {
  std::error_code error;
  const fs::path output(options.stream.outputs.directory);
  return options.inputs.size() == 1 && !fs::is_directory(options.inputs.front(), error) && output.has_extension() &&
         !fs::is_directory(output, error);
}

}  // namespace

Subcommand add_segment_command(CLI::App& cli) {
  auto options = std::make_shared<SegmentOptions>();
  CLI::App* command = cli.add_subcommand(
      "segment", "segment point clouds (.pcd, .ply) into objects and parts: one file to one file, or many into a folder");
  command->add_option("inputs", options->inputs, "input clouds, or folders of them")->required();
  options->stream.add_to(*command);
  command->get_option("-o")->description(
      "OUT.pcd or OUT.ply for one input (a uint32 label per point), else a folder (created if missing)");
  command->get_option("-o")->required();
  command->get_option("--save")->description(save_help({"pcd"}) + "; several inputs only");
  options->stream.outputs.save = {"pcd"};
  command->add_option("--png", options->png, "one input: also write a colour image of the labels (organized clouds)");
  command->add_option("--segments", options->segments,
                      "one input: also write the objects' and parts' geometry as JSON (schema: README)");
  return {command, [options](std::stop_token stop) {
            return is_single(*options) ? segment_one(*options, stop) : segment_many(*options, stop);
          }};
}

}  // namespace lccp::app
