// lccp eval PRED GT: the paper's Appendix B scores of a labelled cloud, or the
// mean over the frames of two folders (files paired by name).
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <set>

#include "commands.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/metrics/scores.hpp"

namespace lccp::app {
namespace {

struct EvalOptions {
  std::string predicted;
  std::string ground_truth;
  std::string ignore;
  bool json = false;
};

std::uint32_t parse_label(const std::string& text) {
  std::uint32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size() || text.empty()) {
    throw Error("--ignore expects a label or a range like 0-9, got '" + text + "'");
  }
  return value;
}

std::optional<LabelRange> parse_range(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const auto dash = text.find('-');
  if (dash == std::string::npos) return LabelRange{parse_label(text), parse_label(text)};
  LabelRange range{parse_label(text.substr(0, dash)), parse_label(text.substr(dash + 1))};
  if (range.first > range.last) throw Error("--ignore range '" + text + "' is empty");
  return range;
}

Labels labels_of(LabelledCloud& cloud, const std::string& path) {
  if (!cloud.labels) throw Error(path + ": no label field");
  return std::move(*cloud.labels);
}

void print_scores(const SegmentationScores& s, bool json) {
  if (json) {
    std::printf(
        "{\"wov\": %.6f, \"tp\": %.6f, \"fp\": %.6f, \"fn\": %.6f, \"fos\": %.6f, \"fus\": %.6f, \"ari\": %.6f, "
        "\"ground_truth_regions\": %u, \"scored_points\": %llu}\n",
        s.weighted_overlap, s.true_positive, s.false_positive, s.false_negative, s.over_segmentation,
        s.under_segmentation, s.adjusted_rand_index, s.ground_truth_regions,
        static_cast<unsigned long long>(s.scored_points));
    return;
  }
  std::printf("WOv %.4f  tp %.4f  fp %.4f  fn %.4f  Fos %.4f  Fus %.4f  ARI %.4f  (%u regions, %llu points)\n",
              s.weighted_overlap, s.true_positive, s.false_positive, s.false_negative, s.over_segmentation,
              s.under_segmentation, s.adjusted_rand_index, s.ground_truth_regions,
              static_cast<unsigned long long>(s.scored_points));
}

SegmentationScores score_files(const std::string& predicted_path, const std::string& truth_path,
                               std::optional<LabelRange> ignored) {
  LabelledCloud predicted = read_cloud(predicted_path);
  LabelledCloud truth = read_cloud(truth_path);
  const Labels predicted_labels = labels_of(predicted, predicted_path);
  const Labels truth_labels = labels_of(truth, truth_path);
  if (predicted.cloud.size() != truth.cloud.size()) {
    throw Error(predicted_path + " has " + std::to_string(predicted.cloud.size()) + " points but " + truth_path +
                " has " + std::to_string(truth.cloud.size()));
  }
  return score_segmentation(predicted_labels, truth_labels, truth.cloud.points, ignored);
}

// The .pcd files of a folder, by name.
std::set<std::string> pcd_names(const std::filesystem::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".pcd") names.insert(entry.path().filename().string());
  }
  return names;
}

// Every score averaged over the frames of the predicted folder; each needs its
// namesake in the ground-truth folder.
SegmentationScores mean_scores(const std::filesystem::path& predicted, const std::filesystem::path& truth,
                               std::optional<LabelRange> ignored, std::size_t& frames) {
  const std::set<std::string> names = pcd_names(predicted);
  if (names.empty()) throw Error("folder " + predicted.string() + " holds no .pcd file");
  const std::set<std::string> truths = pcd_names(truth);
  SegmentationScores mean;
  for (const std::string& name : names) {
    if (!truths.count(name)) throw Error("no ground truth " + (truth / name).string() + " for " + (predicted / name).string());
    const SegmentationScores s = score_files((predicted / name).string(), (truth / name).string(), ignored);
    mean.weighted_overlap += s.weighted_overlap;
    mean.true_positive += s.true_positive;
    mean.false_positive += s.false_positive;
    mean.false_negative += s.false_negative;
    mean.over_segmentation += s.over_segmentation;
    mean.under_segmentation += s.under_segmentation;
    mean.adjusted_rand_index += s.adjusted_rand_index;
    mean.ground_truth_regions += s.ground_truth_regions;
    mean.scored_points += s.scored_points;
  }
  frames = names.size();
  const double n = static_cast<double>(frames);
  for (double* score : {&mean.weighted_overlap, &mean.true_positive, &mean.false_positive, &mean.false_negative,
                        &mean.over_segmentation, &mean.under_segmentation, &mean.adjusted_rand_index}) {
    *score /= n;
  }
  return mean;
}

int run_eval(const EvalOptions& options) {
  const std::optional<LabelRange> ignored = parse_range(options.ignore);
  const bool folders = std::filesystem::is_directory(options.predicted);
  if (folders != std::filesystem::is_directory(options.ground_truth)) {
    throw Error("give two labelled clouds or two folders of them, not one of each");
  }
  if (!folders) {
    print_scores(score_files(options.predicted, options.ground_truth, ignored), options.json);
    return 0;
  }
  std::size_t frames = 0;
  const SegmentationScores mean = mean_scores(options.predicted, options.ground_truth, ignored, frames);
  if (!options.json) std::printf("mean over %zu frames: ", frames);
  print_scores(mean, options.json);
  return 0;
}

}  // namespace

Subcommand add_eval_command(CLI::App& cli) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* command = cli.add_subcommand("eval", "score a labelled cloud against ground truth (paper Appendix B)");
  command->add_option("predicted", options->predicted, "labelled cloud from lccp segment, or a folder of them")
      ->required();
  command->add_option("ground_truth", options->ground_truth,
                      "cloud whose label field is the ground truth, or a folder with one of the same name per frame")
      ->required();
  command->add_option("--ignore", options->ignore, "ground-truth labels to leave out, e.g. 0-9 (mOSD's table)");
  command->add_flag("--json", options->json, "print the scores as one JSON object");
  return {command, [options](std::stop_token) { return run_eval(*options); }};
}

}  // namespace lccp::app
