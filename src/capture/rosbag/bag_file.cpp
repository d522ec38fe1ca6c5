// Reading and writing rosbag files with librosbag_storage (C++17: ROS 1 headers;
// the bag API: wiki.ros.org/rosbag/Code API).
#include <algorithm>
#include <optional>

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "lccp/error.hpp"
#include "ros_frames.hpp"
#include "ros_messages.hpp"

namespace lccp::ros_bridge {
namespace {

constexpr const char* kImageType = "sensor_msgs/Image";
constexpr const char* kCameraInfoType = "sensor_msgs/CameraInfo";
constexpr const char* kCloudType = "sensor_msgs/PointCloud2";

struct BagTopic {
  std::string name;
  std::string type;
};

// The bag's topics in the order their connections were first written.
std::vector<BagTopic> bag_topics(const rosbag::Bag& bag) {
  rosbag::View view(bag);
  std::vector<BagTopic> topics;
  for (const rosbag::ConnectionInfo* connection : view.getConnections()) {
    const bool known = std::any_of(topics.begin(), topics.end(),
                                   [&](const BagTopic& t) { return t.name == connection->topic; });
    if (!known) topics.push_back({connection->topic, connection->datatype});
  }
  return topics;
}

// "/camera/depth/image_raw" -> "/camera/depth/camera_info" (image_pipeline's convention).
std::string camera_info_topic(const std::string& image_topic) {
  const std::size_t slash = image_topic.rfind('/');
  return (slash == std::string::npos ? std::string() : image_topic.substr(0, slash + 1)) + "camera_info";
}

const BagTopic* find_topic(const std::vector<BagTopic>& topics, const std::string& name) {
  for (const BagTopic& topic : topics) {
    if (topic.name == name || (!name.empty() && name[0] != '/' && topic.name == "/" + name)) return &topic;
  }
  return nullptr;
}

bool is_depth_topic(const std::vector<BagTopic>& topics, const BagTopic& topic) {
  const BagTopic* info = find_topic(topics, camera_info_topic(topic.name));
  return topic.type == kImageType && info && info->type == kCameraInfoType;
}

std::string topic_list(const std::vector<BagTopic>& topics) {
  std::string list;
  for (const BagTopic& topic : topics) list += (list.empty() ? "" : ", ") + topic.name + " (" + topic.type + ")";
  return list.empty() ? "none" : list;
}

// The topic to read: `wanted`, or the first depth image topic, else the first PointCloud2.
BagTopic choose_topic(const std::vector<BagTopic>& topics, const std::string& wanted, const std::string& path) {
  if (wanted.empty()) {
    for (const BagTopic& topic : topics) {
      if (is_depth_topic(topics, topic)) return topic;
    }
    for (const BagTopic& topic : topics) {
      if (topic.type == kCloudType) return topic;
    }
    throw Error(path + " has no depth image topic (sensor_msgs/Image with a camera_info beside it) and no "
                "PointCloud2 topic; its topics: " + topic_list(topics));
  }
  const BagTopic* topic = find_topic(topics, wanted);
  if (!topic) throw Error(path + " has no topic " + wanted + "; its topics: " + topic_list(topics));
  if (topic->type == kImageType && !is_depth_topic(topics, *topic)) {
    throw Error(path + ": topic " + topic->name + " has no " + camera_info_topic(topic->name) +
                " (sensor_msgs/CameraInfo) beside it");
  }
  if (topic->type != kImageType && topic->type != kCloudType) {
    throw Error(path + ": topic " + topic->name + " carries " + topic->type + ", not " + kImageType + " or " +
                kCloudType);
  }
  return *topic;
}

}  // namespace

struct BagReader::State {
  rosbag::Bag bag;
  BagTopic topic;
  std::string info_topic;
  std::uint64_t count = 0;
  std::optional<rosbag::View> view;
  rosbag::View::iterator at;
  sensor_msgs::CameraInfo::ConstPtr info;  // the latest camera_info
};

BagReader::BagReader(const std::string& path, const std::string& topic) : state_(std::make_unique<State>()) {
  try {
    state_->bag.open(path, rosbag::bagmode::Read);
    state_->topic = choose_topic(bag_topics(state_->bag), topic, path);
    state_->count = rosbag::View(state_->bag, rosbag::TopicQuery(state_->topic.name)).size();
    std::vector<std::string> read{state_->topic.name};
    if (kind() == TopicKind::depth_image) {
      state_->info_topic = camera_info_topic(state_->topic.name);
      read.push_back(state_->info_topic);
      // An image that comes before any camera_info uses the first one.
      rosbag::View infos(state_->bag, rosbag::TopicQuery(state_->info_topic));
      if (infos.begin() != infos.end()) state_->info = infos.begin()->instantiate<sensor_msgs::CameraInfo>();
    }
    state_->view.emplace(state_->bag, rosbag::TopicQuery(read));
    state_->at = state_->view->begin();
  } catch (const rosbag::BagException& error) {
    throw Error("cannot read " + path + ": " + error.what());
  }
}

BagReader::~BagReader() = default;

const std::string& BagReader::topic() const { return state_->topic.name; }
TopicKind BagReader::kind() const {
  return state_->topic.type == kCloudType ? TopicKind::point_cloud : TopicKind::depth_image;
}
std::uint64_t BagReader::message_count() const { return state_->count; }

bool BagReader::next_depth(DepthMessage& out) {
  for (; state_->at != state_->view->end(); ++state_->at) {
    const rosbag::MessageInstance& message = *state_->at;
    if (message.getTopic() == state_->info_topic) {
      if (auto info = message.instantiate<sensor_msgs::CameraInfo>()) state_->info = info;
      continue;
    }
    const auto image = message.instantiate<sensor_msgs::Image>();
    if (!image) continue;
    if (!state_->info) throw Error("topic " + topic() + ": no camera_info on " + state_->info_topic);
    out = depth_from_ros(*image, *state_->info, topic());
    ++state_->at;
    return true;
  }
  return false;
}

bool BagReader::next_cloud(CloudMessage& out) {
  for (; state_->at != state_->view->end(); ++state_->at) {
    const auto cloud = state_->at->instantiate<sensor_msgs::PointCloud2>();
    if (!cloud) continue;
    out = cloud_from_ros(*cloud, topic());
    ++state_->at;
    return true;
  }
  return false;
}

struct BagWriter::State {
  std::string path;
  rosbag::Bag bag;
};

BagWriter::BagWriter(const std::string& path) : state_(std::make_unique<State>()) {
  state_->path = path;
  try {
    state_->bag.open(path, rosbag::bagmode::Write);
    state_->bag.setCompression(rosbag::compression::LZ4);
  } catch (const rosbag::BagException& error) {
    throw Error("cannot write " + path + ": " + error.what());
  }
}

BagWriter::~BagWriter() = default;

void BagWriter::write_depth(const DepthMessage& depth) {
  sensor_msgs::Image image;
  sensor_msgs::CameraInfo info;
  depth_to_ros(depth, image, info);
  // A bag's receive times must be at least ros::TIME_MIN; the header keeps the stamp.
  const ros::Time time = std::max(image.header.stamp, ros::TIME_MIN);
  try {
    state_->bag.write(kCameraInfoTopic, time, info);
    state_->bag.write(kDepthImageTopic, time, image);
  } catch (const rosbag::BagException& error) {
    throw Error("cannot write " + state_->path + ": " + error.what());
  }
}

void BagWriter::close() {
  try {
    state_->bag.close();
  } catch (const rosbag::BagException& error) {
    throw Error("cannot write " + state_->path + ": " + error.what());
  }
}

}  // namespace lccp::ros_bridge
