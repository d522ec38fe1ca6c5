#pragma once
// The ROS 1 half of lccp_ros (C++17: ROS headers): parameters, subscribers,
// publishers and /diagnostics around a SegmentationNode. Used by the standalone
// executable (lccp_ros_main.cpp) and the nodelet (lccp_nodelet.cpp) alike.
//
// Topics (relative to the node handle, remappable):
//   in  ~input = depth: depth/image_raw (16UC1 mm or 32FC1 m) + depth/camera_info
//       ~input = points: points (sensor_msgs/PointCloud2, float32 x y z)
//   out ~labels (PointCloud2: x y z float32, label and object uint32), ~label_image
//       (rgb8, organized inputs), ~segments (std_msgs/String: the per-frame JSON
//       document of encode_segments_json), ~markers (MarkerArray: a CUBE and an id
//       per object and part), /diagnostics once a second.
// Parameters (private): ~input, ~config (preset or YAML path, default p1),
//   ~inflight (K, default 2), ~threads (0: all cores), and every config key
//   (~parts/KEY for the second level) overriding the config. They stay on the
//   parameter server after the node exits, so an error about one names the
//   `rosparam delete` that clears it.
#include <memory>
#include <mutex>

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include "segmentation_node.hpp"

namespace lccp::ros_node {

class LccpRosNode {
 public:
  // Throws lccp::Error (one line, naming them and the `rosparam delete` that
  // clears them) for unknown private parameters, a bad config, setting or input kind.
  LccpRosNode(ros::NodeHandle node, ros::NodeHandle private_node);
  ~LccpRosNode();

 private:
  void on_camera_info(const sensor_msgs::CameraInfo::ConstPtr& info);
  void on_depth(const sensor_msgs::Image::ConstPtr& image);
  void on_points(const sensor_msgs::PointCloud2::ConstPtr& cloud);
  void publish(FrameOutput&& output);
  void publish_diagnostics();

  ros::NodeHandle node_;
  ros::NodeHandle private_node_;
  ros::Publisher labels_, label_image_, segments_, markers_, diagnostics_;
  std::mutex info_mutex_;
  sensor_msgs::CameraInfo::ConstPtr camera_info_;
  std::unique_ptr<SegmentationNode> segmentation_;
  ros::Subscriber image_subscriber_, info_subscriber_, points_subscriber_;
  ros::WallTimer diagnostics_timer_;
};

}  // namespace lccp::ros_node
