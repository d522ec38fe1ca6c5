#pragma once
// sensor_msgs <-> the plain messages of ros_frames.hpp (C++17: includes ROS 1
// headers). Message layouts: sensor_msgs/Image, CameraInfo and PointCloud2 on the
// ROS wiki (wiki.ros.org/sensor_msgs) and REP 118 (depth images: 16UC1 millimetres,
// 32FC1 metres, 0 or NaN for no return).
#include <cstdint>
#include <string>

#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include "ros_frames.hpp"

namespace lccp::ros_bridge {

std::uint64_t to_nanoseconds(const ros::Time& stamp);
ros::Time to_ros_time(std::uint64_t nanoseconds);

// Throws lccp::Error (one line naming `topic`) for an encoding other than 16UC1
// (or mono16) and 32FC1, big-endian data, a size that does not match, or a
// camera_info without focal lengths or of another size.
DepthMessage depth_from_ros(const sensor_msgs::Image& image, const sensor_msgs::CameraInfo& info,
                            const std::string& topic);

// Throws lccp::Error naming `topic` without float32 x y z fields or with a
// layout that does not match its data.
CloudMessage cloud_from_ros(const sensor_msgs::PointCloud2& cloud, const std::string& topic);

// A 16UC1 image and its camera_info (K and P from fx fy cx cy, no distortion).
void depth_to_ros(const DepthMessage& depth, sensor_msgs::Image& image, sensor_msgs::CameraInfo& info);

}  // namespace lccp::ros_bridge
