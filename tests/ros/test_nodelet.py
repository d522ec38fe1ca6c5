#!/usr/bin/python3
"""The lccp_ros nodelet loaded as the README says (tests/CMakeLists.txt: Ros.*).

Installs the build into a temporary prefix, then with only ROS_PACKAGE_PATH=PREFIX/share
(no CMAKE_PREFIX_PATH) starts a nodelet manager and loads lccp_ros/LccpNodelet into it with
`rosrun nodelet nodelet load`, sends two depth frames of a bag made from the bundled
recording (lccp record-bag) and checks that the nodelet publishes ~labels for each with the
labels of `lccp replay` of the same bag. Own ROS master on a free port; stops what it starts.

  test_nodelet.py --build-dir build --recording recordings/mosd_scenes.oni
"""
import argparse
import os
import subprocess
import time

import numpy as np
import rosbag
import rospy
from sensor_msgs.msg import CameraInfo, Image, PointCloud2

from ros_harness import run_in_scratch, start_master, wait_for
from test_lccp_ros import labels_of, replay_frames

START_TIMEOUT_S = 120  # a manager loading the library on a loaded 2-core machine
RESULT_TIMEOUT_S = 120
FRAMES = 2


def readme_environment(env, prefix):
    """The README's set-up: the installed prefix on ROS_PACKAGE_PATH, nothing else."""
    env = dict(env, ROS_PACKAGE_PATH=os.path.join(prefix, "share"))
    for name in ("CMAKE_PREFIX_PATH", "AMENT_PREFIX_PATH", "LD_LIBRARY_PATH"):
        env.pop(name, None)
    return env


def alive(process, log_path):
    if process.poll() is not None:
        raise AssertionError(f"exited with {process.returncode}:\n" + open(log_path, errors="replace").read()[-4000:])
    return True


def run(args, tmp, processes):
    prefix = os.path.join(tmp, "prefix")
    subprocess.run(["cmake", "--install", args.build_dir, "--prefix", prefix], check=True, capture_output=True,
                   timeout=600)
    lccp = os.path.join(prefix, "bin", "lccp")
    bag = os.path.join(tmp, "frames.bag")
    subprocess.run([lccp, "record-bag", args.recording, "-o", bag, "--frames", str(FRAMES)], check=True,
                   capture_output=True, timeout=600)
    expected = [points["label"] for points, _, _ in replay_frames(lccp, bag, os.path.join(tmp, "replay"))]
    env = readme_environment(start_master(processes, tmp, START_TIMEOUT_S), prefix)
    manager_log, load_log = os.path.join(tmp, "manager.log"), os.path.join(tmp, "load.log")
    manager = processes.start(["rosrun", "nodelet", "nodelet", "manager", "__name:=manager"], env, manager_log)
    load = processes.start(["rosrun", "nodelet", "nodelet", "load", "lccp_ros/LccpNodelet", "manager",
                            "__name:=lccp", "_config:=p1"], env, load_log)
    rospy.init_node("lccp_nodelet_test", anonymous=True, disable_signals=True)
    labels = {}
    subscriber = rospy.Subscriber("/lccp/labels", PointCloud2, lambda m: labels.__setitem__(m.header.stamp, m),
                                  queue_size=10)
    image_pub = rospy.Publisher("/depth/image_raw", Image, queue_size=10)
    info_pub = rospy.Publisher("/depth/camera_info", CameraInfo, queue_size=10)
    wait_for(lambda: alive(manager, manager_log) and alive(load, load_log) and
             image_pub.get_num_connections() > 0 and info_pub.get_num_connections() > 0 and
             subscriber.get_num_connections() > 0, START_TIMEOUT_S, "the nodelet to subscribe and publish")
    frames = {}
    with rosbag.Bag(bag) as recorded:
        for topic, message, _ in recorded.read_messages():
            frames.setdefault(message.header.stamp, {})[topic] = message
    stamps = sorted(frames)
    assert len(stamps) == FRAMES, stamps
    info_pub.publish(frames[stamps[0]]["/depth/camera_info"])
    time.sleep(1.0)  # the nodelet keeps the latest camera_info: let the first one arrive before any image
    for index, stamp in enumerate(stamps):
        info_pub.publish(frames[stamp]["/depth/camera_info"])
        image_pub.publish(frames[stamp]["/depth/image_raw"])
        wait_for(lambda: stamp in labels, RESULT_TIMEOUT_S, f"the nodelet's labels of frame {index}")
        assert np.array_equal(labels_of(labels[stamp]), expected[index]), f"frame {index}: labels differ"
    print(f"OK: the nodelet loaded from {prefix} with ROS_PACKAGE_PATH only and segmented {FRAMES} frames "
          "as lccp replay")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", required=True)
    parser.add_argument("--recording", required=True)
    args = parser.parse_args()
    run_in_scratch("lccp_nodelet_test_", ("manager.log", "load.log", "master.log"),
                   lambda tmp, processes: run(args, tmp, processes))


if __name__ == "__main__":
    main()
