"""evaluate(): the paper's Appendix B scores through score_segmentation / score_objects."""
import numpy as np
import pytest

import lccp_stream

KEYS = {"weighted_overlap", "true_positive", "false_positive", "false_negative", "over_segmentation",
        "under_segmentation", "adjusted_rand_index", "ground_truth_regions", "scored_points", "objects_lost",
        "lost_labels"}


def test_perfect_prediction(mosd_cloud):
    gt = mosd_cloud["labels"]
    scores = lccp_stream.evaluate(gt, gt, points=mosd_cloud["points"])
    assert set(scores) == KEYS
    assert scores["weighted_overlap"] == 1.0
    assert scores["true_positive"] == 1.0 and scores["false_positive"] == 0.0
    assert scores["adjusted_rand_index"] == pytest.approx(1.0)
    assert scores["objects_lost"] == 0 and scores["lost_labels"] == []


def test_hand_computed_case():
    # G_10 = 4 points, G_20 = 2; S_1 = the first 3 points, S_2 = the last 3.
    # G_10: best IoU 3/4 (S_1), G_20: 2/3 (S_2). WOv = (4 * 3/4 + 2 * 2/3) / 6 = 13/18.
    gt = np.array([10, 10, 10, 10, 20, 20])
    pred = np.array([1, 1, 1, 2, 2, 2], np.uint32)
    s = lccp_stream.evaluate(pred, gt, ignore=None)
    assert s["weighted_overlap"] == pytest.approx(13 / 18)
    assert s["true_positive"] == pytest.approx((3 / 4 + 2 / 2) / 2)
    assert s["false_positive"] == pytest.approx((0 / 3 + 1 / 3) / 2)
    assert s["false_negative"] == pytest.approx((1 / 4 + 0) / 2)
    assert s["over_segmentation"] == pytest.approx(1 - 5 / 6)
    assert s["under_segmentation"] == pytest.approx(1 / 6)
    assert s["ground_truth_regions"] == 2 and s["scored_points"] == 6


def test_ignore_and_points():
    gt = np.array([0, 5, 10, 10, 20, 20])
    pred = np.array([7, 7, 1, 1, 2, 3])
    # range(10) (the default) and (0, 9) leave out labels 0 and 5
    assert lccp_stream.evaluate(pred, gt)["ground_truth_regions"] == 2
    assert lccp_stream.evaluate(pred, gt, ignore=(0, 9)) == lccp_stream.evaluate(pred, gt)
    assert lccp_stream.evaluate(pred, gt, ignore=None)["ground_truth_regions"] == 4
    points = np.zeros((6, 3), np.float32)
    points[5] = np.nan  # not scored
    s = lccp_stream.evaluate(pred, gt, points=points)
    assert s["scored_points"] == 5 and s["weighted_overlap"] == pytest.approx(1.0)
    with pytest.raises(ValueError, match="contiguous"):
        lccp_stream.evaluate(pred, gt, ignore=range(0, 10, 2))
    with pytest.raises(ValueError, match="sizes differ"):
        lccp_stream.evaluate(pred[:5], gt)


def test_object_level_merges_parts():
    gt = np.array([50, 50, 51, 51, 1, 1])
    pred = np.array([3, 3, 3, 3, 4, 4])
    assert lccp_stream.evaluate(pred, gt)["weighted_overlap"] == pytest.approx(0.5)
    s = lccp_stream.evaluate(pred, gt, object_level=True)
    assert s["weighted_overlap"] == 1.0 and s["ground_truth_regions"] == 1


def test_segmentation_of_a_real_scene_scores_like_the_paper(mosd_cloud, mosd_labels):
    s = lccp_stream.evaluate(mosd_labels, mosd_cloud["labels"], points=mosd_cloud["points"])
    assert 0.5 < s["weighted_overlap"] < 1.0
