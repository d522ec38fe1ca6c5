"""Shared fixtures for the lccp_stream module's tests (run by ctest, or by hand:
PYTHONPATH=build-py/python LCCP_BINARY=build-py/lccp python3 -m pytest tests/python)."""
import os
import pathlib

import pytest

import lccp_stream

SOURCE_DIR = pathlib.Path(os.environ.get("LCCP_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR


@pytest.fixture(scope="session")
def lccp_binary():
    binary = os.environ.get("LCCP_BINARY")
    if not binary:
        pytest.fail("LCCP_BINARY must name the lccp tool (ctest sets it)")
    return binary


@pytest.fixture(scope="session")
def recording():
    return SOURCE_DIR / "recordings" / "mosd_scenes.oni"


@pytest.fixture(scope="session")
def mosd_cloud():
    """tests/data/mosd_test2.pcd: a real organized Kinect cloud with colours and ground truth."""
    return lccp_stream.read_cloud(SOURCE_DIR / "tests" / "data" / "mosd_test2.pcd")


@pytest.fixture(scope="session")
def mosd_labels(mosd_cloud):
    """segment() of that cloud at P1, computed once for the tests that compare with it."""
    return lccp_stream.segment(mosd_cloud["points"], colors=mosd_cloud["colors"], config="p1")
