// lccp eval PRED.pcd GT.pcd: the paper's Appendix B scores of a labelled cloud.
#include <charconv>
#include <cstdio>

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

int run_eval(const EvalOptions& options) {
  const std::optional<LabelRange> ignored = parse_range(options.ignore);
  LabelledCloud predicted = read_cloud(options.predicted);
  LabelledCloud truth = read_cloud(options.ground_truth);
  const Labels predicted_labels = labels_of(predicted, options.predicted);
  const Labels truth_labels = labels_of(truth, options.ground_truth);
  if (predicted.cloud.size() != truth.cloud.size()) {
    throw Error(options.predicted + " has " + std::to_string(predicted.cloud.size()) + " points but " +
                options.ground_truth + " has " + std::to_string(truth.cloud.size()));
  }
  print_scores(score_segmentation(predicted_labels, truth_labels, truth.cloud.points, ignored), options.json);
  return 0;
}

}  // namespace

Subcommand add_eval_command(CLI::App& cli) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* command = cli.add_subcommand("eval", "score a labelled cloud against ground truth (paper Appendix B)");
  command->add_option("predicted", options->predicted, "labelled cloud from lccp segment")->required();
  command->add_option("ground_truth", options->ground_truth, "cloud whose label field is the ground truth")
      ->required();
  command->add_option("--ignore", options->ignore, "ground-truth labels to leave out, e.g. 0-9 (mOSD's table)");
  command->add_flag("--json", options->json, "print the scores as one JSON object");
  return {command, [options] { return run_eval(*options); }};
}

}  // namespace lccp::app
