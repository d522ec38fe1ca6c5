#!/usr/bin/python3
"""Integration test of the lccp_ros node (issue 13, must-show 1).

Starts its own ROS master on a free port (ROS_MASTER_URI on 127.0.0.1, a temporary
ROS_HOME and ROS_LOG_DIR), starts lccp_ros (~config p1), plays a bag made from the
bundled recording (lccp record-bag) frame by frame, waiting for each frame's results
before sending the next (so nothing is dropped), and checks that every input frame
yields a ~labels message with the input's stamp whose labels equal `lccp replay` of
the same bag, and a ~segments (JSON) and ~markers message; then that /diagnostics
counts them, that the first frames sent as PointCloud2 (~input points) give the
same labels, and that an unknown private parameter makes the node exit non-zero
naming it. Stops everything it started, also on failure.

  test_lccp_ros.py --lccp build/lccp --lccp-ros build/lccp_ros --recording recordings/mosd_scenes.oni
"""
import argparse
import json
import os
import signal
import subprocess
import threading
import time

import numpy as np
import rosbag
import rospy
from diagnostic_msgs.msg import DiagnosticArray
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField
from std_msgs.msg import String
from visualization_msgs.msg import Marker, MarkerArray

from ros_harness import run_in_scratch, start_master, wait_for

RESULT_TIMEOUT_S = 120  # one frame through the node on a loaded 2-core machine
START_TIMEOUT_S = 60
POINTS_FRAMES = 3  # frames also sent as PointCloud2 (~input points)


def read_pcd(path):
    """The points of an uncompressed binary PCD (lccp replay --pcd-data binary) and its size."""
    with open(path, "rb") as f:
        header = {}
        while True:
            line = f.readline().decode("ascii").strip()
            if line.startswith("#"):
                continue
            key, _, value = line.partition(" ")
            header[key] = value.split()
            if key == "DATA":
                break
        assert header["DATA"] == ["binary"], header["DATA"]
        kinds = {("F", "4"): "<f4", ("U", "4"): "<u4", ("I", "4"): "<i4", ("U", "1"): "u1"}
        dtype = np.dtype([(n, kinds[(t, s)]) for n, t, s in zip(header["FIELDS"], header["TYPE"], header["SIZE"])])
        points = np.frombuffer(f.read(), dtype=dtype, count=int(header["POINTS"][0]))
    return points, int(header["WIDTH"][0]), int(header["HEIGHT"][0])


def replay_frames(lccp, bag, out_dir):
    """(points, width, height) per frame from `lccp replay BAG`, in frame order: x y z label."""
    subprocess.run([lccp, "replay", bag, "-o", out_dir, "--save", "pcd", "--pcd-data", "binary", "--quiet",
                    "--config", "p1"], check=True, timeout=600)
    names = sorted(n for n in os.listdir(out_dir) if n.endswith(".pcd"))
    return [read_pcd(os.path.join(out_dir, n)) for n in names]


class Results:
    """What the node publishes, by input stamp."""

    def __init__(self, namespace):
        self.lock = threading.Lock()
        self.labels, self.segments, self.markers, self.diagnostics = {}, {}, {}, []
        self.subscribers = [
            rospy.Subscriber(namespace + "/labels", PointCloud2, self.keep(self.labels), queue_size=100),
            rospy.Subscriber(namespace + "/segments", String, self.keep_segments, queue_size=100),
            rospy.Subscriber(namespace + "/markers", MarkerArray, self.keep_markers, queue_size=100),
            rospy.Subscriber("/diagnostics", DiagnosticArray, self.keep_diagnostics, queue_size=100)]

    def connected(self):
        return all(s.get_num_connections() > 0 for s in self.subscribers)

    def keep(self, table):
        def callback(message):
            with self.lock:
                table[message.header.stamp.to_nsec()] = message
        return callback

    def keep_segments(self, message):
        document = json.loads(message.data)
        with self.lock:
            self.segments[document["timestamp_us"]] = document

    def keep_markers(self, message):
        with self.lock:
            self.markers[message.markers[0].header.stamp.to_nsec()] = message

    def keep_diagnostics(self, message):
        with self.lock:
            self.diagnostics.append(message)

    def complete(self, stamp_ns):
        with self.lock:
            return stamp_ns in self.labels and stamp_ns // 1000 in self.segments and stamp_ns in self.markers


def labels_of(cloud):
    """The `label` and `object` fields of a ~labels message, per point."""
    offsets = {f.name: f.offset for f in cloud.fields}
    assert [f.name for f in cloud.fields] == ["x", "y", "z", "label", "object"], cloud.fields
    points = np.frombuffer(cloud.data, dtype=np.uint8).reshape(-1, cloud.point_step)
    label = points[:, offsets["label"]:offsets["label"] + 4].copy().view("<u4").ravel()
    return label


def play_and_check(bag_path, expected, results, publishers):
    image_pub, info_pub = publishers
    messages = {}
    with rosbag.Bag(bag_path) as bag:
        for topic, message, bag_time in bag.read_messages():
            assert bag_time == message.header.stamp, (topic, bag_time, message.header.stamp)
            messages.setdefault(message.header.stamp.to_nsec(), {})[topic] = message
    stamps = sorted(messages)
    assert len(stamps) == len(expected), (len(stamps), len(expected))
    info_pub.publish(messages[stamps[0]]["/depth/camera_info"])
    time.sleep(1.0)  # the node keeps the latest camera_info: let the first one arrive before any image
    for index, stamp in enumerate(stamps):
        info_pub.publish(messages[stamp]["/depth/camera_info"])
        image_pub.publish(messages[stamp]["/depth/image_raw"])
        wait_for(lambda: results.complete(stamp), RESULT_TIMEOUT_S, f"the results of frame {index}")
        check_frame(index, stamp, expected[index], messages[stamp]["/depth/image_raw"], results)
        print(f"frame {index}: {int(expected[index].max())} labels, as lccp replay", flush=True)
    return stamps


def check_frame(index, stamp, expected_labels, image, results):
    with results.lock:
        cloud, document, markers = results.labels[stamp], results.segments[stamp // 1000], results.markers[stamp]
    assert cloud.header.frame_id == image.header.frame_id, cloud.header.frame_id
    assert (cloud.width, cloud.height) == (image.width, image.height), (cloud.width, cloud.height)
    labels = labels_of(cloud)
    assert np.array_equal(labels, expected_labels), \
        f"frame {index}: {int(np.sum(labels != expected_labels))} labels differ from lccp replay"
    assert document["frame"] == index, document["frame"]
    assert markers.markers[0].action == Marker.DELETEALL
    boxes = sum(1 + len(o["parts"]) for o in document["objects"])
    assert len(markers.markers) == 1 + 2 * boxes, (len(markers.markers), boxes)


def check_diagnostics(results, frames):
    """/diagnostics once a second: counts and per-stage p50; soon it counts every frame."""
    def latest():
        with results.lock:
            found = [s for d in results.diagnostics for s in d.status if "segmentation" in s.name]
        return {v.key: v.value for v in found[-1].values} if found else {}
    wait_for(lambda: latest().get("frames_completed") == str(frames), 10, f"/diagnostics counting {frames} frames")
    values = latest()
    assert values["frames_received"] == str(frames) and values["frames_dropped"] == "0", values
    assert "end_to_end_p50_ms" in values and "voxelize_p50_ms" in values, values


def check_unknown_parameter(args, env, tmp):
    """An unknown private parameter: a ROS_ERROR naming it, exit status 1."""
    result = subprocess.run([args.lccp_ros, "__name:=lccp_bad", "_bogus_key:=3", "_config:=p1"], env=env,
                            capture_output=True, text=True, timeout=START_TIMEOUT_S)
    assert result.returncode == 1, (result.returncode, result.stdout, result.stderr)
    assert "unknown private parameters ~bogus_key" in result.stderr, result.stderr


def run(args, tmp, processes):
    bag = os.path.join(tmp, "mosd_scenes.bag")
    subprocess.run([args.lccp, "record-bag", args.recording, "-o", bag, "--frames", str(args.frames)], check=True)
    replayed = replay_frames(args.lccp, bag, os.path.join(tmp, "replay"))
    expected = [points["label"] for points, _, _ in replayed]
    env = start_master(processes, tmp, START_TIMEOUT_S)
    check_unknown_parameter(args, env, tmp)
    node = processes.start([args.lccp_ros, "_config:=p1", "_inflight:=2", "_threads:=2"], env,
                           os.path.join(tmp, "lccp_ros.log"))
    rospy.init_node("lccp_ros_test", anonymous=True, disable_signals=True)
    results = Results("/lccp_ros")
    image_pub = rospy.Publisher("/depth/image_raw", Image, queue_size=10)
    info_pub = rospy.Publisher("/depth/camera_info", CameraInfo, queue_size=10)
    wait_for(lambda: node.poll() is None and image_pub.get_num_connections() > 0 and
             info_pub.get_num_connections() > 0, START_TIMEOUT_S, "lccp_ros to subscribe")
    wait_for(lambda: node.poll() is None and results.connected(), START_TIMEOUT_S, "lccp_ros's publishers")
    stamps = play_and_check(bag, expected, results, (image_pub, info_pub))
    check_diagnostics(results, len(stamps))
    assert node.poll() is None, "lccp_ros exited"
    check_points_input(args, env, tmp, processes, replayed[:POINTS_FRAMES])
    check_clean_stop(node, os.path.join(tmp, "lccp_ros.log"), len(stamps))
    print(f"OK: {len(stamps)} depth frames and {POINTS_FRAMES} clouds through lccp_ros, labels as lccp replay")


def check_clean_stop(node, log_path, frames):
    """Ctrl-C (SIGINT): the node finishes, logs the pipeline's counts and exits 0."""
    os.killpg(node.pid, signal.SIGINT)
    assert node.wait(timeout=60) == 0, f"lccp_ros exited with {node.returncode} after SIGINT"
    log = open(log_path, errors="replace").read()
    assert f"frames {frames} received + 0 gaps = {frames} completed + 0 failed + 0 dropped" in log, log[-2000:]


def cloud_message(points, width, height, stamp):
    """An organized PointCloud2 with the float32 x y z of a replayed frame."""
    fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1) for i, n in enumerate("xyz")]
    cloud = PointCloud2(height=height, width=width, fields=fields, is_bigendian=False, point_step=12,
                        row_step=12 * width, is_dense=False)
    cloud.header.stamp = stamp
    cloud.header.frame_id = "cloud_frame"
    cloud.data = np.stack([points["x"], points["y"], points["z"]], axis=1).astype("<f4").tobytes()
    return cloud


def check_points_input(args, env, tmp, processes, frames):
    """~input points: the replayed frames' own points as PointCloud2 give the same labels."""
    node = processes.start([args.lccp_ros, "__name:=lccp_points", "_input:=points", "_config:=p1"], env,
                           os.path.join(tmp, "lccp_points.log"))
    labels = {}
    subscriber = rospy.Subscriber("/lccp_points/labels", PointCloud2,
                                  lambda m: labels.__setitem__(m.header.stamp.to_nsec(), m), queue_size=10)
    publisher = rospy.Publisher("/points", PointCloud2, queue_size=10)
    wait_for(lambda: node.poll() is None and publisher.get_num_connections() > 0 and
             subscriber.get_num_connections() > 0, START_TIMEOUT_S, "lccp_points")
    for index, (points, width, height) in enumerate(frames):
        stamp = rospy.Time(100 + index, 123456789)
        publisher.publish(cloud_message(points, width, height, stamp))
        wait_for(lambda: stamp.to_nsec() in labels, RESULT_TIMEOUT_S, f"the labels of cloud {index}")
        message = labels[stamp.to_nsec()]
        assert (message.width, message.height, message.header.frame_id) == (width, height, "cloud_frame")
        assert np.array_equal(labels_of(message), points["label"]), f"cloud {index}: labels differ from lccp replay"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--lccp", required=True)
    parser.add_argument("--lccp-ros", required=True)
    parser.add_argument("--recording", required=True)
    parser.add_argument("--frames", type=int, default=62)
    args = parser.parse_args()
    run_in_scratch("lccp_ros_test_", ("lccp_ros.log", "master.log"),
                   lambda tmp, processes: run(args, tmp, processes))


if __name__ == "__main__":
    main()
