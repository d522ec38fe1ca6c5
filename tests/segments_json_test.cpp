// Tests for the per-frame segments document of lccp/io/segments_json.hpp: the
// exact text of a small scene, the schema of a two-level scene read back by a
// strict RFC 8259 parser, null for a missing plane and for NaN and infinity,
// floats that read back exactly, and the atomic writer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "expect_error.hpp"
#include "test_files.hpp"
#include "lccp/io/segments_json.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

// ------------------------------------------------ a strict little JSON reader

// A parsed JSON value (RFC 8259): what the tests need to look at.
struct Json {
  enum class Type { null, boolean, number, string, array, object } type = Type::null;
  double number = 0;
  std::string text;                                   // a string's value, or a number's own digits
  std::vector<Json> items;                            // array elements
  // Object members in document order, names and values apart: a vector of an
  // incomplete type is allowed (C++17), a vector of pair<string, Json> is not.
  std::vector<std::string> names;
  std::vector<Json> values;

  const Json& operator[](std::string_view key) const {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == key) return values[i];
    ADD_FAILURE() << "no member " << key;
    static const Json missing;
    return missing;
  }
  const Json& operator[](std::size_t i) const { return items.at(i); }
  std::vector<std::string> keys() const { return names; }
  bool is_null() const { return type == Type::null; }
};

// Recursive descent over RFC 8259's grammar; no whitespace is accepted
// (the document is compact) and strings are plain (our keys need no escapes).
class JsonReader {
 public:
  explicit JsonReader(std::string_view text) : text_(text) {}

  // The one value of the text; fails the test on anything else.
  Json document() {
    Json value = parse_value();
    if (pos_ != text_.size()) ADD_FAILURE() << "text after the value at " << pos_;
    return value;
  }

 private:
  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  bool take(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }
  void expect(char c) {
    if (!take(std::string_view(&c, 1))) {
      ADD_FAILURE() << "expected '" << c << "' at " << pos_ << ": " << text_.substr(pos_, 40);
      pos_ = text_.size();
    }
  }

  Json parse_value() {
    Json value;
    if (take("null")) return value;
    if (take("true") || take("false")) {
      value.type = Json::Type::boolean;
      return value;
    }
    if (peek() == '"') return parse_string();
    if (peek() == '[') return parse_array();
    if (peek() == '{') return parse_object();
    return parse_number();
  }

  Json parse_string() {
    Json value;
    value.type = Json::Type::string;
    expect('"');
    while (pos_ < text_.size() && text_[pos_] != '"') {
      EXPECT_GE(static_cast<unsigned char>(text_[pos_]), 0x20) << "control character in a string";
      EXPECT_NE(text_[pos_], '\\') << "an escape (not expected in our documents)";
      value.text += text_[pos_++];
    }
    expect('"');
    return value;
  }

  Json parse_array() {
    Json value;
    value.type = Json::Type::array;
    expect('[');
    if (take("]")) return value;
    do value.items.push_back(parse_value());
    while (take(","));
    expect(']');
    return value;
  }

  Json parse_object() {
    Json value;
    value.type = Json::Type::object;
    expect('{');
    if (take("}")) return value;
    do {
      std::string key = parse_string().text;
      expect(':');
      value.names.push_back(std::move(key));
      value.values.push_back(parse_value());
    } while (take(","));
    expect('}');
    return value;
  }

  void digits(bool at_least_one) {
    const std::size_t start = pos_;
    while (peek() >= '0' && peek() <= '9') ++pos_;
    if (at_least_one && pos_ == start) ADD_FAILURE() << "digit expected at " << pos_;
  }

  // number = [ minus ] int [ frac ] [ exp ]; int = zero / ( digit1-9 *DIGIT )
  Json parse_number() {
    const std::size_t start = pos_;
    take("-");
    if (!take("0")) digits(true);
    if (take(".")) digits(true);
    if (take("e") || take("E")) {
      if (!take("+")) take("-");
      digits(true);
    }
    Json value;
    value.type = Json::Type::number;
    value.text = std::string(text_.substr(start, pos_ - start));
    value.number = std::strtod(value.text.c_str(), nullptr);
    return value;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

Json parse(const std::string& text) {
  EXPECT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "a newline at the end";
  const std::string_view body(text.data(), text.empty() ? 0 : text.size() - 1);
  EXPECT_EQ(body.find_first_of(" \t\r\n"), std::string_view::npos) << "compact: no whitespace";
  return JsonReader(body).document();
}

// ------------------------------------------------------------- the scenes

SegmentGeometry geometry(std::uint32_t id, float offset) {
  SegmentGeometry g;
  g.id = id;
  g.points = 1000 + id;
  g.centroid = {0.25f + offset, -0.5f, 1.125f};
  g.obb.center = {0.25f + offset, -0.5f, 1.0f};
  g.obb.axes.col(0) = Eigen::Vector3f(0, 1, 0);  // columns: x -> row 0 of "axes"
  g.obb.axes.col(1) = Eigen::Vector3f(-1, 0, 0);
  g.obb.axes.col(2) = Eigen::Vector3f(0, 0, 1);
  g.obb.extents = {0.125f, 0.0625f, 0.5f};
  g.principal_axes.col(0) = Eigen::Vector3f(0, 0, 1);
  g.principal_axes.col(1) = Eigen::Vector3f(1, 0, 0);
  g.principal_axes.col(2) = Eigen::Vector3f(0, 1, 0);
  g.principal_extents = {0.5f, 0.125f, 0.0625f};
  g.mean_normal = {0, -1, 0};
  g.grasp = id % 2 == 0 ? Grasp::top : Grasp::side;
  return g;
}

// One object (id 2) with two parts (3, 4) on a support plane (id 1).
SceneSegmentation two_level_scene() {
  SceneSegmentation scene;
  scene.support_plane = Plane{Eigen::Vector3f(0, -1, 0), 0.75f};
  scene.support_id = 1;
  scene.support_noise_m = 0.0015f;
  ObjectSegments object;
  object.object = geometry(2, 0);
  object.object.adjacent = {{1, Boundary::concave}};
  object.parts = {geometry(3, 0.5f), geometry(4, -0.5f)};
  object.parts[0].adjacent = {{4, Boundary::convex}};
  object.parts[1].adjacent = {{3, Boundary::convex}};
  scene.segments.push_back(object);
  scene.new_ids = {3, 4};
  scene.gone_ids = {5};
  return scene;
}

// ------------------------------------------------------------------ tests

void expect_vector(const Json& value, const Eigen::Vector3f& expected, const std::string& what) {
  ASSERT_EQ(value.type, Json::Type::array) << what;
  ASSERT_EQ(value.items.size(), 3u) << what;
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(value[k].type, Json::Type::number) << what;
    EXPECT_EQ(static_cast<float>(value[k].number), expected[k]) << what << "[" << k << "]";
  }
}

void expect_axes(const Json& value, const Eigen::Matrix3f& expected, const std::string& what) {
  ASSERT_EQ(value.items.size(), 3u) << what;
  for (int axis = 0; axis < 3; ++axis)  // row `axis` of the output: column `axis` of the matrix
    expect_vector(value[axis], expected.col(axis), what + "[" + std::to_string(axis) + "]");
}

void expect_segment(const Json& value, const SegmentGeometry& g, bool with_parts) {
  SCOPED_TRACE("segment " + std::to_string(g.id));
  std::vector<std::string> keys = {"id",         "points",           "centroid",          "obb",
                                   "principal_axes", "principal_extents", "mean_normal", "grasp", "adjacent"};
  if (with_parts) keys.push_back("parts");
  EXPECT_EQ(value.keys(), keys);
  EXPECT_EQ(value["id"].text, std::to_string(g.id));
  EXPECT_EQ(value["points"].text, std::to_string(g.points));
  expect_vector(value["centroid"], g.centroid, "centroid");
  EXPECT_EQ(value["obb"].keys(), (std::vector<std::string>{"center", "axes", "extents"}));
  expect_vector(value["obb"]["center"], g.obb.center, "obb.center");
  expect_axes(value["obb"]["axes"], g.obb.axes, "obb.axes");
  expect_vector(value["obb"]["extents"], g.obb.extents, "obb.extents");
  expect_axes(value["principal_axes"], g.principal_axes, "principal_axes");
  expect_vector(value["principal_extents"], g.principal_extents, "principal_extents");
  expect_vector(value["mean_normal"], g.mean_normal, "mean_normal");
  EXPECT_EQ(value["grasp"].type, Json::Type::string);
  EXPECT_EQ(value["grasp"].text, g.grasp == Grasp::top ? "top" : "side");
  ASSERT_EQ(value["adjacent"].items.size(), g.adjacent.size());
  for (std::size_t i = 0; i < g.adjacent.size(); ++i) {
    const Json& neighbour = value["adjacent"][i];
    EXPECT_EQ(neighbour.keys(), (std::vector<std::string>{"id", "boundary"}));
    EXPECT_EQ(neighbour["id"].text, std::to_string(g.adjacent[i].id));
    EXPECT_EQ(neighbour["boundary"].text, g.adjacent[i].boundary == Boundary::convex ? "convex" : "concave");
  }
}

TEST(SegmentsJson, TwoLevelSceneFollowsTheSchema) {
  const SceneSegmentation scene = two_level_scene();
  const std::string text = encode_segments_json(42, 1234567890123ull, scene);
  const Json doc = parse(text);
  ASSERT_EQ(doc.type, Json::Type::object);
  EXPECT_EQ(doc.keys(),
            (std::vector<std::string>{"frame", "timestamp_us", "support_plane", "objects", "new_ids", "gone_ids"}));
  EXPECT_EQ(doc["frame"].text, "42");
  EXPECT_EQ(doc["timestamp_us"].text, "1234567890123");
  EXPECT_EQ(doc["support_plane"].keys(), (std::vector<std::string>{"id", "normal", "d", "noise_m"}));
  EXPECT_EQ(doc["support_plane"]["id"].text, "1");
  expect_vector(doc["support_plane"]["normal"], Eigen::Vector3f(0, -1, 0), "normal");
  EXPECT_EQ(doc["support_plane"]["d"].text, "0.75");
  EXPECT_EQ(doc["support_plane"]["noise_m"].text, "0.0015");
  ASSERT_EQ(doc["objects"].items.size(), 1u);
  const Json& object = doc["objects"][0];
  expect_segment(object, scene.segments[0].object, true);
  ASSERT_EQ(object["parts"].items.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) expect_segment(object["parts"][k], scene.segments[0].parts[k], false);
  ASSERT_EQ(doc["new_ids"].items.size(), 2u);
  EXPECT_EQ(doc["new_ids"][0].text, "3");
  EXPECT_EQ(doc["new_ids"][1].text, "4");
  ASSERT_EQ(doc["gone_ids"].items.size(), 1u);
  EXPECT_EQ(doc["gone_ids"][0].text, "5");
  EXPECT_EQ(encode_segments_json(42, 1234567890123ull, two_level_scene()), text);  // deterministic
}

TEST(SegmentsJson, ExactTextOfAOneLevelSceneWithoutSupport) {
  SceneSegmentation scene;
  scene.segments.push_back({geometry(1, 0), {}});
  scene.segments[0].object.adjacent = {{2, Boundary::convex}};
  scene.new_ids = {1};
  const std::string box = R"("obb":{"center":[0.25,-0.5,1],"axes":[[0,1,0],[-1,0,0],[0,0,1]],)"
                          R"("extents":[0.125,0.0625,0.5]},)";
  const std::string expected =
      R"({"frame":0,"timestamp_us":7,"support_plane":null,"objects":[{"id":1,"points":1001,)"
      R"("centroid":[0.25,-0.5,1.125],)" +
      box +
      R"("principal_axes":[[0,0,1],[1,0,0],[0,1,0]],"principal_extents":[0.5,0.125,0.0625],)"
      R"("mean_normal":[0,-1,0],"grasp":"side","adjacent":[{"id":2,"boundary":"convex"}],"parts":[]}],)"
      R"("new_ids":[1],"gone_ids":[]})"
      "\n";
  EXPECT_EQ(encode_segments_json(0, 7, scene), expected);
  EXPECT_EQ(encode_segments_json(0, 7, SceneSegmentation{}),
            "{\"frame\":0,\"timestamp_us\":7,\"support_plane\":null,\"objects\":[],\"new_ids\":[],\"gone_ids\":[]}\n");
}

TEST(SegmentsJson, NoSupportPlaneIsNull) {
  SceneSegmentation scene = two_level_scene();
  scene.support_plane.reset();
  scene.support_id = 0;
  const Json doc = parse(encode_segments_json(1, 2, scene));
  EXPECT_TRUE(doc["support_plane"].is_null());
  EXPECT_EQ(doc["objects"].items.size(), 1u);
}

TEST(SegmentsJson, NonFiniteNumbersAreWrittenAsNull) {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  SceneSegmentation scene = two_level_scene();
  scene.support_plane->d = kNaN;
  scene.segments[0].object.centroid = {kNaN, 0.5f, -kInf};
  scene.segments[0].parts[1].obb.axes(2, 1) = kInf;
  const std::string text = encode_segments_json(3, 4, scene);
  for (const char* word : {"nan", "NaN", "inf", "Inf"}) EXPECT_EQ(text.find(word), std::string::npos) << word;
  const Json doc = parse(text);
  EXPECT_TRUE(doc["support_plane"]["d"].is_null());
  const Json& centroid = doc["objects"][0]["centroid"];
  EXPECT_TRUE(centroid[0].is_null());
  EXPECT_EQ(centroid[1].text, "0.5");
  EXPECT_TRUE(centroid[2].is_null());
  const Json& axes = doc["objects"][0]["parts"][1]["obb"]["axes"];
  EXPECT_TRUE(axes[1][2].is_null());  // matrix (row 2, column 1): axis 1, component 2
  EXPECT_EQ(axes[1][0].text, "-1");
}

TEST(SegmentsJson, FloatsReadBackExactly) {
  // Shortest round-trip digits: millimetres at metres (and far finer) survive.
  const std::vector<float> values = {0.1f,   1.2345678f, -3.4e-5f, 1e20f,  -0.0f, 4.0012345f,
                                     1e-38f, 3.4028235e38f, 0.001f, 2.5e-3f, 12345.678f};
  for (const float value : values) {
    SceneSegmentation scene = two_level_scene();
    scene.support_plane->d = value;
    const Json d = parse(encode_segments_json(0, 0, scene))["support_plane"]["d"];
    ASSERT_EQ(d.type, Json::Type::number) << value;
    EXPECT_EQ(std::strtof(d.text.c_str(), nullptr), value) << d.text;
    EXPECT_EQ(std::signbit(std::strtof(d.text.c_str(), nullptr)), std::signbit(value)) << d.text;
    EXPECT_LE(d.text.size(), 15u) << d.text;  // at most 9 significant digits, sign, point, exponent
  }
}

TEST(SegmentsJson, WriterIsAtomicAndWritesTheDocument) {
  const fs::path dir = test::scratch_dir("lccp_segments_json");
  const SceneSegmentation scene = two_level_scene();
  write_segments_json(dir / "frame.segments.json", 9, 10, scene);
  EXPECT_EQ(test::read_bytes(dir / "frame.segments.json"), encode_segments_json(9, 10, scene));
  test::expect_lccp_error([&] { write_segments_json(dir / "missing" / "x.json", 9, 10, scene); },
                          {"x.json", "does not exist"});
  EXPECT_FALSE(fs::exists(dir / "missing"));
}

}  // namespace
}  // namespace lccp
