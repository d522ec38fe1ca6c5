// lccp eval PRED GT: the paper's Appendix B scores of a labelled cloud, or the
// mean over the frames of two folders (files paired by name), against the
// ground truth's regions or (--object-level) its objects, and the objects lost
// into the support. At object level a prediction with an `object` field (a
// two-level result: robot, paper-robot) is scored by its objects.
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <set>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "run_report.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/metrics/scores.hpp"

namespace lccp::app {
namespace {

struct EvalOptions {
  std::string predicted;
  std::string ground_truth;
  std::string ignore;
  std::string support = "1-9";
  bool object_level = false;
  bool json = false;
};

// What scoring one pair of clouds takes besides the clouds.
struct Scoring {
  std::optional<LabelRange> ignored;
  LabelRange support = kSupportLabels;
  bool object_level = false;
};

std::uint32_t parse_label(const std::string& text, const std::string& option) {
  std::uint32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size() || text.empty()) {
    throw Error(option + " expects a label or a range like 0-9, got '" + text + "'");
  }
  return value;
}

std::optional<LabelRange> parse_range(const std::string& text, const std::string& option) {
  if (text.empty()) return std::nullopt;
  const auto dash = text.find('-');
  if (dash == std::string::npos) return LabelRange{parse_label(text, option), parse_label(text, option)};
  LabelRange range{parse_label(text.substr(0, dash), option), parse_label(text.substr(dash + 1), option)};
  if (range.first > range.last) throw Error(option + " range '" + text + "' is empty");
  return range;
}

Scoring scoring_of(const EvalOptions& options) {
  Scoring scoring;
  scoring.ignored = parse_range(options.ignore, "--ignore");
  const std::optional<LabelRange> support = parse_range(options.support, "--support");
  if (!support || support->first == 0) {
    throw Error("--support must name labels from 1 up (0 is no data), got '" + options.support + "'");
  }
  scoring.support = *support;
  scoring.object_level = options.object_level;
  return scoring;
}

Labels labels_of(LabelledCloud& cloud, const std::string& path) {
  if (!cloud.labels) throw Error(path + ": no label field");
  return std::move(*cloud.labels);
}

// "40, 50".
std::string label_list(const std::vector<std::uint32_t>& labels) {
  std::string text;
  for (std::size_t i = 0; i < labels.size(); ++i) text += (i ? ", " : "") + std::to_string(labels[i]);
  return text;
}

// The regions lost into the support, their number and labels: "objects lost
// into the support: 2 (40, 50)".
std::string lost_text(const SegmentationScores& s) {
  std::string text = "objects lost into the support: " + std::to_string(s.objects_lost);
  return s.lost_labels.empty() ? text : text + " (" + label_list(s.lost_labels) + ")";
}

// The scores as a JSON object; the caller adds what was lost (per cloud or per frame).
Json scores_json(const SegmentationScores& s, bool object_level) {
  return {{"wov", s.weighted_overlap},
          {"tp", s.true_positive},
          {"fp", s.false_positive},
          {"fn", s.false_negative},
          {"fos", s.over_segmentation},
          {"fus", s.under_segmentation},
          {"ari", s.adjusted_rand_index},
          {"ground_truth_regions", s.ground_truth_regions},
          {"scored_points", s.scored_points},
          {"object_level", object_level},
          {"objects_lost", s.objects_lost}};
}

void print_scores(const SegmentationScores& s, bool json, bool object_level) {
  if (json) {
    Json document = scores_json(s, object_level);
    document["lost_labels"] = s.lost_labels;
    std::fputs(json_line(document).c_str(), stdout);
    return;
  }
  std::printf("WOv %.4f  tp %.4f  fp %.4f  fn %.4f  Fos %.4f  Fus %.4f  ARI %.4f  (%u regions, %llu points)\n",
              s.weighted_overlap, s.true_positive, s.false_positive, s.false_negative, s.over_segmentation,
              s.under_segmentation, s.adjusted_rand_index, s.ground_truth_regions,
              static_cast<unsigned long long>(s.scored_points));
  std::printf("%s\n", lost_text(s).c_str());
}

SegmentationScores score_files(const std::string& predicted_path, const std::string& truth_path,
                               const Scoring& scoring) {
  LabelledCloud predicted = read_cloud(predicted_path);
  LabelledCloud truth = read_cloud(truth_path);
  // At object level a two-level result is scored by its objects (its `object` field).
  const Labels predicted_labels = scoring.object_level && predicted.objects ? std::move(*predicted.objects)
                                                                            : labels_of(predicted, predicted_path);
  const Labels truth_labels = labels_of(truth, truth_path);
  if (predicted.cloud.size() != truth.cloud.size()) {
    throw Error(predicted_path + " has " + std::to_string(predicted.cloud.size()) + " points but " + truth_path +
                " has " + std::to_string(truth.cloud.size()));
  }
  const auto score = scoring.object_level ? score_objects : score_segmentation;
  return score(predicted_labels, truth_labels, truth.cloud.points, scoring.ignored, scoring.support);
}

// The .pcd files of a folder, by name.
std::set<std::string> pcd_names(const std::filesystem::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".pcd") names.insert(entry.path().filename().string());
  }
  return names;
}

// The frames of a folder that lost objects into the support, with their labels.
using LostByFrame = std::vector<std::pair<std::string, std::vector<std::uint32_t>>>;

// Every score averaged over the frames of the predicted folder (objects_lost
// summed); each needs its namesake in the ground-truth folder.
SegmentationScores mean_scores(const std::filesystem::path& predicted, const std::filesystem::path& truth,
                               const Scoring& scoring, std::size_t& frames, LostByFrame& lost) {
  const std::set<std::string> names = pcd_names(predicted);
  if (names.empty()) throw Error("folder " + predicted.string() + " holds no .pcd file");
  const std::set<std::string> truths = pcd_names(truth);
  SegmentationScores mean;
  for (const std::string& name : names) {
    if (!truths.count(name)) throw Error("no ground truth " + (truth / name).string() + " for " + (predicted / name).string());
    const SegmentationScores s = score_files((predicted / name).string(), (truth / name).string(), scoring);
    if (s.objects_lost > 0) lost.emplace_back(name, s.lost_labels);
    mean.objects_lost += s.objects_lost;
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

// Folders: text names each frame that lost objects ("NAME: objects lost into
// the support: 1 (50)"), then the mean and the total over the frames; JSON has
// the total and "lost_frames": {"NAME": [50], ...}.
void print_mean(const SegmentationScores& mean, std::size_t frames, const LostByFrame& lost, bool json,
                bool object_level) {
  if (json) {
    Json document = scores_json(mean, object_level);
    document["frames"] = frames;
    Json& lost_frames = document["lost_frames"] = Json::object();
    for (const auto& [name, labels] : lost) lost_frames[name] = labels;
    std::fputs(json_line(document).c_str(), stdout);
    return;
  }
  for (const auto& [name, labels] : lost) {
    SegmentationScores frame;
    frame.objects_lost = static_cast<std::uint32_t>(labels.size());
    frame.lost_labels = labels;
    std::printf("%s: %s\n", name.c_str(), lost_text(frame).c_str());
  }
  std::printf("mean over %zu frames: ", frames);
  SegmentationScores total = mean;
  total.lost_labels.clear();  // they are per frame, above
  print_scores(total, false, object_level);
}

int run_eval(const EvalOptions& options) {
  const Scoring scoring = scoring_of(options);
  const bool folders = std::filesystem::is_directory(options.predicted);
  if (folders != std::filesystem::is_directory(options.ground_truth)) {
    throw Error("give two labelled clouds or two folders of them, not one of each");
  }
  if (!folders) {
    print_scores(score_files(options.predicted, options.ground_truth, scoring), options.json, options.object_level);
    return 0;
  }
  std::size_t frames = 0;
  LostByFrame lost;
  const SegmentationScores mean = mean_scores(options.predicted, options.ground_truth, scoring, frames, lost);
  print_mean(mean, frames, lost, options.json, options.object_level);
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
  command->add_flag("--object-level", options->object_level,
                    "score objects: ground-truth parts n*10+k merged per object n, the support labels as one region; "
                    "a prediction with an object field (a two-level result) is scored by it");
  command->add_option("--support", options->support,
                      "ground-truth labels of the support (table), for objects lost into it and --object-level")
      ->capture_default_str();
  command->add_flag("--json", options->json, "print the scores as one JSON object");
  return {command, [options](std::stop_token) { return run_eval(*options); }};
}

}  // namespace lccp::app
