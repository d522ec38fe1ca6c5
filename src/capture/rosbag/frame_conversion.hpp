#pragma once
// The plain ROS messages of ros_frames.hpp <-> lccp Frames (C++20): the one
// conversion the bag source, the bag writer and the ROS node share.
#include <cstdint>

#include "lccp/frame.hpp"
#include "ros_frames.hpp"

namespace lccp::ros_bridge {

// Depth with its fields of view from fx and fy (see open_rosbag); the frame's
// timestamp_us is the stamp in microseconds, captured now.
Frame to_frame(DepthMessage&& depth, std::uint64_t index);
Frame to_frame(CloudMessage&& cloud, std::uint64_t index);

// A depth frame as a message whose K gives back its fields of view exactly;
// throws lccp::Error if they would not come back bit for bit, or the frame has
// no depth image.
DepthMessage to_depth_message(const Frame& frame, const std::string& frame_id);

}  // namespace lccp::ros_bridge
