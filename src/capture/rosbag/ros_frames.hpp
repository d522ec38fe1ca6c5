#pragma once
// Plain data between ROS 1 messages and LCCP Stream frames. ROS 1's generated
// messages and roscpp's serialization use std::allocator<T>::rebind, which C++20
// removed, so every file that includes a ROS header is compiled as C++17
// (cmake/Ros.cmake): this header is the boundary, valid C++17 and C++20, with no
// ROS and no lccp type beyond std.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lccp::ros_bridge {

// A sensor_msgs/Image depth image with its sensor_msgs/CameraInfo, in millimetres.
struct DepthMessage {
  std::uint64_t stamp_ns = 0;  // header.stamp
  std::string frame_id;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;  // CameraInfo K, pixels
  std::vector<std::uint16_t> depth_mm;    // row-major, 0 = no return
};

// A sensor_msgs/PointCloud2 with float32 x y z and, if present, rgb or rgba.
struct CloudMessage {
  std::uint64_t stamp_ns = 0;
  std::string frame_id;
  std::uint32_t width = 0;
  std::uint32_t height = 1;
  std::vector<float> xyz;            // 3 per point, metres, NaN = no data
  std::vector<std::uint32_t> rgb;    // 0x00RRGGBB per point; empty without colour
};

// Which message type a bag topic carries.
enum class TopicKind { depth_image, point_cloud };

// A rosbag file read in bag order (librosbag_storage). One topic: depth images
// (each with the latest camera_info of the same namespace, the first one if the
// image comes before any) or PointCloud2 messages.
class BagReader {
 public:
  // `topic` empty: the first depth image topic (sensor_msgs/Image with a
  // camera_info beside it), else the first PointCloud2 topic. Throws lccp::Error
  // (one line) for an unreadable bag, a missing topic or one of another type.
  BagReader(const std::string& path, const std::string& topic);
  ~BagReader();
  BagReader(const BagReader&) = delete;
  BagReader& operator=(const BagReader&) = delete;

  const std::string& topic() const;
  TopicKind kind() const;
  std::uint64_t message_count() const;
  // The next message of the topic (by kind), false at the end. Throws
  // lccp::Error naming the topic for an encoding or layout it cannot read.
  bool next_depth(DepthMessage& out);
  bool next_cloud(CloudMessage& out);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Writes depth frames to a bag as openni2_camera publishes them: 16UC1
// `depth/image_raw` and `depth/camera_info` (K from fx fy cx cy, no distortion),
// both with the frame's stamp, stamped in the bag at that time.
class BagWriter {
 public:
  explicit BagWriter(const std::string& path);  // throws lccp::Error naming the path
  ~BagWriter();
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  void write_depth(const DepthMessage& depth);
  void close();  // writes the bag's index; throws lccp::Error on failure

 private:
  struct State;
  std::unique_ptr<State> state_;
};

inline constexpr const char* kDepthImageTopic = "/depth/image_raw";
inline constexpr const char* kCameraInfoTopic = "/depth/camera_info";

}  // namespace lccp::ros_bridge
