#pragma once
// Segmentation scores of the paper's Appendix B, plus the adjusted Rand index,
// at the level of the ground truth's regions or of its objects, and the objects
// a segmentation lost into the table.
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

// Ground-truth labels in the OSD / mOSD convention (Richtsfeld et al. 2012):
// 0 invalid or no data, 1-9 the support (table; our synthetic scene's floor and
// wall too), and object n's parts n * 10 + k (mOSD: 50 and 51 two parts of one
// object), so label / 10 is the object.
inline constexpr LabelRange kSupportLabels{1, 9};
inline constexpr std::uint32_t kLabelsPerObject = 10;

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
  // Regions lost into the support: G_i whose S_i holds more support points
  // (finite, ground truth in the support range, never label 0) than points of
  // G_i. Their ground-truth labels, ascending; objects_lost is their number.
  std::uint32_t objects_lost = 0;
  std::vector<std::uint32_t> lost_labels;
};

// Scores `predicted` against `ground_truth` over the finite points of `points`
// only. Ground-truth regions G_i are the non-ignored GT labels; S_i is the
// predicted segment with the largest intersection with G_i (its size counts all
// finite points, ignored ones included). A region whose label is in `support`
// is never counted lost. Throws lccp::Error if the sizes differ or no
// ground-truth region is left.
SegmentationScores score_segmentation(const Labels& predicted, const Labels& ground_truth,
                                      const std::vector<Eigen::Vector3f>& points,
                                      std::optional<LabelRange> ignored = std::nullopt,
                                      LabelRange support = kSupportLabels);

// The ground truth at object level: every label in `support` becomes
// support.first (one region), every other label >= 10 becomes label / 10 * 10
// (an object's parts n * 10 + k one region, n * 10), and the rest (0) stays.
Labels merge_object_parts(const Labels& ground_truth, LabelRange support = kSupportLabels);

// score_segmentation against merge_object_parts(ground_truth, support): the
// paper counts a handle split off its object as over-segmentation "according
// to the full-object ground truth labeling" (Sec. III.B); this is that score.
// `ignored` applies to the merged labels (0-9 still leaves out the support).
SegmentationScores score_objects(const Labels& predicted, const Labels& ground_truth,
                                 const std::vector<Eigen::Vector3f>& points,
                                 std::optional<LabelRange> ignored = std::nullopt,
                                 LabelRange support = kSupportLabels);

}  // namespace lccp
