// Segmentation scores of the paper's Appendix B (eqs. 6-8) and the adjusted Rand index,
// at region or object level, and the regions lost into the support.
#include "lccp/metrics/scores.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "lccp/error.hpp"

namespace lccp {
namespace {

// Sparse label ids mapped to dense indices 0..n-1 (order of first appearance),
// with the number of points counted under each. Labels come in long runs in
// organized clouds, so the last look-up is remembered.
struct DenseCounts {
  std::unordered_map<std::uint32_t, std::uint32_t> index;
  std::vector<std::uint32_t> labels;  // dense index -> label id
  std::vector<std::uint64_t> sizes;   // dense index -> point count
  std::uint32_t last_label = 0;
  std::uint32_t last_index = 0;

  std::uint32_t add(std::uint32_t label) {
    if (labels.empty() || label != last_label) {
      const auto [it, inserted] = index.try_emplace(label, static_cast<std::uint32_t>(labels.size()));
      if (inserted) {
        labels.push_back(label);
        sizes.push_back(0);
      }
      last_label = label;
      last_index = it->second;
    }
    ++sizes[last_index];
    return last_index;
  }
};

struct Cell {
  std::uint32_t region;   // dense ground-truth index i
  std::uint32_t segment;  // dense predicted index j
  std::uint64_t count;    // |G_i ∩ S_j| > 0
};

struct Contingency {
  DenseCounts regions;   // G_i: finite, non-ignored points per GT label
  DenseCounts segments;  // S_j: all finite points per predicted label (ignored ones included)
  std::vector<std::uint64_t> support_points;  // per S_j: its finite points with support GT (not 0)
  std::vector<Cell> cells;
  std::uint64_t finite_points = 0;
};

// The best segments of one ground-truth region.
struct RegionMatch {
  double best_iou = 0;          // OV_i
  std::uint64_t largest = 0;    // |TP_i| = |G_i ∩ S_i|
  std::uint32_t segment = 0;    // dense index of S_i
};

void check_support(LabelRange support) {
  if (support.first == 0 || support.first > support.last) {
    throw Error("support label range " + std::to_string(support.first) + "-" + std::to_string(support.last) +
                " must be non-empty and leave out 0 (no data)");
  }
}

void check_sizes(const Labels& predicted, const Labels& ground_truth,
                 const std::vector<Eigen::Vector3f>& points) {
  if (predicted.size() == points.size() && ground_truth.size() == points.size()) return;
  throw Error("score_segmentation: sizes differ: " + std::to_string(predicted.size()) +
              " predicted labels, " + std::to_string(ground_truth.size()) +
              " ground-truth labels, " + std::to_string(points.size()) + " points");
}

// Counts |G_i ∩ S_j| per cell, adding runs of consecutive points of one cell at once.
class CellCounter {
 public:
  void add(std::uint32_t region, std::uint32_t segment) {
    const std::uint64_t key = (static_cast<std::uint64_t>(region) << 32) | segment;
    if (key != run_key_) flush();
    run_key_ = key;
    ++run_length_;
  }

  std::vector<Cell> cells() {
    flush();
    std::vector<Cell> cells;
    cells.reserve(counts_.size());
    for (const auto& [key, count] : counts_) {
      cells.push_back({static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key), count});
    }
    return cells;
  }

 private:
  void flush() {
    if (run_length_ > 0) counts_[run_key_] += run_length_;
    run_length_ = 0;
  }

  std::unordered_map<std::uint64_t, std::uint64_t> counts_;
  std::uint64_t run_key_ = 0;
  std::uint64_t run_length_ = 0;
};

// One pass over the points: O(points) work, O(cells) memory.
Contingency tabulate(const Labels& predicted, const Labels& ground_truth,
                     const std::vector<Eigen::Vector3f>& points,
                     const std::optional<LabelRange>& ignored, LabelRange support) {
  Contingency table;
  CellCounter counter;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!is_finite(points[k])) continue;
    ++table.finite_points;
    const std::uint32_t segment = table.segments.add(predicted[k]);
    if (segment == table.support_points.size()) table.support_points.push_back(0);
    table.support_points[segment] += support.contains(ground_truth[k]);  // support.first >= 1: never 0
    if (ignored && ignored->contains(ground_truth[k])) continue;
    counter.add(table.regions.add(ground_truth[k]), segment);
  }
  table.cells = counter.cells();
  return table;
}

// Per region: the maximum IoU over all segments (eq. 6) and the segment with the
// largest intersection, ties going to the smaller label id (S_i of eq. 7).
std::vector<RegionMatch> match_regions(const Contingency& table) {
  std::vector<RegionMatch> matches(table.regions.labels.size());
  for (const Cell& cell : table.cells) {
    RegionMatch& match = matches[cell.region];
    const std::uint64_t union_size =
        table.regions.sizes[cell.region] + table.segments.sizes[cell.segment] - cell.count;
    match.best_iou = std::max(match.best_iou, double(cell.count) / double(union_size));
    const bool tie_to_smaller = cell.count == match.largest &&
        table.segments.labels[cell.segment] < table.segments.labels[match.segment];
    if (cell.count > match.largest || tie_to_smaller) {
      match.largest = cell.count;
      match.segment = cell.segment;
    }
  }
  return matches;
}

void add_paper_scores(const Contingency& table, const std::vector<RegionMatch>& matches,
                      SegmentationScores& scores) {
  double weighted_overlap = 0, tp = 0, fp = 0, fn = 0;
  std::uint64_t n_all = 0, n_true = 0, n_false = 0;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const double g = double(table.regions.sizes[i]);                  // |G_i|
    const std::uint64_t s = table.segments.sizes[matches[i].segment];  // |S_i|
    const std::uint64_t true_pos = matches[i].largest;                 // |TP_i|
    weighted_overlap += g * matches[i].best_iou;                       // eq. (6) numerator
    tp += double(true_pos) / g;                                        // eq. (7) |TP_i|/|G_i|
    fp += double(s - true_pos) / double(s);                            // eq. (7) |FP_i|/|S_i|
    fn += (g - double(true_pos)) / g;                                  // eq. (7) |FN_i|/|G_i|
    n_all += table.regions.sizes[i];
    n_true += true_pos;
    n_false += s - true_pos;
  }
  const double n_g = double(matches.size());
  scores.weighted_overlap = weighted_overlap / double(n_all);  // eq. (6)
  scores.true_positive = tp / n_g;                              // eq. (7), mean over N_G
  scores.false_positive = fp / n_g;
  scores.false_negative = fn / n_g;
  // Eq. (8), read with the sets of eq. (7): N_true = sum_i |TP_i|, N_false =
  // sum_i |FP_i| (a segment matched by several regions counts once per region),
  // N_all = sum_i |G_i|. So F_os = 1 - N_true/N_all, F_us = N_false/N_all.
  scores.over_segmentation = 1.0 - double(n_true) / double(n_all);
  scores.under_segmentation = double(n_false) / double(n_all);
}

// A region is lost into the support when its best segment S_i (largest
// intersection, as in eq. 7) holds more support points than points of G_i: the
// object was merged into the table, what the paper's robot application removes
// the ground plane first against (Sec. III.C: object-to-table and handle-to-body
// transitions look alike). Support regions themselves are never lost.
void add_lost_regions(const Contingency& table, const std::vector<RegionMatch>& matches, LabelRange support,
                      SegmentationScores& scores) {
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const std::uint32_t label = table.regions.labels[i];
    if (support.contains(label)) continue;
    if (table.support_points[matches[i].segment] > matches[i].largest) scores.lost_labels.push_back(label);
  }
  std::sort(scores.lost_labels.begin(), scores.lost_labels.end());
  scores.objects_lost = static_cast<std::uint32_t>(scores.lost_labels.size());
}

std::uint64_t pairs(std::uint64_t n) { return n * (n - 1) / 2; }  // n choose 2, 0 for n = 0

// Hubert & Arabie's ARI over the non-ignored finite points: rows are the G_i,
// columns the predicted labels restricted to those points (not |S_j|).
double adjusted_rand_index(const Contingency& table) {
  std::vector<std::uint64_t> column(table.segments.labels.size(), 0);
  std::uint64_t n = 0, index = 0, rows = 0, columns = 0;
  for (const Cell& cell : table.cells) {
    column[cell.segment] += cell.count;
    n += cell.count;
    index += pairs(cell.count);
  }
  for (const std::uint64_t size : table.regions.sizes) rows += pairs(size);
  for (const std::uint64_t size : column) columns += pairs(size);
  const std::uint64_t total = pairs(n);
  // max - expected = 0 only when both partitions are one cluster or both all
  // singletons (or n < 2): the partitions are then identical.
  const bool degenerate = (rows == total && columns == total) || (rows == 0 && columns == 0);
  if (degenerate) return 1.0;
  const long double expected = static_cast<long double>(rows) * columns / total;
  const long double maximum = (static_cast<long double>(rows) + columns) / 2;
  return static_cast<double>((index - expected) / (maximum - expected));
}

}  // namespace

SegmentationScores score_segmentation(const Labels& predicted, const Labels& ground_truth,
                                      const std::vector<Eigen::Vector3f>& points,
                                      std::optional<LabelRange> ignored, LabelRange support) {
  check_sizes(predicted, ground_truth, points);
  check_support(support);
  const Contingency table = tabulate(predicted, ground_truth, points, ignored, support);
  if (table.regions.labels.empty()) {
    throw Error("no ground-truth region to score (all points ignored or non-finite)");
  }
  SegmentationScores scores;
  const std::vector<RegionMatch> matches = match_regions(table);
  add_paper_scores(table, matches, scores);
  add_lost_regions(table, matches, support, scores);
  scores.adjusted_rand_index = adjusted_rand_index(table);
  scores.ground_truth_regions = static_cast<std::uint32_t>(table.regions.labels.size());
  scores.scored_points = table.finite_points;
  return scores;
}

// OSD / mOSD label an object's parts n * 10 + k (README.md, Data: 20-29
// object 1, 30-39 object 2); label / 10 is the object.
Labels merge_object_parts(const Labels& ground_truth, LabelRange support) {
  check_support(support);
  Labels merged(ground_truth);
  for (std::uint32_t& label : merged) {
    if (support.contains(label)) {
      label = support.first;
    } else if (label >= kLabelsPerObject) {
      label = label / kLabelsPerObject * kLabelsPerObject;
    }
  }
  return merged;
}

SegmentationScores score_objects(const Labels& predicted, const Labels& ground_truth,
                                 const std::vector<Eigen::Vector3f>& points, std::optional<LabelRange> ignored,
                                 LabelRange support) {
  check_sizes(predicted, ground_truth, points);
  return score_segmentation(predicted, merge_object_parts(ground_truth, support), points, ignored, support);
}

}  // namespace lccp
