#!/usr/bin/python3
"""Latency through ROS (issue 13, must-show 2): input stamp -> ~labels received.

Starts its own ROS master on a free port and lccp_ros (~config, ~threads,
~inflight), then publishes the bundled recording's depth frames (made into a bag by
`lccp record-bag`, looped) on depth/image_raw + depth/camera_info at RATE Hz for
SECONDS, each stamped with the time it is published. A subscriber in this process
takes every ~labels message's receipt time minus its stamp. Prints p50, p99, max,
frames published, labelled and dropped (published - labelled, and the node's own
/diagnostics count), and writes them as JSON with --json.

  perf/ros_latency.py --lccp build/lccp --lccp-ros build/lccp_ros \
      --recording recordings/mosd_scenes.oni [--rate 30] [--seconds 60] [--config p1] [--threads 2] [--inflight 2]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np
import rosbag
import rospy
from diagnostic_msgs.msg import DiagnosticArray
from sensor_msgs.msg import CameraInfo, Image, PointCloud2

# The private master and process handling the integration test uses (tests/ros).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "ros"))
from ros_harness import Processes, start_master, wait_for  # noqa: E402


def load_frames(lccp, recording, tmp):
    bag_path = os.path.join(tmp, "frames.bag")
    subprocess.run([lccp, "record-bag", recording, "-o", bag_path], check=True, stdout=subprocess.DEVNULL)
    frames = {}
    with rosbag.Bag(bag_path) as bag:
        for topic, message, _ in bag.read_messages():
            frames.setdefault(message.header.stamp.to_nsec(), {})[topic] = message
    return [(frames[s]["/depth/image_raw"], frames[s]["/depth/camera_info"]) for s in sorted(frames)]


class Receiver:
    def __init__(self):
        self.lock = threading.Lock()
        self.latencies_ms = []
        self.dropped_by_node = 0
        self.subscribers = [rospy.Subscriber("/lccp_ros/labels", PointCloud2, self.on_labels, queue_size=100),
                            rospy.Subscriber("/diagnostics", DiagnosticArray, self.on_diagnostics, queue_size=10)]

    def on_labels(self, cloud):
        latency = (rospy.Time.now() - cloud.header.stamp).to_sec() * 1000
        with self.lock:
            self.latencies_ms.append(latency)

    def on_diagnostics(self, array):
        for status in array.status:
            values = {v.key: v.value for v in status.values}
            if "frames_dropped" in values:
                self.dropped_by_node = int(values["frames_dropped"])


def publish_at_rate(frames, rate_hz, seconds, image_pub, info_pub):
    period = 1.0 / rate_hz
    start_time = time.monotonic()
    published = 0
    while time.monotonic() - start_time < seconds:
        image, info = frames[published % len(frames)]
        stamp = rospy.Time.now()
        image.header.stamp = info.header.stamp = stamp
        info_pub.publish(info)
        image_pub.publish(image)
        published += 1
        time.sleep(max(0.0, start_time + published * period - time.monotonic()))
    return published


def measure(args, tmp, processes):
    frames = load_frames(args.lccp, args.recording, tmp)
    env = start_master(processes, tmp, 60)
    node = processes.start([args.lccp_ros, f"_config:={args.config}", f"_threads:={args.threads}",
                            f"_inflight:={args.inflight}"], env, os.path.join(tmp, "lccp_ros.log"))
    rospy.init_node("lccp_ros_latency", anonymous=True, disable_signals=True)
    receiver = Receiver()
    image_pub = rospy.Publisher("/depth/image_raw", Image, queue_size=2)
    info_pub = rospy.Publisher("/depth/camera_info", CameraInfo, queue_size=2)
    wait_for(lambda: node.poll() is None and image_pub.get_num_connections() > 0 and
             all(s.get_num_connections() > 0 for s in receiver.subscribers), 60, "lccp_ros")
    info_pub.publish(frames[0][1])
    time.sleep(1.0)
    published = publish_at_rate(frames, args.rate, args.seconds, image_pub, info_pub)
    time.sleep(3.0)  # the frames in flight arrive
    with receiver.lock:
        latencies = np.array(receiver.latencies_ms)
    return {"rate_hz": args.rate, "seconds": args.seconds, "config": args.config, "threads": args.threads,
            "inflight": args.inflight, "published": published, "labelled": int(latencies.size),
            "dropped": published - int(latencies.size), "dropped_by_node": receiver.dropped_by_node,
            "p50_ms": float(np.percentile(latencies, 50)), "p99_ms": float(np.percentile(latencies, 99)),
            "max_ms": float(latencies.max())}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lccp", required=True)
    parser.add_argument("--lccp-ros", required=True)
    parser.add_argument("--recording", required=True)
    parser.add_argument("--rate", type=float, default=30)
    parser.add_argument("--seconds", type=float, default=60)
    parser.add_argument("--config", default="p1")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--inflight", type=int, default=2)
    parser.add_argument("--json", help="also write the figures to this file")
    args = parser.parse_args()
    processes = Processes()
    with tempfile.TemporaryDirectory(prefix="lccp_ros_latency_") as tmp:
        try:
            result = measure(args, tmp, processes)
        finally:
            if rospy.core.is_initialized():
                rospy.signal_shutdown("done")
            processes.stop_all()
    print(f"ROS latency (stamp -> ~labels received), {args.config}, {args.threads} threads, K={args.inflight}, "
          f"{args.rate:g} Hz for {args.seconds:g} s: p50 {result['p50_ms']:.1f} ms, p99 {result['p99_ms']:.1f} ms, "
          f"max {result['max_ms']:.1f} ms; {result['published']} published, {result['labelled']} labelled, "
          f"{result['dropped']} dropped ({result['dropped_by_node']} counted by the node)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=2)


if __name__ == "__main__":
    main()
