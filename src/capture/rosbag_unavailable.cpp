// Without ROS (cmake/Ros.cmake did not find it): the rosbag calls say so.
#ifndef LCCP_HAVE_ROSBAG
#include "lccp/capture/rosbag.hpp"
#include "lccp/error.hpp"

namespace lccp {

bool rosbag_supported() { return false; }

std::unique_ptr<FrameSource> open_rosbag(const std::filesystem::path& path, const std::string&) {
  throw Error("cannot read " + path.string() + ": this build of LCCP Stream has no ROS (rosbag) support");
}

std::uint64_t record_bag(FrameSource&, const std::filesystem::path& output, std::stop_token) {
  throw Error("cannot write " + output.string() + ": this build of LCCP Stream has no ROS (rosbag) support");
}

}  // namespace lccp
#endif
