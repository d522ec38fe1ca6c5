"""segment(): the same labels as the lccp tool, shapes kept, NaN points 0,
float64 and thread counts changing nothing, configs in every form."""
import json
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


def test_finite_points_alone_get_the_organized_labels(mosd_cloud, mosd_labels):
    # What numpy and Open3D users pass: a depth frame's finite points as (N, 3).
    # A camera's cloud is binned in camera cells organized or not, so it is the
    # same segmentation.
    points = mosd_cloud["points"].reshape(-1, 3)
    finite = np.isfinite(points).all(axis=-1)
    flat = lccp_stream.segment(np.ascontiguousarray(points[finite]),
                               colors=np.ascontiguousarray(mosd_cloud["colors"].reshape(-1, 3)[finite]))
    np.testing.assert_array_equal(flat, mosd_labels.reshape(-1)[finite])


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
    result = lccp_stream.segment(mosd_cloud["points"], config="objects", segments=True)
    labels, segments = result.labels, result.segments
    assert isinstance(segments, list) and segments
    ids = {s["id"] for s in segments}
    assert ids == set(np.unique(labels)) - {0, 1}  # 1: the support plane, not an object
    for s in segments:
        assert s["points"] == int((labels == s["id"]).sum())
        assert s["grasp"] in ("top", "side")
        assert s["obb"]["axes"].shape == (3, 3) and s["parts"] == []


def test_segment_result_has_the_names_of_a_frame(mosd_cloud, recording):
    # The same names for the same things in segment()'s result and a stream's Frame:
    # labels and objects per point, segments and support_plane per segment.
    result = lccp_stream.segment(mosd_cloud["points"], config="robot", segments=True)
    frame = next(iter(lccp_stream.Replay(recording, config="robot", frames=1)))
    for segmentation in (result, frame):
        assert isinstance(segmentation, lccp_stream.Segmentation)
        assert segmentation.labels.dtype == np.uint32 and segmentation.labels.shape == (480, 640)
        assert segmentation.objects.dtype == np.uint32 and segmentation.objects.shape == (480, 640)
        assert isinstance(segmentation.segments, list) and isinstance(segmentation.segments[0], dict)
        assert segmentation.support_plane["id"] == 1
    with pytest.raises(TypeError, match="labels, objects .per point., segments"):
        labels, objects = result  # the (labels, objects) tuple it returned before
    assert isinstance(lccp_stream.segment(mosd_cloud["points"]), np.ndarray)  # the default: labels alone


def test_segment_gives_per_point_objects_and_the_support_plane(mosd_cloud):
    result = lccp_stream.segment(mosd_cloud["points"], config="robot", segments=True)
    plane = result.support_plane
    assert plane is not None and plane["id"] == 1
    assert ((result.objects == 1) == (result.labels == 1)).all()  # the support is one segment on both levels
    finite = np.isfinite(mosd_cloud["points"]).all(axis=-1)
    on_plane = result.objects == 1
    distance = mosd_cloud["points"][on_plane] @ plane["normal"] + plane["d"]
    assert np.abs(distance).max() < 0.011  # support_distance_m 1 cm of the robot preset
    assert (result.objects[~finite] == 0).all()
    for segment in result.segments:
        assert segment["points"] == int((result.objects == segment["id"]).sum())
        for part in segment["parts"]:
            in_part = result.labels == part["id"]
            assert part["points"] == int(in_part.sum())
            assert (result.objects[in_part] == segment["id"]).all()  # parts nest in their object
    one_level = lccp_stream.segment(mosd_cloud["points"], config="p1", segments=True)
    assert one_level.objects is None and one_level.support_plane is None


def test_geometry_comes_as_numpy_float_arrays(tmp_path, source_dir, lccp_binary, mosd_cloud, recording):
    result = lccp_stream.segment(mosd_cloud["points"], colors=mosd_cloud["colors"], config="robot", segments=True)
    frame = next(iter(lccp_stream.Replay(recording, config="robot", frames=1)))
    for segmentation in (result, frame):
        assert segmentation.support_plane["normal"].dtype == np.float64
        assert segmentation.support_plane["normal"].shape == (3,)
        parts = [p for s in segmentation.segments for p in s["parts"]]
        assert parts
        for segment in segmentation.segments + parts:
            shapes = {name: (3,) for name in ("centroid", "principal_extents", "mean_normal")}
            shapes["principal_axes"] = (3, 3)
            for name, shape in shapes.items():
                value = segment[name]
                assert isinstance(value, np.ndarray) and value.dtype == np.float64 and value.shape == shape, name
            assert segment["obb"]["center"].shape == (3,) and segment["obb"]["extents"].shape == (3,)
            axes = segment["obb"]["axes"]
            assert axes.dtype == np.float64 and axes.shape == (3, 3)
            np.testing.assert_allclose(np.linalg.norm(axes, axis=1), 1, atol=1e-5)  # one unit axis a row
    # The numbers are the JSON file's: lccp segment --segments writes the same document.
    written = tmp_path / "segments.json"
    subprocess.run([lccp_binary, "segment", str(source_dir / "tests" / "data" / "mosd_test2.pcd"), "--config",
                    "robot", "-o", str(tmp_path / "labels.pcd"), "--segments", str(written)],
                   check=True, capture_output=True)
    document = json.loads(written.read_text())
    np.testing.assert_array_equal(result.support_plane["normal"], document["support_plane"]["normal"])
    assert len(result.segments) == len(document["objects"])
    for ours, theirs in zip(result.segments, document["objects"]):
        np.testing.assert_array_equal(ours["centroid"], theirs["centroid"])
        np.testing.assert_array_equal(ours["obb"]["axes"], theirs["obb"]["axes"])
        np.testing.assert_array_equal(ours["principal_axes"], theirs["principal_axes"])


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
    assert lccp_stream.presets() == ["objects", "p1", "p2", "paper-robot", "paper", "robot"]
    robot, paper_robot = lccp_stream.load_config("robot"), lccp_stream.load_config("paper-robot")
    assert robot.levels == 2 and paper_robot.levels == 2 and lccp_stream.load_config("p1").levels == 1
    assert "objects_from_parts: true" in str(robot) and "parts.beta_thresh_deg" not in str(robot)
    text = str(paper_robot)
    assert "beta_thresh_deg" in text and "parts.beta_thresh_deg" in text
    two_levels = lccp_stream.load_config({"support_plane": True, "parts": {"beta_thresh_deg": 12}})
    assert two_levels.levels == 2 and "12" in str(two_levels)


def test_two_levels_give_parts_within_objects(mosd_cloud):
    result = lccp_stream.segment(mosd_cloud["points"], config="robot", segments=True)
    assert result.labels.shape == (480, 640)
    parts = [p for s in result.segments for p in s["parts"]]
    assert parts and {p["id"] for p in parts} <= set(np.unique(result.labels))
