"""segment(): the same labels as the lccp tool, shapes kept, NaN points 0,
float64 and thread counts changing nothing, configs in every form."""
import subprocess

import numpy as np
import pytest

import lccp_stream


def test_labels_equal_the_command_line(tmp_path, source_dir, lccp_binary, mosd_cloud, mosd_labels):
    out = tmp_path / "mosd_test2.pcd"
    subprocess.run([lccp_binary, "segment", str(source_dir / "tests" / "data" / "mosd_test2.pcd"),
                    "--config", "p1", "-o", str(out)], check=True, capture_output=True)
    cli = lccp_stream.read_cloud(out)
    assert cli["labels"].shape == (480, 640)
    np.testing.assert_array_equal(cli["points"], mosd_cloud["points"])
    assert mosd_labels.dtype == np.uint32
    assert len(np.unique(mosd_labels)) > 2  # 0 and more than one segment
    np.testing.assert_array_equal(mosd_labels, cli["labels"])


def test_organized_cloud_keeps_its_shape(mosd_cloud, mosd_labels):
    assert mosd_cloud["points"].shape == (480, 640, 3)
    assert mosd_labels.shape == (480, 640)
    assert not mosd_labels.flags.owndata  # a view of the library's label vector, not a copy
    flat = lccp_stream.segment(mosd_cloud["points"].reshape(-1, 3), colors=mosd_cloud["colors"].reshape(-1, 3))
    assert flat.shape == (480 * 640,) and flat.dtype == np.uint32
    finite = np.isfinite(mosd_cloud["points"]).all(axis=-1).reshape(-1)
    assert (flat[finite] > 0).all() and (flat[~finite] == 0).all()


def test_float64_and_packed_colors_give_the_same_labels(mosd_cloud, mosd_labels):
    rgb = mosd_cloud["colors"].astype(np.uint32)
    packed = rgb[..., 0] << 16 | rgb[..., 1] << 8 | rgb[..., 2]
    labels = lccp_stream.segment(mosd_cloud["points"].astype(np.float64), colors=packed)
    np.testing.assert_array_equal(labels, mosd_labels)


def test_a_non_contiguous_view_is_copied_and_segmented_alike(mosd_cloud, mosd_labels):
    xyzw = np.zeros((480, 640, 4), np.float32)
    xyzw[..., :3] = mosd_cloud["points"]
    labels = lccp_stream.segment(xyzw[..., :3], colors=mosd_cloud["colors"])
    np.testing.assert_array_equal(labels, mosd_labels)


def test_nan_points_are_labelled_0(mosd_cloud):
    points = mosd_cloud["points"].copy()
    points[100:140] = np.nan  # 40 whole rows without data
    labels = lccp_stream.segment(points)
    assert (labels[100:140] == 0).all()
    finite = np.isfinite(points).all(axis=-1)
    assert (labels[finite] > 0).all()
    assert (labels[~finite] == 0).all()


def test_one_and_two_threads_give_identical_labels(mosd_cloud):
    points = mosd_cloud["points"]
    one = lccp_stream.segment(points, config="p2", threads=1)
    two = lccp_stream.segment(points, config="p2", threads=2)
    np.testing.assert_array_equal(one, two)
    with pytest.raises(ValueError, match="threads"):
        lccp_stream.segment(points, threads=0)


def test_segments_are_the_json_documents_objects(mosd_cloud):
    labels, objects = lccp_stream.segment(mosd_cloud["points"], config="objects", segments=True)
    assert isinstance(objects, list) and objects
    ids = {o["id"] for o in objects}
    assert ids == set(np.unique(labels)) - {0, 1}  # 1: the support plane, not an object
    for o in objects:
        assert o["points"] == int((labels == o["id"]).sum())
        assert o["grasp"] in ("top", "side")
        assert len(o["obb"]["axes"]) == 3 and o["parts"] == []


def test_config_forms_agree(tmp_path, source_dir, mosd_cloud):
    points = mosd_cloud["points"]
    by_name = lccp_stream.segment(points, config="p2")
    by_path = lccp_stream.segment(points, config=source_dir / "config" / "p2.yaml")
    by_config = lccp_stream.segment(points, config=lccp_stream.load_config("p2"))
    by_dict = lccp_stream.segment(points, config={"voxel_size_m": 0.0075, "seed_size_m": 0.06,
                                                  "n_filter_supervoxels": 1})
    for labels in (by_path, by_config, by_dict):
        np.testing.assert_array_equal(labels, by_name)
    assert not np.array_equal(by_name, lccp_stream.segment(points, config="p1"))


def test_config_objects(source_dir):
    assert lccp_stream.presets() == ["objects", "p1", "p2", "paper", "robot"]
    robot = lccp_stream.load_config("robot")
    assert robot.levels == 2 and lccp_stream.load_config("p1").levels == 1
    text = str(robot)
    assert "beta_thresh_deg" in text and "parts.beta_thresh_deg" in text
    two_levels = lccp_stream.load_config({"support_plane": True, "parts": {"beta_thresh_deg": 12}})
    assert two_levels.levels == 2 and "12" in str(two_levels)


def test_two_levels_give_parts_within_objects(mosd_cloud):
    labels, objects = lccp_stream.segment(mosd_cloud["points"], config="robot", segments=True)
    assert labels.shape == (480, 640)
    parts = [p for o in objects for p in o["parts"]]
    assert parts and {p["id"] for p in parts} <= set(np.unique(labels))
