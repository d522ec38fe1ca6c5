// The rosbag frame source and bag recording (C++20, no ROS header: the bag is
// read and written through ros_frames.hpp, compiled as C++17).
#include <chrono>
#include <cmath>

#include <spdlog/spdlog.h>

#include "frame_conversion.hpp"
#include "lccp/capture/rosbag.hpp"
#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"

namespace lccp {
namespace ros_bridge {
namespace {

// The pinhole of back_project (src/core/back_projection.cpp, after OpenNI2's
// CoordinateConverter): f = pixels / (2 tan(fov / 2)), computed in double.
double focal_length(std::uint32_t pixels, float fov_rad) {
  return static_cast<double>(pixels) / (2.0 * std::tan(static_cast<double>(fov_rad) / 2.0));
}

// Its inverse. For an f made by focal_length from a float fov, the double result
// is within a few double ulps of that fov, far below half a float ulp, so the
// rounding gives the fov back bit for bit (to_depth_message checks it).
float field_of_view(std::uint32_t pixels, double focal) {
  return static_cast<float>(2.0 * std::atan(static_cast<double>(pixels) / (2.0 * focal)));
}

}  // namespace

Frame to_frame(DepthMessage&& depth, std::uint64_t index) {
  Frame frame;
  frame.index = index;
  frame.timestamp_us = depth.stamp_ns / 1000;
  frame.captured = Clock::now();
  DepthImage image;
  image.width = depth.width;
  image.height = depth.height;
  image.horizontal_fov_rad = field_of_view(depth.width, depth.fx);
  image.vertical_fov_rad = field_of_view(depth.height, depth.fy);
  image.depth_mm = std::move(depth.depth_mm);
  frame.depth = std::move(image);
  return frame;
}

Frame to_frame(CloudMessage&& cloud, std::uint64_t index) {
  Frame frame;
  frame.index = index;
  frame.timestamp_us = cloud.stamp_ns / 1000;
  frame.captured = Clock::now();
  frame.cloud.width = cloud.width;
  frame.cloud.height = cloud.height;
  const std::size_t points = cloud.xyz.size() / 3;
  frame.cloud.points.resize(points);
  for (std::size_t i = 0; i < points; ++i) {
    frame.cloud.points[i] = Eigen::Vector3f(cloud.xyz[3 * i], cloud.xyz[3 * i + 1], cloud.xyz[3 * i + 2]);
  }
  frame.cloud.colors = std::move(cloud.rgb);
  return frame;
}

DepthMessage to_depth_message(const Frame& frame, const std::string& frame_id) {
  if (!frame.depth) throw Error("frame " + std::to_string(frame.index) + " is a point cloud, not a depth image");
  const DepthImage& image = *frame.depth;
  DepthMessage depth;
  depth.stamp_ns = frame.timestamp_us * 1000;
  depth.frame_id = frame_id;
  depth.width = image.width;
  depth.height = image.height;
  depth.fx = focal_length(image.width, image.horizontal_fov_rad);
  depth.fy = focal_length(image.height, image.vertical_fov_rad);
  depth.cx = image.width / 2.0;
  depth.cy = image.height / 2.0;
  if (field_of_view(image.width, depth.fx) != image.horizontal_fov_rad ||
      field_of_view(image.height, depth.fy) != image.vertical_fov_rad) {
    throw Error("frame " + std::to_string(frame.index) + ": its fields of view do not survive camera_info's K");
  }
  depth.depth_mm = image.depth_mm;
  return depth;
}

}  // namespace ros_bridge

namespace {

class RosbagSource final : public FrameSource {
 public:
  RosbagSource(const std::filesystem::path& path, const std::string& topic) : reader_(path.string(), topic) {
    spdlog::info("{}: reading {} ({} messages)", path.string(), reader_.topic(), reader_.message_count());
  }

  std::optional<Frame> next(std::stop_token stop) override {
    if (stop.stop_requested()) return std::nullopt;
    if (reader_.kind() == ros_bridge::TopicKind::point_cloud) {
      ros_bridge::CloudMessage cloud;
      if (!reader_.next_cloud(cloud)) return std::nullopt;
      return ros_bridge::to_frame(std::move(cloud), next_index_++);
    }
    ros_bridge::DepthMessage depth;
    if (!reader_.next_depth(depth)) return std::nullopt;
    warn_about_principal_point(depth);
    return ros_bridge::to_frame(std::move(depth), next_index_++);
  }

  std::optional<std::uint64_t> frame_count() const override { return reader_.message_count(); }
  bool is_live() const override { return false; }

 private:
  // back_project puts the principal point at the image centre (as OpenNI2 does).
  void warn_about_principal_point(const ros_bridge::DepthMessage& depth) {
    if (warned_ || (std::abs(depth.cx - depth.width / 2.0) <= 1 && std::abs(depth.cy - depth.height / 2.0) <= 1)) {
      return;
    }
    warned_ = true;
    spdlog::warn("{}: principal point ({}, {}) is taken as the image centre ({}, {})", reader_.topic(), depth.cx,
                 depth.cy, depth.width / 2.0, depth.height / 2.0);
  }

  ros_bridge::BagReader reader_;
  std::uint64_t next_index_ = 0;
  bool warned_ = false;
};

// Header stamps for recorded frames, in microseconds since the Unix epoch: the
// time the recording of the bag started plus each frame's offset from the first
// frame's timestamp. A frame's own timestamp is relative (an .oni's count from
// its start, a device's from the device's), and an .oni holds no wall-clock
// time (its file header: version, largest timestamp, node count), so the time
// of writing the bag stands for the time the frames were taken.
class BagStamps {
 public:
  std::uint64_t stamp_us(const Frame& frame) {
    if (frames_++ == 0) first_us_ = frame.timestamp_us;
    const std::uint64_t offset = frame.timestamp_us >= first_us_ ? frame.timestamp_us - first_us_ : 0;
    return start_us_ + offset;
  }

 private:
  std::uint64_t start_us_ = static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
          .count());
  std::uint64_t first_us_ = 0;  // the first frame's timestamp
  std::uint64_t frames_ = 0;
};

}  // namespace

bool rosbag_supported() { return true; }

std::unique_ptr<FrameSource> open_rosbag(const std::filesystem::path& path, const std::string& topic) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error("cannot open " + path.string() + ": no such file");
  return std::make_unique<RosbagSource>(path, topic);
}

std::uint64_t record_bag(FrameSource& source, const std::filesystem::path& output, std::stop_token stop) {
  if (output.extension() != ".bag") throw Error("bag " + output.string() + " must have the .bag suffix");
  // Written under a hidden name beside the output (rosbag opens files by path),
  // named when complete (lccp/io/atomic_file.hpp).
  PendingFile pending = PendingFile::named(output);
  ros_bridge::BagWriter writer(pending.temporary_path().string());
  BagStamps stamps;
  std::uint64_t frames = 0;
  while (std::optional<Frame> frame = source.next(stop)) {
    if (!frame->depth) throw Error("record-bag needs depth frames; the source gives point clouds");
    ros_bridge::DepthMessage depth = ros_bridge::to_depth_message(*frame, "camera_depth_optical_frame");
    depth.stamp_ns = stamps.stamp_us(*frame) * 1000;
    writer.write_depth(depth);
    ++frames;
  }
  if (frames == 0) throw Error("no frames to write; " + output.string() + " not written");
  writer.close();
  pending.commit();
  return frames;
}

}  // namespace lccp
