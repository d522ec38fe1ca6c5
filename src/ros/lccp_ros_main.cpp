// lccp_ros: the LCCP Stream node as a standalone process (ros_node.hpp lists its
// topics and parameters). Exits 1 after a ROS_ERROR for a bad parameter; --help
// prints the usage and exits 0 without starting ROS.
#include <ros/ros.h>

#include <cstdio>
#include <string>

#include "lccp/process.hpp"
#include "ros_node.hpp"

namespace {

constexpr const char* kUsage =
    "Usage: lccp_ros [_KEY:=VALUE ...] [NAME:=REMAPPED ...]\n"
    "The LCCP Stream segmentation node (needs a ROS master: roscore).\n"
    "  in:  ~input depth (default): depth/image_raw (16UC1 mm or 32FC1 m) + depth/camera_info;\n"
    "       ~input points: points (sensor_msgs/PointCloud2, float32 x y z [rgb])\n"
    "  out: ~labels (PointCloud2, uint32 label and object), ~label_image (rgb8),\n"
    "       ~segments (std_msgs/String, the per-frame JSON), ~markers (MarkerArray), /diagnostics\n"
    "  parameters: ~config (p1, p2, paper, objects, robot or a YAML file; default p1), every config\n"
    "       key as ~KEY (~parts/KEY for the part level), ~inflight (2), ~threads (0: every core)\n"
    "  e.g. rosrun lccp_ros lccp_ros _input:=points points:=/my/cloud _config:=objects\n";

// --help or -h anywhere (ROS remappings contain ":="): usage, and no master contacted.
bool asks_for_help(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (asks_for_help(argc, argv)) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  ros::init(argc, argv, "lccp_ros");
  lccp::keep_freed_memory_for_next_frames();  // as lccp's main: a frame reuses the previous frame's pages
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  std::unique_ptr<lccp::ros_node::LccpRosNode> lccp_node;
  try {
    lccp_node = std::make_unique<lccp::ros_node::LccpRosNode>(node, private_node);
  } catch (const std::exception& error) {
    ROS_ERROR("lccp_ros: %s", error.what());
    return 1;
  }
  ros::spin();  // until Ctrl-C or rosnode kill (ros::init's SIGINT handler)
  lccp_node.reset();  // the frames in flight are finished and published
  return 0;
}
