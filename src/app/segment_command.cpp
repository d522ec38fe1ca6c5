// lccp segment IN -o OUT.pcd [--png OUT.png]: one cloud in, labelled cloud out.
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"
#include "lccp/io/cloud_io.hpp"
#include "stop_signal.hpp"

namespace lccp::app {
namespace {

struct SegmentOptions {
  std::string input;
  std::string output;
  std::string png;
  ConfigOptions config;
};

void print_summary(const PointCloud& cloud, const SegmentationResult& r) {
  std::size_t finite = 0;
  for (const auto& p : cloud.points) finite += is_finite(p);
  const StageTimes& t = r.times;
  std::printf(
      "points %zu (finite %zu), voxels %u, supervoxels %u, segments %u | ms: voxelize %.1f normals %.1f seeds %.1f "
      "growth %.1f adjacency %.1f classify %.1f label %.1f filter %.1f total %.1f\n",
      cloud.size(), finite, r.voxel_count, r.supervoxel_count, r.segment_count, t.voxelize_ms, t.normals_ms,
      t.seeds_ms, t.growth_ms, t.adjacency_ms, t.classify_ms, t.label_ms, t.filter_ms, t.total_ms());
}

// The labelled cloud and, if asked, its label image, written together: both
// appear, or neither does.
void write_outputs(const SegmentOptions& options, const PointCloud& cloud, const Labels& labels) {
  std::vector<FileBytes> files{{options.output, encode_labelled_pcd(cloud, labels)}};
  if (!options.png.empty()) files.push_back({options.png, encode_label_png(cloud, labels)});
  write_files_together(files);
}

// -o or --png naming the input (or the same file by another path) would destroy it.
void refuse_overwriting_input(const SegmentOptions& options) {
  for (const std::string& output : {options.output, options.png}) {
    std::error_code error;
    if (!output.empty() && std::filesystem::equivalent(options.input, output, error)) {
      throw Error(output + ": is the input file; choose another output name");
    }
  }
}

int run_segment(const SegmentOptions& options) {
  const StopOnSignal stop;
  const LccpSegmenter segmenter(options.config.resolve());
  refuse_overwriting_input(options);
  const PointCloud cloud = read_cloud(options.input).cloud;
  if (!options.png.empty() && !cloud.organized()) {
    throw Error(options.input + ": --png needs an organized (image-shaped) cloud");
  }
  const SegmentationResult result = segmenter.segment(cloud);
  if (stop.requested()) return 130;  // interrupted: nothing written
  write_outputs(options, cloud, result.labels);
  print_summary(cloud, result);
  return 0;
}

}  // namespace

Subcommand add_segment_command(CLI::App& cli) {
  auto options = std::make_shared<SegmentOptions>();
  CLI::App* command = cli.add_subcommand("segment", "segment one point cloud (.pcd or .ply) into objects and parts");
  command->add_option("input", options->input, "input cloud")->required();
  command->add_option("-o,--output", options->output, "labelled cloud to write (.pcd with a uint32 label field)")
      ->required();
  command->add_option("--png", options->png, "also write a colour image of the labels (organized clouds)");
  options->config.add_to(*command);
  return {command, [options] { return run_segment(*options); }};
}

}  // namespace lccp::app
