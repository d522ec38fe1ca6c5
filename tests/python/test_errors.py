"""Bad input raises ValueError with a one-line message naming the problem."""
import numpy as np
import pytest

import lccp_stream

POINTS = np.random.default_rng(1).random((100, 3), dtype=np.float32)


@pytest.mark.parametrize("points, expected", [
    (np.zeros((5, 2), np.float32), r"points: expected an \(N, 3\) or \(H, W, 3\) float32/float64 array, got "
                                   r"float32 array of shape \(5, 2\)"),
    (np.zeros((5, 3), np.int32), r"points: .* got int32 array of shape \(5, 3\)"),
    (np.zeros((0, 3), np.float32), r"points: no points \(shape \(0, 3\)\)"),
    (np.zeros((2, 3, 4), np.float32), r"shape \(2, 3, 4\)"),
    (np.zeros(3, np.float32), r"shape \(3,\)"),
])
def test_bad_points(points, expected):
    with pytest.raises(ValueError, match=expected) as error:
        lccp_stream.segment(points)
    assert "\n" not in str(error.value)


def test_bad_colors_and_normals():
    with pytest.raises(ValueError, match=r"colors: .* for 100 points, got uint8 array of shape \(99, 3\)"):
        lccp_stream.segment(POINTS, colors=np.zeros((99, 3), np.uint8))
    with pytest.raises(ValueError, match=r"colors: .* got float32"):
        lccp_stream.segment(POINTS, colors=np.zeros((100, 3), np.float32))
    with pytest.raises(ValueError, match=r"normals: expected one normal per point \(100\)"):
        lccp_stream.segment(POINTS, normals=np.zeros((10, 3), np.float32))


def test_dict_config_with_an_unknown_key_names_it():
    with pytest.raises(ValueError, match="unknown config key 'voxel_size'"):
        lccp_stream.segment(POINTS, config={"voxel_size": 0.01})
    with pytest.raises(ValueError, match="parts.*unknown config key 'beta'"):
        lccp_stream.segment(POINTS, config={"parts": {"beta": 1}})


def test_out_of_range_config_value_names_the_key():
    with pytest.raises(ValueError, match="voxel_size_m"):
        lccp_stream.segment(POINTS, config={"voxel_size_m": -1})


def test_unknown_preset_lists_the_presets():
    with pytest.raises(ValueError, match="nosuchpreset.*p1") as error:
        lccp_stream.segment(POINTS, config="nosuchpreset")
    assert "\n" not in str(error.value)
    with pytest.raises(ValueError, match="nosuchpreset"):
        lccp_stream.load_config("nosuchpreset")


def test_wrong_config_type():
    with pytest.raises(TypeError):
        lccp_stream.segment(POINTS, config=3)


def test_missing_files(tmp_path):
    with pytest.raises(ValueError, match="missing.pcd"):
        lccp_stream.read_cloud(tmp_path / "missing.pcd")
    with pytest.raises(ValueError, match="missing.oni"):
        lccp_stream.Replay(tmp_path / "missing.oni")


def test_all_nan_cloud_is_a_library_error():
    with pytest.raises(ValueError, match="finite"):
        lccp_stream.segment(np.full((10, 3), np.nan, np.float32))
