// The per-frame segments document of lccp/io/segments_json.hpp, written by
// hand: RFC 8259's grammar for the few value kinds it needs (objects, arrays,
// numbers, fixed strings, null).
#include "lccp/io/segments_json.hpp"

#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>

#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"

namespace lccp {
namespace {

// Appends JSON text; keys and separators are added by the caller.
class JsonText {
 public:
  std::string& text() { return text_; }
  void raw(std::string_view part) { text_ += part; }
  void key(std::string_view name) {  // our keys need no escaping (RFC 8259 Sec. 7)
    text_ += '"';
    text_ += name;
    text_ += "\":";
  }
  void next(std::string_view name) {  // a key after another member
    text_ += ',';
    key(name);
  }
  void integer(std::uint64_t value) { text_ += std::to_string(value); }
  // RFC 8259 Sec. 6: "Numeric values that cannot be represented in the
  // grammar below (such as Infinity and NaN) are not permitted": null instead.
  // Otherwise the shortest form that reads back as the same float (C++17
  // std::to_chars); its output ("-0.25", "1e-05", "3e+20") is in the grammar.
  void number(float value) {
    if (!std::isfinite(value)) {
      text_ += "null";
      return;
    }
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
    if (ec != std::errc()) throw Error("internal: cannot format a float");
    text_.append(buffer, end);
  }
  void vector(const Eigen::Vector3f& v) {
    text_ += '[';
    for (int k = 0; k < 3; ++k) {
      if (k > 0) text_ += ',';
      number(v[k]);
    }
    text_ += ']';
  }
  // Each column of the matrix (one axis) as a row of the output.
  void axes(const Eigen::Matrix3f& m) {
    text_ += '[';
    for (int c = 0; c < 3; ++c) {
      if (c > 0) text_ += ',';
      vector(m.col(c));
    }
    text_ += ']';
  }
  void ids(const std::vector<std::uint32_t>& values) {
    text_ += '[';
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) text_ += ',';
      integer(values[i]);
    }
    text_ += ']';
  }

 private:
  std::string text_;
};

void write_adjacent(JsonText& json, const std::vector<Neighbour>& adjacent) {
  json.raw("[");
  for (std::size_t i = 0; i < adjacent.size(); ++i) {
    if (i > 0) json.raw(",");
    json.raw("{");
    json.key("id");
    json.integer(adjacent[i].id);
    json.next("boundary");
    json.raw(adjacent[i].boundary == Boundary::convex ? "\"convex\"" : "\"concave\"");
    json.raw("}");
  }
  json.raw("]");
}

void write_box(JsonText& json, const OrientedBox& box) {
  json.raw("{");
  json.key("center");
  json.vector(box.center);
  json.next("axes");
  json.axes(box.axes);
  json.next("extents");
  json.vector(box.extents);
  json.raw("}");
}

// The fields of one object or part, without the braces.
void write_geometry(JsonText& json, const SegmentGeometry& segment) {
  json.key("id");
  json.integer(segment.id);
  json.next("points");
  json.integer(segment.points);
  json.next("centroid");
  json.vector(segment.centroid);
  json.next("obb");
  write_box(json, segment.obb);
  json.next("principal_axes");
  json.axes(segment.principal_axes);
  json.next("principal_extents");
  json.vector(segment.principal_extents);
  json.next("mean_normal");
  json.vector(segment.mean_normal);
  json.next("grasp");
  json.raw(segment.grasp == Grasp::top ? "\"top\"" : "\"side\"");
  json.next("adjacent");
  write_adjacent(json, segment.adjacent);
}

void write_object(JsonText& json, const ObjectSegments& object) {
  json.raw("{");
  write_geometry(json, object.object);
  json.next("parts");
  json.raw("[");
  for (std::size_t i = 0; i < object.parts.size(); ++i) {
    json.raw(i > 0 ? ",{" : "{");
    write_geometry(json, object.parts[i]);
    json.raw("}");
  }
  json.raw("]}");
}

void write_support(JsonText& json, const SceneSegmentation& scene) {
  json.next("support_plane");
  if (!scene.support_plane) {
    json.raw("null");
    return;
  }
  json.raw("{");
  json.key("id");
  json.integer(scene.support_id);
  json.next("normal");
  json.vector(scene.support_plane->normal);
  json.next("d");
  json.number(scene.support_plane->d);
  json.raw("}");
}

}  // namespace

std::string encode_segments_json(std::uint64_t frame_index, std::uint64_t timestamp_us,
                                 const SceneSegmentation& scene) {
  JsonText json;
  json.raw("{");
  json.key("frame");
  json.integer(frame_index);
  json.next("timestamp_us");
  json.integer(timestamp_us);
  write_support(json, scene);
  json.next("objects");
  json.raw("[");
  for (std::size_t i = 0; i < scene.segments.size(); ++i) {
    if (i > 0) json.raw(",");
    write_object(json, scene.segments[i]);
  }
  json.raw("]");
  json.next("new_ids");
  json.ids(scene.new_ids);
  json.next("gone_ids");
  json.ids(scene.gone_ids);
  json.raw("}\n");
  return std::move(json.text());
}

void write_segments_json(const std::filesystem::path& path, std::uint64_t frame_index, std::uint64_t timestamp_us,
                         const SceneSegmentation& scene) {
  write_file_atomically(path, std::string_view(encode_segments_json(frame_index, timestamp_us, scene)));
}

}  // namespace lccp
