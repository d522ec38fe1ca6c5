"""The installed package as a user meets it (cmake/Install.cmake): install the
build to a temporary prefix, move the prefix, then from another folder run the
installed lccp (its drivers and the virtual sensor), build examples/consumer
against the installed CMake package, and import the installed Python module.
Each must give the same segments as the build's own `lccp segment`."""
import json
import os
import pathlib
import re
import subprocess
import sys

import pytest

BUILD = pathlib.Path(os.environ["LCCP_BUILD_DIR"])
SOURCE = pathlib.Path(os.environ["LCCP_SOURCE_DIR"])
CLOUD = SOURCE / "tests" / "data" / "mosd_test2.pcd"


def run(args, cwd, env=None):
    done = subprocess.run([str(a) for a in args], cwd=cwd, env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, f"{args} failed ({done.returncode}):\n{done.stdout}\n{done.stderr}"
    return done.stdout


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    """The install, moved after installing: nothing may point back at the first place."""
    first = tmp_path_factory.mktemp("install") / "prefix"
    log = run(["cmake", "--install", BUILD, "--prefix", first], cwd=BUILD)
    moved = first.parent / "moved"
    first.rename(moved)
    return moved, log


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The build tree's lccp segment: the objects (id, points) of the P1 segments JSON."""
    out = tmp_path_factory.mktemp("reference")
    run([BUILD / "lccp", "segment", CLOUD, "-o", out / "labels.pcd", "--segments", out / "segments.json"], cwd=out)
    document = json.loads((out / "segments.json").read_text())
    return [(o["id"], o["points"]) for o in document["objects"]]


def test_layout(prefix):
    root, log = prefix
    for path in ["bin/lccp", "lib/liblccp_stream.so", "lib/libOpenNI2.so.0",
                 "lib/OpenNI2/Drivers/libLccpVirtualSensor.so.0", "lib/OpenNI2/Drivers/libOniFile.so.0",
                 "include/lccp/objects/scene.hpp", "lib/cmake/LccpStream/LccpStreamConfig.cmake"]:
        assert (root / path).exists(), path
    assert "Python module:" in log


def test_installed_lccp_finds_its_drivers_after_a_move(prefix, tmp_path):
    root, _ = prefix
    out = run([root / "bin" / "lccp", "profile", "virtual://synthetic", "--frames", "2", "-o", tmp_path / "p"], cwd=tmp_path)
    assert "2 received" in out and "2 completed" in out


def test_consumer_builds_against_the_package_and_agrees(prefix, reference, tmp_path):
    root, _ = prefix
    build = tmp_path / "consumer"
    run(["cmake", "-S", SOURCE / "examples" / "consumer", "-B", build, f"-DCMAKE_PREFIX_PATH={root}"], cwd=tmp_path)
    run(["cmake", "--build", build], cwd=tmp_path)
    out = run([build / "segment_cloud", CLOUD, "p1"], cwd=tmp_path)
    printed = [(int(i), int(n)) for i, n in re.findall(r"^object (\d+): (\d+) points", out, re.M)]
    assert printed == reference


def test_installed_python_module_agrees(prefix, reference, tmp_path):
    root, _ = prefix
    (site,) = root.glob("lib/python3*/dist-packages")
    script = ("import lccp_stream, sys\n"
              "cloud = lccp_stream.read_cloud(sys.argv[1])\n"
              "result = lccp_stream.segment(cloud['points'], cloud['colors'], segments=True)\n"
              "print(*[f\"{o['id']} {o['points']}\" for o in result.segments], sep='\\n')\n")
    env = dict(os.environ, PYTHONPATH=str(site))
    out = run([sys.executable, "-c", script, CLOUD], cwd=tmp_path, env=env)
    printed = [tuple(int(v) for v in line.split()) for line in out.splitlines()]
    assert printed == reference
