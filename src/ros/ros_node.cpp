// The ROS 1 half of lccp_ros (C++17): see ros_node.hpp. Message layouts from the
// ROS wiki: sensor_msgs/PointCloud2 and PointField, sensor_msgs/Image (REP 118),
// visualization_msgs/Marker (rviz's marker types), diagnostic_msgs/DiagnosticArray.
#include "ros_node.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <set>

#include <Eigen/Geometry>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <std_msgs/String.h>
#include <visualization_msgs/MarkerArray.h>

#include "lccp/error.hpp"
#include "ros_messages.hpp"

namespace lccp::ros_node {
namespace {

// Private parameters stay on the parameter server after the node exits: rosrun's
// `_input:=foo` sets /lccp_ros/input there (wiki.ros.org/Remapping%20Arguments,
// "assignment for private node parameters"; wiki.ros.org/Parameter%20Server), and
// a later run without it reads it again. So an error about parameters names each
// one set there and the command that clears it.
Error parameter_error(const std::string& problem, const ros::NodeHandle& private_node,
                      const std::vector<std::string>& names) {
  std::string commands;
  std::size_t count = 0;
  for (const std::string& name : names) {
    if (!private_node.hasParam(name)) continue;
    commands += (count++ == 0 ? "rosparam delete " : "; rosparam delete ") + private_node.resolveName(name);
  }
  if (count == 0) return Error(problem);
  const bool one = count == 1;
  return Error(problem + " (" + (one ? "it stays" : "they stay") +
               " on the parameter server after the node exits, and later runs read " + (one ? "it" : "them") +
               " too: `" + commands + "` clears " + (one ? "it" : "them") + ")");
}

// ~KEY values as the config's text: bool, int, double (shortest exact) or string.
std::string parameter_text(const XmlRpc::XmlRpcValue& value, const std::string& name,
                           const ros::NodeHandle& private_node) {
  XmlRpc::XmlRpcValue copy = value;  // XmlRpcValue's conversions are not const
  switch (copy.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean: return static_cast<bool>(copy) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeInt: return std::to_string(static_cast<int>(copy));
    case XmlRpc::XmlRpcValue::TypeString: return static_cast<std::string>(copy);
    case XmlRpc::XmlRpcValue::TypeDouble: {
      char text[64];
      const auto end = std::to_chars(text, text + sizeof text, static_cast<double>(copy)).ptr;
      return std::string(text, end);
    }
    default: throw parameter_error("~" + name + " must be a number, a boolean or a string", private_node, {name});
  }
}

// The private parameters (names relative to the private namespace, "parts/x").
std::vector<std::string> private_parameter_names(const ros::NodeHandle& private_node) {
  std::vector<std::string> all;
  private_node.getParamNames(all);
  const std::string prefix = private_node.getNamespace() + "/";
  std::vector<std::string> names;
  for (const std::string& name : all) {
    if (name.compare(0, prefix.size(), prefix) == 0) names.push_back(name.substr(prefix.size()));
  }
  return names;
}

template <class T>
T parameter_or(const ros::NodeHandle& private_node, const std::string& name, T fallback) {
  T value = fallback;
  private_node.param(name, value, fallback);
  return value;
}

// The private parameters other than ~input, ~config, ~inflight, ~threads: config keys, or unknown.
std::vector<std::string> config_key_parameters(const ros::NodeHandle& private_node) {
  std::vector<std::string> names;
  for (const std::string& name : private_parameter_names(private_node)) {
    if (name != "input" && name != "config" && name != "inflight" && name != "threads") names.push_back(name);
  }
  return names;
}

Error unknown_parameters_error(const std::vector<std::string>& unknown, const std::vector<std::string>& keys,
                               const ros::NodeHandle& private_node) {
  std::string names, list;
  for (const std::string& name : unknown) names += (names.empty() ? "~" : ", ~") + name;
  for (const std::string& key : keys) list += (list.empty() ? "" : ", ") + key;
  return parameter_error("unknown private parameters " + names + " (known: input, config, inflight, threads, " +
                             list + ")",
                         private_node, unknown);
}

// ~config, ~inflight, ~threads and the config keys; unknown names are refused.
NodeSettings read_settings(const ros::NodeHandle& private_node) {
  NodeSettings settings;
  settings.config = parameter_or<std::string>(private_node, "config", "p1");
  const int inflight = parameter_or(private_node, "inflight", 2);
  const int threads = parameter_or(private_node, "threads", 0);
  if (inflight < 1 || inflight > 16) {
    throw parameter_error("~inflight must be 1 to 16, not " + std::to_string(inflight), private_node, {"inflight"});
  }
  if (threads < 0) {
    throw parameter_error("~threads must be 0 (all cores) or more, not " + std::to_string(threads), private_node,
                          {"threads"});
  }
  settings.frames_in_flight = static_cast<unsigned>(inflight);
  settings.threads = static_cast<unsigned>(threads);
  std::vector<std::string> keys;
  try {
    keys = config_parameter_names(settings.config);
  } catch (const Error& error) {
    throw parameter_error(std::string("~config: ") + error.what(), private_node, {"config"});
  }
  std::set<std::string> known(keys.begin(), keys.end());
  std::vector<std::string> unknown;
  for (const std::string& name : config_key_parameters(private_node)) {
    if (!known.count(name)) {
      unknown.push_back(name);
      continue;
    }
    XmlRpc::XmlRpcValue value;
    private_node.getParam(name, value);
    std::string key = name;
    if (key.compare(0, 6, "parts/") == 0) key.replace(0, 6, "parts.");
    settings.settings.push_back(key + "=" + parameter_text(value, name, private_node));
  }
  if (!unknown.empty()) throw unknown_parameters_error(unknown, keys, private_node);
  return settings;
}

void fill_header(std_msgs::Header& header, const FrameOutput& output) {
  header.stamp = ros_bridge::to_ros_time(output.stamp_ns);
  header.frame_id = output.frame_id;
}

// A PointCloud2 or an Image with the frame's header and layout (width x height).
template <class Message>
Message frame_message(const FrameOutput& output) {
  Message message;
  fill_header(message.header, output);
  message.width = output.width;
  message.height = output.height;
  return message;
}

sensor_msgs::PointField point_field(const char* name, std::uint32_t offset, std::uint8_t datatype) {
  sensor_msgs::PointField field;
  field.name = name;
  field.offset = offset;
  field.datatype = datatype;
  field.count = 1;
  return field;
}

// x y z float32, label and object uint32: 20 bytes a point, in the input's layout.
sensor_msgs::PointCloud2 labels_message(const FrameOutput& output) {
  auto cloud = frame_message<sensor_msgs::PointCloud2>(output);
  cloud.fields = {point_field("x", 0, sensor_msgs::PointField::FLOAT32),
                  point_field("y", 4, sensor_msgs::PointField::FLOAT32),
                  point_field("z", 8, sensor_msgs::PointField::FLOAT32),
                  point_field("label", 12, sensor_msgs::PointField::UINT32),
                  point_field("object", 16, sensor_msgs::PointField::UINT32)};
  cloud.is_bigendian = false;
  cloud.point_step = 20;
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.is_dense = false;
  const std::size_t points = output.labels.size();
  cloud.data.resize(points * cloud.point_step);
  for (std::size_t i = 0; i < points; ++i) {
    std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
    std::memcpy(point, &output.xyz[3 * i], 12);
    std::memcpy(point + 12, &output.labels[i], 4);
    std::memcpy(point + 16, &output.objects[i], 4);
  }
  return cloud;
}

sensor_msgs::Image label_image_message(const FrameOutput& output) {
  auto image = frame_message<sensor_msgs::Image>(output);
  image.encoding = "rgb8";
  image.is_bigendian = 0;
  image.step = 3 * output.width;
  image.data = output.label_rgb;
  return image;
}

visualization_msgs::Marker marker(const FrameOutput& output, const SegmentBox& box, std::int32_t type) {
  visualization_msgs::Marker marker;
  fill_header(marker.header, output);
  marker.ns = box.is_part ? "parts" : "objects";
  marker.id = static_cast<std::int32_t>(box.id);
  marker.type = type;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.position.x = box.center[0];
  marker.pose.position.y = box.center[1];
  marker.pose.position.z = box.center[2];
  const Eigen::Matrix3f axes = Eigen::Map<const Eigen::Matrix<float, 3, 3, Eigen::RowMajor>>(box.axes.data());
  const Eigen::Quaternionf rotation(axes);
  marker.pose.orientation.x = rotation.x();
  marker.pose.orientation.y = rotation.y();
  marker.pose.orientation.z = rotation.z();
  marker.pose.orientation.w = rotation.w();
  marker.color.r = box.color[0] / 255.0f;
  marker.color.g = box.color[1] / 255.0f;
  marker.color.b = box.color[2] / 255.0f;
  marker.color.a = box.is_part ? 0.6f : 0.3f;
  return marker;
}

// DELETEALL first (the previous frame's boxes go), then per object and part an
// oriented CUBE (the obb) and a TEXT_VIEW_FACING with its id above it.
visualization_msgs::MarkerArray markers_message(const FrameOutput& output) {
  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker clear;
  fill_header(clear.header, output);
  clear.action = visualization_msgs::Marker::DELETEALL;
  markers.markers.push_back(clear);
  for (const SegmentBox& box : output.boxes) {
    visualization_msgs::Marker cube = marker(output, box, visualization_msgs::Marker::CUBE);
    cube.scale.x = std::max(box.extents[0], 0.001f);
    cube.scale.y = std::max(box.extents[1], 0.001f);
    cube.scale.z = std::max(box.extents[2], 0.001f);
    markers.markers.push_back(cube);
    visualization_msgs::Marker text = marker(output, box, visualization_msgs::Marker::TEXT_VIEW_FACING);
    text.ns += "_ids";
    text.pose.orientation = geometry_msgs::Quaternion();
    text.pose.orientation.w = 1;
    text.pose.position.y -= 0.5 * box.extents[2] + 0.02;  // above it: the optical frame's y points down
    text.scale.z = 0.03;
    text.color.r = text.color.g = text.color.b = text.color.a = 1;
    text.text = std::to_string(box.id);
    markers.markers.push_back(text);
  }
  return markers;
}

diagnostic_msgs::KeyValue key_value(const std::string& key, const std::string& value) {
  diagnostic_msgs::KeyValue pair;
  pair.key = key;
  pair.value = value;
  return pair;
}

diagnostic_msgs::DiagnosticStatus diagnostic_status(const NodeDiagnostics& diagnostics) {
  diagnostic_msgs::DiagnosticStatus status;
  status.name = ros::this_node::getName() + ": segmentation";
  status.hardware_id = "lccp_stream";
  status.level = diagnostic_msgs::DiagnosticStatus::OK;
  status.message = std::to_string(diagnostics.window_frames) + " frames in the last second";
  status.values = {key_value("frames_received", std::to_string(diagnostics.received)),
                   key_value("sensor_gaps", std::to_string(diagnostics.gaps)),
                   key_value("frames_completed", std::to_string(diagnostics.completed)),
                   key_value("frames_failed", std::to_string(diagnostics.failed)),
                   key_value("frames_dropped", std::to_string(diagnostics.dropped)),
                   key_value("window_frames", std::to_string(diagnostics.window_frames))};
  for (const StageLatency& stage : diagnostics.latency) {
    status.values.push_back(key_value(stage.name + "_p50_ms", std::to_string(stage.p50_ms)));
  }
  return status;
}

}  // namespace

LccpRosNode::LccpRosNode(ros::NodeHandle node, ros::NodeHandle private_node)
    : node_(node), private_node_(private_node) {
  const std::string input = parameter_or<std::string>(private_node_, "input", "depth");
  if (input != "depth" && input != "points") {
    throw parameter_error("~input must be depth or points, not " + input, private_node_, {"input"});
  }
  const NodeSettings settings = read_settings(private_node_);
  labels_ = private_node_.advertise<sensor_msgs::PointCloud2>("labels", 2);
  label_image_ = private_node_.advertise<sensor_msgs::Image>("label_image", 2);
  segments_ = private_node_.advertise<std_msgs::String>("segments", 2);
  markers_ = private_node_.advertise<visualization_msgs::MarkerArray>("markers", 2);
  diagnostics_ = node_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 2);
  try {  // the config's values are checked here (SceneSegmenter)
    segmentation_ = std::make_unique<SegmentationNode>(settings, [this](FrameOutput&& out) { publish(std::move(out)); });
  } catch (const Error& error) {
    std::vector<std::string> names = config_key_parameters(private_node_);
    names.insert(names.begin(), "config");
    throw parameter_error(error.what(), private_node_, names);
  }
  if (input == "depth") {
    info_subscriber_ = node_.subscribe("depth/camera_info", 2, &LccpRosNode::on_camera_info, this);
    image_subscriber_ = node_.subscribe("depth/image_raw", 2, &LccpRosNode::on_depth, this);
  } else {
    points_subscriber_ = node_.subscribe("points", 2, &LccpRosNode::on_points, this);
  }
  diagnostics_timer_ = node_.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) {
    publish_diagnostics();
  });
  ROS_INFO("lccp_ros: config %s, %u frames in flight, input %s (%s)", settings.config.c_str(),
           settings.frames_in_flight, input.c_str(),
           input == "depth" ? image_subscriber_.getTopic().c_str() : points_subscriber_.getTopic().c_str());
}

LccpRosNode::~LccpRosNode() {
  image_subscriber_.shutdown();
  points_subscriber_.shutdown();
  diagnostics_timer_.stop();
  const std::string counts = segmentation_->stop();
  // On stdout, not through rosconsole: after ros::shutdown (Ctrl-C) it prints nothing.
  std::printf("%s: %s\n", ros::this_node::getName().c_str(), counts.c_str());
  std::fflush(stdout);
}

void LccpRosNode::on_camera_info(const sensor_msgs::CameraInfo::ConstPtr& info) {
  const std::lock_guard<std::mutex> lock(info_mutex_);
  camera_info_ = info;
}

void LccpRosNode::on_depth(const sensor_msgs::Image::ConstPtr& image) {
  sensor_msgs::CameraInfo::ConstPtr info;
  {
    const std::lock_guard<std::mutex> lock(info_mutex_);
    info = camera_info_;
  }
  if (!info) {
    ROS_WARN_THROTTLE(5, "lccp_ros: depth image without a camera_info yet on %s", info_subscriber_.getTopic().c_str());
    return;
  }
  try {
    segmentation_->push(ros_bridge::depth_from_ros(*image, *info, image_subscriber_.getTopic()));
  } catch (const Error& error) {
    ROS_ERROR_THROTTLE(5, "lccp_ros: %s", error.what());
  }
}

void LccpRosNode::on_points(const sensor_msgs::PointCloud2::ConstPtr& cloud) {
  try {
    segmentation_->push(ros_bridge::cloud_from_ros(*cloud, points_subscriber_.getTopic()));
  } catch (const Error& error) {
    ROS_ERROR_THROTTLE(5, "lccp_ros: %s", error.what());
  }
}

void LccpRosNode::publish(FrameOutput&& output) {
  if (!output.error.empty()) ROS_WARN("lccp_ros: %s", output.error.c_str());
  labels_.publish(labels_message(output));
  if (output.height > 1) label_image_.publish(label_image_message(output));
  std_msgs::String segments;
  segments.data = std::move(output.segments_json);
  segments_.publish(segments);
  markers_.publish(markers_message(output));
}

void LccpRosNode::publish_diagnostics() {
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  array.status.push_back(diagnostic_status(segmentation_->take_diagnostics()));
  diagnostics_.publish(array);
}

}  // namespace lccp::ros_node
