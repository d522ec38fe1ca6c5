#!/usr/bin/python3
"""lccp_ros's private parameters as a new user meets them (tests/CMakeLists.txt: Ros.*).

A private parameter given on the command line (`_input:=foo`) is set on the parameter
server and stays there after the node exits (wiki.ros.org/Remapping Arguments), so a
mistyped one makes every later plain run fail too. The node's error line must name the
parameter and the `rosparam delete` command that clears it; running that command must
let the next plain run start. Own ROS master on a free port; stops what it starts.

  test_parameters.py --lccp-ros build/lccp_ros
"""
import argparse
import os
import re
import signal
import subprocess

import rosgraph

from ros_harness import run_in_scratch, start_master, wait_for

START_TIMEOUT_S = 60
NODE = "lccp_typo"


def refused(lccp_ros, env, *args):
    """Runs the node expecting a refusal: exit 1 and one error line, which is returned."""
    result = subprocess.run([lccp_ros, f"__name:={NODE}", *args], env=env, capture_output=True, text=True,
                            timeout=START_TIMEOUT_S)
    assert result.returncode == 1, (args, result.returncode, result.stdout, result.stderr)
    errors = [line for line in result.stderr.splitlines() if "lccp_ros:" in line]
    assert len(errors) == 1, result.stderr
    return errors[0]


def clear_as_told(error, env, parameters):
    """Runs the `rosparam delete ...` the error line names; they must be exactly `parameters`."""
    commands = re.search(r"`(rosparam delete [^`]*)`", error)
    assert commands, f"no rosparam delete command in: {error}"
    deleted = []
    for command in commands.group(1).split("; "):
        words = command.split()
        assert words[:2] == ["rosparam", "delete"] and len(words) == 3, command
        deleted.append(words[2])
        subprocess.run(words, env=env, check=True, capture_output=True, timeout=START_TIMEOUT_S)
    assert deleted == [f"/{NODE}/{name}" for name in parameters], deleted


def starts(lccp_ros, env, processes, tmp):
    """A plain run subscribes to its input; SIGINT then ends it with status 0."""
    node = processes.start([lccp_ros, f"__name:={NODE}"], env, os.path.join(tmp, "plain.log"))
    master = rosgraph.Master("/lccp_parameters_test", master_uri=env["ROS_MASTER_URI"])

    def subscribed():
        assert node.poll() is None, open(os.path.join(tmp, "plain.log"), errors="replace").read()
        _, subscribers, _ = master.getSystemState()
        return any(topic == "/depth/image_raw" and f"/{NODE}" in nodes for topic, nodes in subscribers)
    wait_for(subscribed, START_TIMEOUT_S, "the plain run to subscribe")
    os.killpg(node.pid, signal.SIGINT)
    assert node.wait(timeout=60) == 0, node.returncode


def run(args, tmp, processes):
    env = start_master(processes, tmp, START_TIMEOUT_S)
    # A mistyped ~input: refused, and refused again without it until it is deleted.
    error = refused(args.lccp_ros, env, "_input:=foo")
    assert "~input must be depth or points, not foo" in error, error
    assert f"rosparam delete /{NODE}/input" in error, error
    again = refused(args.lccp_ros, env)
    assert "not foo" in again and f"rosparam delete /{NODE}/input" in again, again
    clear_as_told(again, env, ["input"])
    starts(args.lccp_ros, env, processes, tmp)
    # Unknown names and bad config values are named the same way.
    error = refused(args.lccp_ros, env, "_bogus_key:=3", "_voxel_size_mm:=5")
    assert "unknown private parameters ~bogus_key, ~voxel_size_mm" in error, error
    clear_as_told(refused(args.lccp_ros, env), env, ["bogus_key", "voxel_size_mm"])
    error = refused(args.lccp_ros, env, "_voxel_size_m:=-1")
    assert "voxel_size_m" in error and "> 0" in error, error
    clear_as_told(refused(args.lccp_ros, env), env, ["voxel_size_m"])
    starts(args.lccp_ros, env, processes, tmp)
    print("OK: bad private parameters name the rosparam delete that clears them")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--lccp-ros", required=True)
    args = parser.parse_args()
    run_in_scratch("lccp_ros_parameters_", ("plain.log", "master.log"),
                   lambda tmp, processes: run(args, tmp, processes))


if __name__ == "__main__":
    main()
