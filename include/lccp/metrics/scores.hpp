#pragma once
// Segmentation scores of the paper's Appendix B, plus the adjusted Rand index.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "lccp/cloud.hpp"

namespace lccp {

// Inclusive range of ground-truth labels to leave out of the scores (e.g. 0-9, the table in mOSD).
struct LabelRange {
  std::uint32_t first = 0;
  std::uint32_t last = 0;
  bool contains(std::uint32_t label) const { return label >= first && label <= last; }
};

struct SegmentationScores {
  double weighted_overlap = 0;    // WOv, eq. (6)
  double true_positive = 0;       // tp, eq. (7)
  double false_positive = 0;      // fp, eq. (7)
  double false_negative = 0;      // fn, eq. (7)
  double over_segmentation = 0;   // F_os, eq. (8)
  double under_segmentation = 0;  // F_us, eq. (8)
  double adjusted_rand_index = 0; // over the scored points
  std::uint32_t ground_truth_regions = 0;  // N_G
  std::uint64_t scored_points = 0;
};

// Scores `predicted` against `ground_truth` over the finite points of `points`
// only. Ground-truth regions G_i are the non-ignored GT labels; S_i is the
// predicted segment with the largest intersection with G_i (its size counts all
// finite points, ignored ones included). Throws lccp::Error if the sizes differ
// or no ground-truth region is left.
SegmentationScores score_segmentation(const Labels& predicted, const Labels& ground_truth,
                                      const std::vector<Eigen::Vector3f>& points,
                                      std::optional<LabelRange> ignored = std::nullopt);

}  // namespace lccp
