// The LCCP Stream node as a nodelet (lccp_ros/LccpNodelet; nodelet_plugins.xml):
// the same LccpRosNode as lccp_ros, in a nodelet manager's process
// (wiki.ros.org/nodelet). A bad parameter is a NODELET_ERROR; the nodelet then
// stays idle, as a manager's other nodelets must keep running.
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "ros_node.hpp"

namespace lccp::ros_node {

class LccpNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      node_ = std::make_unique<LccpRosNode>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& error) {
      NODELET_ERROR("lccp_ros: %s", error.what());
    }
  }

  std::unique_ptr<LccpRosNode> node_;
};

}  // namespace lccp::ros_node

PLUGINLIB_EXPORT_CLASS(lccp::ros_node::LccpNodelet, nodelet::Nodelet)
