#pragma once
// ROS 1 bag files as frame sources, and depth streams written to bags. Built
// when the library is built with ROS (LCCP_HAVE_ROSBAG, cmake/Ros.cmake); without
// it every call throws lccp::Error saying so.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <stop_token>
#include <string>

#include "lccp/frame_source.hpp"

namespace lccp {

// True when this build reads and writes rosbag files.
bool rosbag_supported();

// A .bag file's frames in bag order (index 0, 1, ...; timestamp_us from each
// header stamp), lossless like an .oni recording (not live). `topic` empty: the
// first depth image topic (sensor_msgs/Image, 16UC1 mm or 32FC1 m, with the
// sensor_msgs/CameraInfo of the same namespace), else the first PointCloud2
// topic. A depth image's field of view comes from its camera_info's focal
// lengths: hfov = 2 atan(width / (2 fx)), as back_project uses it (its principal
// point is the image centre). Throws lccp::Error (one line naming the file or
// topic) for an unreadable bag, a missing topic or one of another type; next()
// throws for an encoding or layout it cannot read.
std::unique_ptr<FrameSource> open_rosbag(const std::filesystem::path& path, const std::string& topic = {});

// Writes every depth frame of `source` to a bag as openni2_camera publishes
// them: /depth/image_raw (16UC1) and /depth/camera_info, both stamped (header
// and bag time) with the wall-clock time the recording of the bag started plus
// the frame's offset from the first frame (timestamp_us - the first one's): an
// .oni holds no wall-clock time, so a bag of one starts when it is written,
// and open_rosbag gives timestamps in microseconds since the Unix epoch. K is fx = width / (2 tan(hfov / 2)) (in double),
// cx = width / 2, so that open_rosbag recovers the fields of view bit for bit
// (checked for every frame) and back-projection gives the same points. The
// file appears only when complete (PendingFile). Stops early, keeping the
// frames written, when `stop` is requested. Returns the frames written; throws
// lccp::Error for a source of point clouds, no frames, or a write error.
std::uint64_t record_bag(FrameSource& source, const std::filesystem::path& output, std::stop_token stop = {});

}  // namespace lccp
