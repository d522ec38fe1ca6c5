// lccp_ros: the LCCP Stream node as a standalone process (ros_node.hpp lists its
// topics and parameters). Exits 1 after a ROS_ERROR for a bad parameter.
#include <ros/ros.h>

#include "lccp/process.hpp"
#include "ros_node.hpp"

int main(int argc, char** argv) {
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
