// C++17 (ROS 1 headers): see ros_frames.hpp.
#include "ros_messages.hpp"

#include <cmath>
#include <cstring>
#include <optional>

#include "lccp/error.hpp"

namespace lccp::ros_bridge {
namespace {

constexpr std::uint64_t kNanosecondsPerSecond = 1000000000ULL;

void check_image_layout(const sensor_msgs::Image& image, std::uint32_t bytes_per_pixel, const std::string& topic) {
  if (image.is_bigendian) throw Error("topic " + topic + ": big-endian depth images are not supported");
  if (image.width == 0 || image.height == 0 || image.step < std::uint64_t{image.width} * bytes_per_pixel ||
      image.data.size() < std::uint64_t{image.step} * image.height) {
    throw Error("topic " + topic + ": a " + std::to_string(image.width) + "x" + std::to_string(image.height) + " " +
                image.encoding + " image with step " + std::to_string(image.step) + " and " +
                std::to_string(image.data.size()) + " bytes");
  }
}

// Metres to millimetres as 16UC1 holds them: no return (0, NaN) and depths
// beyond 65.535 m become 0.
std::uint16_t millimetres(float metres) {
  if (!(metres > 0) || !std::isfinite(metres)) return 0;
  const float mm = std::round(metres * 1000.0f);
  return mm > 65535.0f ? 0 : static_cast<std::uint16_t>(mm);
}

void copy_depth(const sensor_msgs::Image& image, const std::string& topic, std::vector<std::uint16_t>& out) {
  const bool metres = image.encoding == "32FC1";
  if (!metres && image.encoding != "16UC1" && image.encoding != "mono16") {
    throw Error("topic " + topic + ": encoding " + image.encoding +
                " is not a depth encoding (16UC1 millimetres or 32FC1 metres)");
  }
  check_image_layout(image, metres ? 4 : 2, topic);
  out.resize(std::size_t{image.width} * image.height);
  for (std::uint32_t row = 0; row < image.height; ++row) {
    const std::uint8_t* bytes = image.data.data() + std::size_t{row} * image.step;
    std::uint16_t* line = out.data() + std::size_t{row} * image.width;
    if (!metres) {
      std::memcpy(line, bytes, std::size_t{image.width} * 2);
      continue;
    }
    for (std::uint32_t col = 0; col < image.width; ++col) {
      float value = 0;
      std::memcpy(&value, bytes + std::size_t{col} * 4, 4);
      line[col] = millimetres(value);
    }
  }
}

std::optional<std::uint32_t> field_offset(const sensor_msgs::PointCloud2& cloud, const std::string& name,
                                          bool any_four_bytes) {
  for (const sensor_msgs::PointField& field : cloud.fields) {
    if (field.name != name) continue;
    const bool float32 = field.datatype == sensor_msgs::PointField::FLOAT32;
    const bool uint32 = field.datatype == sensor_msgs::PointField::UINT32;
    if ((float32 || (any_four_bytes && uint32)) && field.count >= 1 && field.offset + 4 <= cloud.point_step) {
      return field.offset;
    }
  }
  return std::nullopt;
}

void check_cloud_layout(const sensor_msgs::PointCloud2& cloud, const std::string& topic) {
  if (cloud.is_bigendian) throw Error("topic " + topic + ": big-endian point clouds are not supported");
  if (cloud.width == 0 || cloud.height == 0 || cloud.row_step < std::uint64_t{cloud.width} * cloud.point_step ||
      cloud.data.size() < std::uint64_t{cloud.row_step} * cloud.height) {
    throw Error("topic " + topic + ": a " + std::to_string(cloud.width) + "x" + std::to_string(cloud.height) +
                " PointCloud2 with point_step " + std::to_string(cloud.point_step) + ", row_step " +
                std::to_string(cloud.row_step) + " and " + std::to_string(cloud.data.size()) + " bytes");
  }
}

}  // namespace

std::uint64_t to_nanoseconds(const ros::Time& stamp) {
  return std::uint64_t{stamp.sec} * kNanosecondsPerSecond + stamp.nsec;
}

ros::Time to_ros_time(std::uint64_t nanoseconds) {
  return ros::Time(static_cast<std::uint32_t>(nanoseconds / kNanosecondsPerSecond),
                   static_cast<std::uint32_t>(nanoseconds % kNanosecondsPerSecond));
}

DepthMessage depth_from_ros(const sensor_msgs::Image& image, const sensor_msgs::CameraInfo& info,
                            const std::string& topic) {
  DepthMessage depth;
  copy_depth(image, topic, depth.depth_mm);
  if (!(info.K[0] > 0 && info.K[4] > 0)) throw Error("topic " + topic + ": its camera_info has no focal length (K)");
  if ((info.width != 0 || info.height != 0) && (info.width != image.width || info.height != image.height)) {
    throw Error("topic " + topic + ": camera_info is " + std::to_string(info.width) + "x" +
                std::to_string(info.height) + ", the image " + std::to_string(image.width) + "x" +
                std::to_string(image.height));
  }
  depth.stamp_ns = to_nanoseconds(image.header.stamp);
  depth.frame_id = image.header.frame_id;
  depth.width = image.width;
  depth.height = image.height;
  depth.fx = info.K[0];
  depth.cx = info.K[2];
  depth.fy = info.K[4];
  depth.cy = info.K[5];
  return depth;
}

CloudMessage cloud_from_ros(const sensor_msgs::PointCloud2& cloud, const std::string& topic) {
  const std::optional<std::uint32_t> x = field_offset(cloud, "x", false);
  const std::optional<std::uint32_t> y = field_offset(cloud, "y", false);
  const std::optional<std::uint32_t> z = field_offset(cloud, "z", false);
  if (!x || !y || !z) throw Error("topic " + topic + ": the PointCloud2 has no float32 x, y and z fields");
  check_cloud_layout(cloud, topic);
  std::optional<std::uint32_t> rgb = field_offset(cloud, "rgb", true);
  if (!rgb) rgb = field_offset(cloud, "rgba", true);
  CloudMessage out;
  out.stamp_ns = to_nanoseconds(cloud.header.stamp);
  out.frame_id = cloud.header.frame_id;
  out.width = cloud.width;
  out.height = cloud.height;
  const std::size_t points = std::size_t{cloud.width} * cloud.height;
  out.xyz.resize(points * 3);
  if (rgb) out.rgb.resize(points);
  for (std::size_t i = 0; i < points; ++i) {
    const std::uint8_t* point = cloud.data.data() + (i / cloud.width) * cloud.row_step + (i % cloud.width) * cloud.point_step;
    std::memcpy(&out.xyz[3 * i], point + *x, 4);
    std::memcpy(&out.xyz[3 * i + 1], point + *y, 4);
    std::memcpy(&out.xyz[3 * i + 2], point + *z, 4);
    if (rgb) {
      std::memcpy(&out.rgb[i], point + *rgb, 4);
      out.rgb[i] &= 0xFFFFFFu;
    }
  }
  return out;
}

void depth_to_ros(const DepthMessage& depth, sensor_msgs::Image& image, sensor_msgs::CameraInfo& info) {
  image.header.stamp = to_ros_time(depth.stamp_ns);
  image.header.frame_id = depth.frame_id;
  image.width = depth.width;
  image.height = depth.height;
  image.encoding = "16UC1";
  image.is_bigendian = 0;
  image.step = depth.width * 2;
  image.data.resize(depth.depth_mm.size() * 2);
  std::memcpy(image.data.data(), depth.depth_mm.data(), image.data.size());
  info.header = image.header;
  info.width = depth.width;
  info.height = depth.height;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {depth.fx, 0, depth.cx, 0, depth.fy, depth.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {depth.fx, 0, depth.cx, 0, 0, depth.fy, depth.cy, 0, 0, 0, 1, 0};
}

}  // namespace lccp::ros_bridge
