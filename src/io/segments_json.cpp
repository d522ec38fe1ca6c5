// The per-frame segments document of lccp/io/segments_json.hpp, built with
// nlohmann-json (https://json.nlohmann.me), members in the order they are added.
#include "lccp/io/segments_json.hpp"

#include <cmath>
#include <string_view>

#include <nlohmann/json.hpp>

#include "lccp/io/atomic_file.hpp"

namespace lccp {
namespace {

// Floats as floats, so a value is written as the shortest decimal that reads
// back as the same float.
using Json = nlohmann::basic_json<nlohmann::ordered_map, std::vector, std::string, bool, std::int64_t,
                                  std::uint64_t, float>;

// RFC 8259 Sec. 6: "Numeric values that cannot be represented in the grammar
// below (such as Infinity and NaN) are not permitted": null instead. A whole
// number is written as an integer ("1", where nlohmann writes a float as
// "1.0"), but -0 as a float ("-0.0"), so its sign reads back.
Json number(float value) {
  if (!std::isfinite(value)) return nullptr;
  const bool whole = std::trunc(value) == value && std::fabs(value) < 16777216.0f;  // 2^24: exact in a float
  if (whole && !(value == 0 && std::signbit(value))) return static_cast<std::int64_t>(value);
  return value;
}

Json vector(const Eigen::Vector3f& v) { return Json::array({number(v[0]), number(v[1]), number(v[2])}); }

// Each column of the matrix (one axis) as a row of the output.
Json axes(const Eigen::Matrix3f& m) { return Json::array({vector(m.col(0)), vector(m.col(1)), vector(m.col(2))}); }

Json adjacent(const std::vector<Neighbour>& neighbours) {
  Json list = Json::array();
  for (const Neighbour& n : neighbours) {
    list.push_back({{"id", n.id}, {"boundary", n.boundary == Boundary::convex ? "convex" : "concave"}});
  }
  return list;
}

Json geometry(const SegmentGeometry& segment) {
  return {{"id", segment.id},
          {"points", segment.points},
          {"centroid", vector(segment.centroid)},
          {"obb", {{"center", vector(segment.obb.center)}, {"axes", axes(segment.obb.axes)},
                   {"extents", vector(segment.obb.extents)}}},
          {"principal_axes", axes(segment.principal_axes)},
          {"principal_extents", vector(segment.principal_extents)},
          {"mean_normal", vector(segment.mean_normal)},
          {"grasp", segment.grasp == Grasp::top ? "top" : "side"},
          {"adjacent", adjacent(segment.adjacent)}};
}

Json object(const ObjectSegments& object) {
  Json document = geometry(object.object);
  Json& parts = document["parts"] = Json::array();
  for (const SegmentGeometry& part : object.parts) parts.push_back(geometry(part));
  return document;
}

Json support(const SceneSegmentation& scene) {
  if (!scene.support_plane) return nullptr;
  return {{"id", scene.support_id}, {"normal", vector(scene.support_plane->normal)},
          {"d", number(scene.support_plane->d)}, {"noise_m", number(scene.support_noise_m)}};
}

}  // namespace

std::string encode_segments_json(std::uint64_t frame_index, std::uint64_t timestamp_us,
                                 const SceneSegmentation& scene) {
  Json objects = Json::array();
  for (const ObjectSegments& o : scene.segments) objects.push_back(object(o));
  const Json document = {{"frame", frame_index},           {"timestamp_us", timestamp_us},
                         {"support_plane", support(scene)}, {"objects", std::move(objects)},
                         {"new_ids", scene.new_ids},        {"gone_ids", scene.gone_ids}};
  return document.dump() + "\n";
}

void write_segments_json(const std::filesystem::path& path, std::uint64_t frame_index, std::uint64_t timestamp_us,
                         const SceneSegmentation& scene) {
  write_file_atomically(path, std::string_view(encode_segments_json(frame_index, timestamp_us, scene)));
}

}  // namespace lccp
