// Hand-computed checks of the Appendix B scores (eqs. 6-8) and the adjusted Rand index.
#include "lccp/metrics/scores.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lccp/error.hpp"

namespace lccp {
namespace {

constexpr double kTol = 1e-12;

// n points on the x axis; those listed in `nan_at` have no data.
std::vector<Eigen::Vector3f> cloud(std::size_t n, std::vector<std::size_t> nan_at = {}) {
  std::vector<Eigen::Vector3f> points;
  for (std::size_t k = 0; k < n; ++k) points.emplace_back(float(k), 0.0f, 0.0f);
  for (const std::size_t k : nan_at) {
    points[k] = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  }
  return points;
}

void expect_perfect(const SegmentationScores& s) {
  EXPECT_NEAR(s.weighted_overlap, 1.0, kTol);
  EXPECT_NEAR(s.true_positive, 1.0, kTol);
  EXPECT_NEAR(s.false_positive, 0.0, kTol);
  EXPECT_NEAR(s.false_negative, 0.0, kTol);
  EXPECT_NEAR(s.over_segmentation, 0.0, kTol);
  EXPECT_NEAR(s.under_segmentation, 0.0, kTol);
  EXPECT_NEAR(s.adjusted_rand_index, 1.0, kTol);
}

TEST(ScoreSegmentation, PerfectSegmentationWithOtherIdsAndLabelZero) {
  // Same partition, different ids; predicted 0 is a segment like any other.
  const Labels gt = {1, 1, 1, 2, 2, 3};
  const Labels pred = {7, 7, 7, 0, 0, 4};
  const SegmentationScores s = score_segmentation(pred, gt, cloud(6));
  expect_perfect(s);
  EXPECT_EQ(s.ground_truth_regions, 3u);
  EXPECT_EQ(s.scored_points, 6u);
}

TEST(ScoreSegmentation, RegionSplitInTwoSegments) {
  // G_1 (6 points) split 4 / 2 into segments 10 / 11; G_2 (4 points) = segment 12.
  const Labels gt = {1, 1, 1, 1, 1, 1, 2, 2, 2, 2};
  const Labels pred = {10, 10, 10, 10, 11, 11, 12, 12, 12, 12};
  const SegmentationScores s = score_segmentation(pred, gt, cloud(10));
  // OV_1 = 4/6, OV_2 = 1: WOv = (6 * 4/6 + 4 * 1) / 10 = 0.8.
  EXPECT_NEAR(s.weighted_overlap, 0.8, kTol);
  // S_1 = 10: TP = 4, FP = 0, FN = 2; S_2 = 12: TP = 4, FP = FN = 0.
  EXPECT_NEAR(s.true_positive, (4.0 / 6 + 1.0) / 2, kTol);   // 5/6
  EXPECT_NEAR(s.false_positive, 0.0, kTol);
  EXPECT_NEAR(s.false_negative, (2.0 / 6 + 0.0) / 2, kTol);  // 1/6
  EXPECT_NEAR(s.over_segmentation, 1.0 - 8.0 / 10, kTol);    // 0.2
  EXPECT_NEAR(s.under_segmentation, 0.0, kTol);
  // Contingency [4 2 0; 0 0 4], n = 10, C(10,2) = 45: index = 6+1+6 = 13,
  // rows = 15+6 = 21, columns = 6+1+6 = 13, expected = 21*13/45 = 273/45,
  // max = 17: ARI = (13 - 273/45) / (17 - 273/45) = 312/492 = 26/41.
  EXPECT_NEAR(s.adjusted_rand_index, 26.0 / 41, kTol);
}

TEST(ScoreSegmentation, TwoRegionsMergedIntoOneSegment) {
  // G_1 (5) and G_2 (3) merged into segment 5 (8 points); G_3 (2) = segment 6.
  const Labels gt = {1, 1, 1, 1, 1, 2, 2, 2, 3, 3};
  const Labels pred = {5, 5, 5, 5, 5, 5, 5, 5, 6, 6};
  const SegmentationScores s = score_segmentation(pred, gt, cloud(10));
  // OV = 5/8, 3/8, 1: WOv = (5*5/8 + 3*3/8 + 2) / 10 = (50/8) / 10 = 0.625.
  EXPECT_NEAR(s.weighted_overlap, 0.625, kTol);
  EXPECT_NEAR(s.true_positive, 1.0, kTol);
  // FP_1 = 3 of |S| = 8, FP_2 = 5 of 8, FP_3 = 0: fp = (3/8 + 5/8 + 0) / 3 = 1/3.
  EXPECT_NEAR(s.false_positive, 1.0 / 3, kTol);
  EXPECT_NEAR(s.false_negative, 0.0, kTol);
  EXPECT_NEAR(s.over_segmentation, 0.0, kTol);
  // N_false = 3 + 5 + 0 = 8, N_all = 10.
  EXPECT_NEAR(s.under_segmentation, 0.8, kTol);
}

TEST(ScoreSegmentation, IgnoredTableCountsInSegmentSizeOnly) {
  // Table labels 1-9 (ignored 0-9): 4 points; object 20: 4 points; object 30: 2.
  const Labels gt = {1, 1, 2, 2, 20, 20, 20, 20, 30, 30};
  const LabelRange table{0, 9};
  // Two table points merged into the segment of object 20.
  const Labels merged = {1, 1, 2, 2, 1, 1, 1, 1, 3, 3};
  const SegmentationScores s = score_segmentation(merged, gt, cloud(10), table);
  EXPECT_EQ(s.ground_truth_regions, 2u);  // the table is no region
  EXPECT_EQ(s.scored_points, 10u);
  // Object 20: |S| = 6 (2 table points), IoU = 4/6, TP = 4, FP = 2; object 30 perfect.
  // WOv = (4 * 4/6 + 2 * 1) / 6 = 7/9.
  EXPECT_NEAR(s.weighted_overlap, 7.0 / 9, kTol);
  EXPECT_NEAR(s.true_positive, 1.0, kTol);
  EXPECT_NEAR(s.false_positive, (2.0 / 6 + 0.0) / 2, kTol);  // 1/6
  EXPECT_NEAR(s.false_negative, 0.0, kTol);
  EXPECT_NEAR(s.over_segmentation, 0.0, kTol);
  EXPECT_NEAR(s.under_segmentation, 2.0 / 6, kTol);
  // The ARI sees only the object points: identical partitions.
  EXPECT_NEAR(s.adjusted_rand_index, 1.0, kTol);

  // Table in its own segments, however badly split: objects are perfect.
  const Labels separate = {7, 8, 9, 0, 1, 1, 1, 1, 3, 3};
  expect_perfect(score_segmentation(separate, gt, cloud(10), table));
}

TEST(ScoreSegmentation, NonFinitePointsAreNotCounted) {
  // Points 4-6 are NaN: one carries GT 101 (mOSD test63), the others wrong labels.
  const Labels gt = {20, 20, 30, 30, 101, 20, 30};
  const Labels pred = {1, 1, 2, 2, 0, 2, 1};
  const SegmentationScores s = score_segmentation(pred, gt, cloud(7, {4, 5, 6}), LabelRange{0, 9});
  expect_perfect(s);
  EXPECT_EQ(s.ground_truth_regions, 2u);  // no region 101
  EXPECT_EQ(s.scored_points, 4u);
}

TEST(ScoreSegmentation, LargestIntersectionTieGoesToSmallerLabel) {
  // G_1 (4 points): 2 in segment 9 (seen first), 2 in segment 4; G_2 (3): 1 in 4, 2 in 7.
  const Labels gt = {1, 1, 1, 1, 2, 2, 2};
  const Labels pred = {9, 9, 4, 4, 4, 7, 7};
  const SegmentationScores s = score_segmentation(pred, gt, cloud(7));
  // S_1 = 4 (|S| = 3): TP = 2, FP = 1, FN = 2. S_2 = 7 (|S| = 2): TP = 2, FP = 0, FN = 1.
  EXPECT_NEAR(s.true_positive, (2.0 / 4 + 2.0 / 3) / 2, kTol);   // 7/12
  EXPECT_NEAR(s.false_positive, (1.0 / 3 + 0.0) / 2, kTol);      // 1/6
  EXPECT_NEAR(s.false_negative, (2.0 / 4 + 1.0 / 3) / 2, kTol);  // 5/12
  EXPECT_NEAR(s.over_segmentation, 1.0 - 4.0 / 7, kTol);         // 3/7
  EXPECT_NEAR(s.under_segmentation, 1.0 / 7, kTol);
  // WOv takes the max IoU over all segments, not S_i: OV_1 = max(2/4, 2/5) = 1/2,
  // OV_2 = max(2/3, 1/5) = 2/3: WOv = (4 * 1/2 + 3 * 2/3) / 7 = 4/7.
  EXPECT_NEAR(s.weighted_overlap, 4.0 / 7, kTol);
}

TEST(ScoreSegmentation, AdjustedRandIndexOfThreeByThreeTable) {
  // Contingency (rows G = 1,2,3; columns S = 5,6,7), n = 12:
  //   [3 1 0]   row sums 4 4 4, column sums 4 4 4
  //   [1 2 1]
  //   [0 1 3]
  // index = C(3,2)+C(2,2)+C(3,2) = 3+1+3 = 7; rows = columns = 3*C(4,2) = 18;
  // C(12,2) = 66; expected = 18*18/66 = 54/11; max = 18;
  // ARI = (7 - 54/11) / (18 - 54/11) = (77 - 54) / (198 - 54) = 23/144.
  // A point with ignored GT 0 (in segment 5) and a NaN point must not change it.
  const Labels gt = {1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 0, 2};
  const Labels pred = {5, 5, 5, 6, 5, 6, 6, 7, 6, 7, 7, 7, 5, 5};
  const SegmentationScores s =
      score_segmentation(pred, gt, cloud(14, {13}), LabelRange{0, 0});
  EXPECT_NEAR(s.adjusted_rand_index, 23.0 / 144, kTol);
  EXPECT_EQ(s.scored_points, 13u);
}

TEST(ScoreSegmentation, SingleClusterBothSidesIsPerfect) {
  const SegmentationScores s = score_segmentation({3, 3, 3}, {20, 20, 20}, cloud(3));
  expect_perfect(s);
}

TEST(ScoreSegmentation, SizeMismatchNamesBothSizes) {
  try {
    score_segmentation({1, 1, 1}, {1, 1, 1, 1}, cloud(4));
    FAIL() << "expected lccp::Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("3 predicted"), std::string::npos) << message;
    EXPECT_NE(message.find("4 ground-truth"), std::string::npos) << message;
  }
  EXPECT_THROW(score_segmentation({1, 1}, {1, 1}, cloud(3)), Error);
}

TEST(ScoreSegmentation, NothingLeftToScoreThrows) {
  const std::string expected = "no ground-truth region to score (all points ignored or non-finite)";
  try {
    score_segmentation({1, 2, 3}, {0, 5, 9}, cloud(3), LabelRange{0, 9});
    FAIL() << "expected lccp::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
  EXPECT_THROW(score_segmentation({1, 2}, {20, 30}, cloud(2, {0, 1})), Error);
  EXPECT_THROW(score_segmentation({}, {}, {}), Error);
}

// --- object level: ground-truth parts n * 10 + k merged per object n ------------------

TEST(MergeObjectParts, PartsBecomeTheirObjectAndTheSupportOneRegion) {
  const Labels gt = {0, 1, 2, 9, 10, 19, 20, 50, 51, 59, 101};
  EXPECT_EQ(merge_object_parts(gt), (Labels{0, 1, 1, 1, 10, 10, 20, 50, 50, 50, 100}));
  // Another support range: labels outside it below 10 stay as they are.
  EXPECT_EQ(merge_object_parts({0, 1, 2, 3, 51}, LabelRange{2, 3}), (Labels{0, 1, 2, 2, 50}));
  EXPECT_THROW(merge_object_parts({1}, LabelRange{0, 9}), Error);  // 0 is no data, never support
}

// A mug (body 50: 4 points, handle 51: 2) and a can (30: 2 points) on a table
// (1 and 2: 3 points), the table ignored. LCCP splits the handle off: perfect
// for the parts, over-segmentation for the objects (paper Sec. III.B).
TEST(ScoreObjects, HandleSplitOffIsPerfectForPartsAndOverSegmentationForObjects) {
  const Labels gt = {1, 1, 2, 50, 50, 50, 50, 51, 51, 30, 30};
  const Labels split = {1, 1, 1, 4, 4, 4, 4, 5, 5, 6, 6};
  const LabelRange table{0, 9};
  const SegmentationScores parts = score_segmentation(split, gt, cloud(11), table);
  expect_perfect(parts);
  EXPECT_EQ(parts.ground_truth_regions, 3u);

  const SegmentationScores objects = score_objects(split, gt, cloud(11), table);
  EXPECT_EQ(objects.ground_truth_regions, 2u);
  // The mug: 6 points, best segment 4 (IoU 4/6, TP 4, FN 2); the can perfect.
  // WOv = (6 * 4/6 + 2 * 1) / 8 = 3/4.
  EXPECT_NEAR(objects.weighted_overlap, 0.75, kTol);
  EXPECT_NEAR(objects.true_positive, (4.0 / 6 + 1.0) / 2, kTol);
  EXPECT_NEAR(objects.false_negative, (2.0 / 6) / 2, kTol);
  EXPECT_NEAR(objects.false_positive, 0.0, kTol);
  EXPECT_NEAR(objects.over_segmentation, 1.0 - 6.0 / 8, kTol);
  EXPECT_NEAR(objects.under_segmentation, 0.0, kTol);
  EXPECT_EQ(objects.scored_points, 11u);
}

TEST(ScoreObjects, OneSegmentPerObjectIsPerfectForObjectsOnly) {
  const Labels gt = {1, 1, 2, 50, 50, 50, 50, 51, 51, 30, 30};
  const Labels whole = {1, 1, 1, 4, 4, 4, 4, 4, 4, 6, 6};
  const LabelRange table{0, 9};
  expect_perfect(score_objects(whole, gt, cloud(11), table));
  // Parts: body and handle share segment 4 (6 points): OV = 4/6 and 2/6.
  // WOv = (4 * 4/6 + 2 * 2/6 + 2 * 1) / 8 = 2/3.
  EXPECT_NEAR(score_segmentation(whole, gt, cloud(11), table).weighted_overlap, 2.0 / 3, kTol);
}

TEST(ScoreObjects, SupportLabelsAreOneRegionWhenNotIgnored) {
  // Table 1 (3 points) and wall 2 (2 points) in segments of their own: two
  // perfect regions, or one region (1) split 3 / 2 at object level.
  const Labels gt = {1, 1, 1, 2, 2, 20, 20};
  const Labels pred = {7, 7, 7, 8, 8, 9, 9};
  EXPECT_EQ(score_segmentation(pred, gt, cloud(7)).ground_truth_regions, 3u);
  const SegmentationScores objects = score_objects(pred, gt, cloud(7));
  EXPECT_EQ(objects.ground_truth_regions, 2u);
  // Support: 5 points, OV 3/5; object 20 perfect: WOv = (5 * 3/5 + 2) / 7 = 5/7.
  EXPECT_NEAR(objects.weighted_overlap, 5.0 / 7, kTol);
  EXPECT_EQ(objects.objects_lost, 0u);  // the support is never lost into itself
}

// --- objects lost into the support ------------------------------------------------

TEST(ObjectsLost, RegionSwallowedByTheTableSegmentIsLost) {
  // Table (1): 6 points in segment 1 with all 3 of object 20; object 30 alone in
  // segment 2; object 40 (4 points) shares segment 3 with 3 table points (fewer
  // than its own: not lost).
  const Labels gt = {1, 1, 1, 1, 1, 1, 20, 20, 20, 30, 30, 40, 40, 40, 40, 1, 1, 1};
  const Labels pred = {1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 3, 3, 3, 3, 3, 3, 3};
  const SegmentationScores s = score_segmentation(pred, gt, cloud(18), LabelRange{0, 9});
  EXPECT_EQ(s.objects_lost, 1u);
  EXPECT_EQ(s.lost_labels, (std::vector<std::uint32_t>{20}));
  // The table not ignored: still only object 20 (the table region is never lost).
  EXPECT_EQ(score_segmentation(pred, gt, cloud(18)).lost_labels, (std::vector<std::uint32_t>{20}));
}

TEST(ObjectsLost, NoReturnAndNonFinitePointsAreNotSupport) {
  // Object 50 (2 points) shares segment 5 with 1 table point, 3 finite points
  // of label 0 and 2 NaN table points: 1 support point < 2, not lost.
  const Labels gt = {50, 50, 1, 0, 0, 0, 1, 1, 1, 1};
  const Labels pred = {5, 5, 5, 5, 5, 5, 5, 5, 6, 6};
  const SegmentationScores s = score_segmentation(pred, gt, cloud(10, {6, 7}), LabelRange{0, 9});
  EXPECT_EQ(s.objects_lost, 0u);
  EXPECT_TRUE(s.lost_labels.empty());
  // The two finite table points of segment 6 moved to segment 5: 3 > 2, lost.
  const Labels merged = {5, 5, 5, 5, 5, 5, 5, 5, 5, 5};
  EXPECT_EQ(score_segmentation(merged, gt, cloud(10, {6, 7}), LabelRange{0, 9}).objects_lost, 1u);
}

TEST(ObjectsLost, SupportRangeIsAParameter) {
  // Object 60 (2 points) in one segment with 3 wall points (label 2).
  const Labels gt = {60, 60, 2, 2, 2, 1, 1};
  const Labels pred = {4, 4, 4, 4, 4, 5, 5};
  EXPECT_EQ(score_segmentation(pred, gt, cloud(7), LabelRange{0, 9}).lost_labels, (std::vector<std::uint32_t>{60}));
  EXPECT_EQ(score_segmentation(pred, gt, cloud(7), LabelRange{0, 9}, LabelRange{1, 1}).objects_lost, 0u);
  EXPECT_THROW(score_segmentation(pred, gt, cloud(7), LabelRange{0, 9}, LabelRange{0, 9}), Error);
}

TEST(ObjectsLost, CountedPerRegionOrPerObject) {
  // The mug's body (50: 3 points) in the table segment with 4 table points, its
  // handle (51: 3 points) a segment of its own. Parts: the body is lost, the
  // handle not. Objects: the mug (6 points) meets segment 1 and segment 2 with
  // 3 points each; the tie goes to the smaller label, 1, holding 4 support
  // points > 3: lost, as one object.
  const Labels gt = {1, 1, 1, 1, 50, 50, 50, 51, 51, 51};
  const Labels pred = {1, 1, 1, 1, 1, 1, 1, 2, 2, 2};
  const LabelRange table{0, 9};
  EXPECT_EQ(score_segmentation(pred, gt, cloud(10), table).lost_labels, (std::vector<std::uint32_t>{50}));
  const SegmentationScores objects = score_objects(pred, gt, cloud(10), table);
  EXPECT_EQ(objects.objects_lost, 1u);
  EXPECT_EQ(objects.lost_labels, (std::vector<std::uint32_t>{50}));
  // Several lost regions are listed in ascending order.
  const Labels two = {1, 1, 1, 1, 1, 1, 30, 20, 20, 40};
  const Labels swallowed = {1, 1, 1, 1, 1, 1, 1, 1, 1, 2};
  EXPECT_EQ(score_segmentation(swallowed, two, cloud(10), table).lost_labels, (std::vector<std::uint32_t>{20, 30}));
}

}  // namespace
}  // namespace lccp
