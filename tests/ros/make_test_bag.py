#!/usr/bin/python3
"""Writes a small rosbag for tests/rosbag_source_test.cpp: the kinds of topic the
rosbag frame source reads or refuses (rosbag's Python API, wiki.ros.org/rosbag/Code API).

  /cam/depth/image_raw + camera_info   2x2 32FC1 metres: 0.5, NaN, 1.25, 0
  /bad/depth/image_raw + camera_info   2x1 rgb8 (not a depth encoding)
  /points                              2x1 PointCloud2, float32 x y z and rgb
  /chatter                             std_msgs/String
"""
import struct
import sys

import rosbag
import rospy
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField
from std_msgs.msg import String


def camera_info(header, width, height):
    info = CameraInfo(header=header, width=width, height=height, distortion_model="plumb_bob")
    info.D = [0.0] * 5
    info.K = [2.0, 0, width / 2.0, 0, 2.0, height / 2.0, 0, 0, 1]
    return info


def image(stamp, width, height, encoding, data):
    msg = Image(width=width, height=height, encoding=encoding, is_bigendian=0, data=data)
    msg.header.stamp = stamp
    msg.header.frame_id = "cam"
    msg.step = len(data) // height
    return msg


def main(path):
    stamp = rospy.Time(5, 250000000)
    depth = image(stamp, 2, 2, "32FC1", struct.pack("<4f", 0.5, float("nan"), 1.25, 0.0))
    bad = image(stamp, 2, 1, "rgb8", bytes(6))
    fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1)
              for i, n in enumerate(["x", "y", "z", "rgb"])]
    points = PointCloud2(height=1, width=2, fields=fields, is_bigendian=False, point_step=16, row_step=32,
                         is_dense=True)
    points.header.stamp = stamp
    points.data = struct.pack("<3fI3fI", 1, 2, 3, 0xFF0000, 4, 5, 6, 0x00FF00)
    with rosbag.Bag(path, "w") as bag:
        bag.write("/cam/depth/camera_info", camera_info(depth.header, 2, 2), stamp)
        bag.write("/cam/depth/image_raw", depth, stamp)
        bag.write("/bad/depth/camera_info", camera_info(bad.header, 2, 1), stamp)
        bag.write("/bad/depth/image_raw", bad, stamp)
        bag.write("/points", points, stamp)
        bag.write("/chatter", String(data="hello"), stamp)


if __name__ == "__main__":
    main(sys.argv[1])
