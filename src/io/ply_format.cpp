// PLY reading and the labelled-PLY writer. The format is Greg Turk's "The PLY
// Polygon File Format" (paulbourke.net/dataformats/ply): a text header
// (`ply`, `format`, `comment` / `obj_info`, `element NAME COUNT`, `property
// TYPE NAME`, `property list COUNT_TYPE ITEM_TYPE NAME`, `end_header`), then
// the elements in header order, each element's properties in order; ascii as
// whitespace-separated numbers, binary as packed values in the stated byte
// order. The `vertex` element is read, every other one (faces, with lists) is
// parsed and skipped, except that a `camera` element's viewport gives an
// organized cloud's shape.
#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "point_records.hpp"

namespace lccp {
namespace {

using namespace io_detail;

enum class Format { ascii, little_endian, big_endian };

// Elements, and properties over all elements, in a header: far more than any
// real file has, few enough that the header's description stays small.
constexpr std::size_t kMaxDeclarations = 4096;

struct Property {
  std::string_view name;
  Scalar type;                        // the item type, for a list
  std::optional<Scalar> count_type;   // set for a list property
};

struct Element {
  std::string_view name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct PlyHeader {
  Format format = Format::ascii;
  std::vector<Element> elements;
  std::size_t properties = 0;   // over all elements
  std::size_t data_offset = 0;  // first byte after the end_header line
};

[[noreturn]] void not_ply(std::string_view name, const std::string& problem) {
  fail(name, "not a readable PLY point cloud (" + problem + ")");
}

std::optional<Scalar> scalar_type(std::string_view word) {
  if (word == "char" || word == "int8") return Scalar{Kind::signed_int, 1};
  if (word == "uchar" || word == "uint8") return Scalar{Kind::unsigned_int, 1};
  if (word == "short" || word == "int16") return Scalar{Kind::signed_int, 2};
  if (word == "ushort" || word == "uint16") return Scalar{Kind::unsigned_int, 2};
  if (word == "int" || word == "int32") return Scalar{Kind::signed_int, 4};
  if (word == "uint" || word == "uint32") return Scalar{Kind::unsigned_int, 4};
  if (word == "float" || word == "float32") return Scalar{Kind::floating, 4};
  if (word == "double" || word == "float64") return Scalar{Kind::floating, 8};
  return std::nullopt;
}

// The words of a header line; no keyword takes more than 5, so splitting
// stops at 6 (a long comment line must not become a huge vector).
std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> words;
  for (std::size_t pos = 0; words.size() < 6;) {
    const std::size_t start = line.find_first_not_of(" \t\r", pos);
    if (start == std::string_view::npos) break;
    pos = std::min(line.find_first_of(" \t\r", start), line.size());
    words.push_back(line.substr(start, pos - start));
  }
  return words;
}

Scalar need_type(std::string_view name, std::string_view word) {
  const std::optional<Scalar> type = scalar_type(word);
  if (!type) not_ply(name, "unknown property type '" + one_line(word) + "'");
  return *type;
}

// `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME`.
Property parse_property(std::string_view name, const std::vector<std::string_view>& words) {
  if (words.size() == 3) return {words[2], need_type(name, words[1]), std::nullopt};
  if (words.size() == 5 && words[1] == "list") {
    const Scalar count_type = need_type(name, words[2]);
    if (count_type.kind == Kind::floating) not_ply(name, "list count type is not an integer");
    return {words[4], need_type(name, words[3]), count_type};
  }
  not_ply(name, "bad property line");
}

Format parse_format(std::string_view name, const std::vector<std::string_view>& words) {
  if (words.size() != 3 || words[2] != "1.0") not_ply(name, "bad format line");
  if (words[1] == "ascii") return Format::ascii;
  if (words[1] == "binary_little_endian") return Format::little_endian;
  if (words[1] == "binary_big_endian") return Format::big_endian;
  not_ply(name, "unknown format '" + one_line(words[1]) + "'");
}

std::uint64_t parse_element_count(std::string_view name, std::string_view word) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc() || end != word.data() + word.size())
    not_ply(name, "bad element count '" + one_line(word) + "'");
  return value;
}

// Applies one header line after `ply`; returns true at end_header.
bool apply_header_line(std::string_view name, const std::vector<std::string_view>& words, bool& has_format,
                       PlyHeader& header) {
  const std::string_view key = words.empty() ? std::string_view() : words[0];
  if (key.empty() || key == "comment" || key == "obj_info") return false;
  if (key == "format") {
    if (has_format || !header.elements.empty()) not_ply(name, "misplaced format line");
    header.format = parse_format(name, words);
    has_format = true;
  } else if (key == "element") {
    if (words.size() != 3) not_ply(name, "bad element line");
    if (header.elements.size() == kMaxDeclarations) not_ply(name, "too many elements");
    header.elements.push_back({words[1], parse_element_count(name, words[2]), {}});
  } else if (key == "property") {
    if (header.elements.empty()) not_ply(name, "property before any element");
    if (++header.properties > kMaxDeclarations) not_ply(name, "too many properties");
    header.elements.back().properties.push_back(parse_property(name, words));
  } else if (key == "end_header" && words.size() == 1) {
    if (!has_format) not_ply(name, "no format line");
    return true;
  } else {
    not_ply(name, "unknown header line '" + one_line(key) + "'");
  }
  return false;
}

PlyHeader parse_header(std::string_view text, std::string_view name) {
  PlyHeader header;
  bool has_format = false;
  bool magic = false;
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) break;
    const std::vector<std::string_view> words = split(text.substr(pos, end - pos));
    pos = end + 1;
    if (!magic) {
      if (words.size() != 1 || words[0] != "ply") break;
      magic = true;
    } else if (apply_header_line(name, words, has_format, header)) {
      header.data_offset = pos;
      return header;
    }
  }
  not_ply(name, magic ? "truncated header, no end_header" : "no 'ply' line");
}

template <typename T>
T load(const std::uint8_t* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

// An integer value in host order as a whole number, or nothing if negative.
std::optional<std::uint64_t> whole_number(const std::uint8_t* bytes, Scalar type) {
  if (type.kind == Kind::unsigned_int) {
    switch (type.size) {
      case 1: return load<std::uint8_t>(bytes);
      case 2: return load<std::uint16_t>(bytes);
      case 4: return load<std::uint32_t>(bytes);
      default: return load<std::uint64_t>(bytes);
    }
  }
  std::int64_t value = 0;
  switch (type.size) {
    case 1: value = load<std::int8_t>(bytes); break;
    case 2: value = load<std::int16_t>(bytes); break;
    case 4: value = load<std::int32_t>(bytes); break;
    default: value = load<std::int64_t>(bytes); break;
  }
  if (value < 0) return std::nullopt;
  return static_cast<std::uint64_t>(value);
}

// Consumes values from the data section: binary in the file's byte order, or
// ascii numbers. Every read is bounds-checked and fails with "truncated".
class Reader {
 public:
  Reader(std::string_view name, std::span<const std::uint8_t> data, Format format)
      : name_(name), data_(data), format_(format) {}

  std::uint64_t remaining() const { return data_.size() - pos_; }
  bool ascii() const { return format_ == Format::ascii; }

  // One value of `type` into out[0, type.size), host byte order.
  void value(Scalar type, std::uint8_t* out) {
    if (ascii()) {
      const std::string_view word = next_word();
      if (!store_text_value(word, type, out)) fail(name_, "bad value '" + one_line(word) + "' in PLY data");
      return;
    }
    if (remaining() < type.size) cut();
    std::memcpy(out, data_.data() + pos_, type.size);
    pos_ += type.size;
    const bool big = format_ == Format::big_endian;
    if (big != (std::endian::native == std::endian::big)) std::reverse(out, out + type.size);
  }

  // A list's length: a whole number >= 0 of the (integer) count type.
  std::uint64_t list_length(Scalar type) {
    std::uint8_t bytes[8] = {};
    value(type, bytes);
    const std::optional<std::uint64_t> length = whole_number(bytes, type);
    if (!length) fail(name_, "negative list length in PLY data");
    return *length;
  }

  // Skips `count` values of `type`.
  void skip(Scalar type, std::uint64_t count) {
    if (!ascii()) {
      if (count > remaining() / type.size) cut();
      pos_ += count * type.size;
      return;
    }
    for (std::uint64_t k = 0; k < count; ++k) next_word();  // each word is >= 1 byte: bounded
  }

  [[noreturn]] void cut() const { fail(name_, "truncated PLY data"); }

 private:
  std::string_view next_word() {
    const auto space = [](std::uint8_t c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
    while (pos_ < data_.size() && space(data_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !space(data_[pos_])) ++pos_;
    if (start == pos_) cut();
    return {reinterpret_cast<const char*>(data_.data()) + start, pos_ - start};
  }

  std::string_view name_;
  std::span<const std::uint8_t> data_;
  Format format_;
  std::size_t pos_ = 0;
};

// The least bytes one element takes: its binary values (a list at least its
// length), or in ascii one character and a separator per value.
std::uint64_t min_element_bytes(const Element& element, bool ascii) {
  std::uint64_t bytes = 0;
  for (const Property& property : element.properties)
    bytes += ascii ? 2 : (property.count_type ? property.count_type->size : property.type.size);
  return bytes;
}

// Rejects a count the data cannot hold before anything is read or allocated.
void check_fits(const Reader& reader, const Element& element) {
  const std::uint64_t least = min_element_bytes(element, reader.ascii());
  const std::uint64_t room = reader.remaining() + (reader.ascii() ? 1 : 0);
  if (least != 0 && element.count > room / least) reader.cut();
}

void skip_element(Reader& reader, const Element& element) {
  check_fits(reader, element);
  if (element.properties.empty()) return;
  for (std::uint64_t i = 0; i < element.count; ++i) {  // bounded by check_fits: >= 1 byte each
    for (const Property& property : element.properties) {
      if (property.count_type) reader.skip(property.type, reader.list_length(*property.count_type));
      else reader.skip(property.type, 1);
    }
  }
}

// PLY's usual normal names, as PCL's PLYReader maps them.
std::string_view canonical_name(std::string_view name) {
  if (name == "nx") return "normal_x";
  if (name == "ny") return "normal_y";
  if (name == "nz") return "normal_z";
  return name;
}

// The vertex's scalar properties packed one after another; returns the bytes per vertex.
std::uint64_t vertex_fields(const Element& vertex, std::vector<RecordField>& fields) {
  std::uint64_t step = 0;
  for (const Property& property : vertex.properties) {
    if (property.count_type) continue;
    fields.push_back({canonical_name(property.name), property.type, 1, step, 0});
    step += property.type.size;
  }
  for (RecordField& field : fields) field.stride = step;
  return step;
}

// PCL's PLYWriter stores an organized cloud's width and height as
// `viewportx` / `viewporty` of a `camera` element, and PLYReader restores
// them (io/src/ply_io.cpp); read from the first camera record.
std::optional<std::array<std::uint64_t, 2>> read_viewport(Reader& reader, const Element& camera) {
  check_fits(reader, camera);
  std::optional<std::uint64_t> size[2];
  for (std::uint64_t i = 0; i < camera.count; ++i) {  // bounded by check_fits
    for (const Property& property : camera.properties) {
      if (property.count_type) {
        reader.skip(property.type, reader.list_length(*property.count_type));
        continue;
      }
      std::uint8_t bytes[8] = {};
      reader.value(property.type, bytes);
      const int axis = property.name == "viewportx" ? 0 : property.name == "viewporty" ? 1 : -1;
      if (i == 0 && axis >= 0 && property.type.kind != Kind::floating) size[axis] = whole_number(bytes, property.type);
    }
  }
  if (!size[0] || !size[1]) return std::nullopt;
  return std::array<std::uint64_t, 2>{*size[0], *size[1]};
}

void read_vertices(Reader& reader, const Element& vertex, std::uint64_t step, Records& records) {
  check_fits(reader, vertex);
  records.storage.assign(vertex.count * step, 0);
  std::uint8_t* record = records.storage.data();
  for (std::uint64_t i = 0; i < vertex.count; ++i, record += step) {
    std::size_t field = 0;
    for (const Property& property : vertex.properties) {
      if (property.count_type) reader.skip(property.type, reader.list_length(*property.count_type));
      else reader.value(property.type, record + records.fields[field++].offset);
    }
  }
  records.data = records.storage;
}

// ------------------------------------------------------------------ writing

// PCL's PLYWriter (io/src/ply_io.cpp, generateHeader and writeBinary) with
// its default use_camera = true writes every one of width x height points,
// NaN ones included, then an empty `face` element ("vtk requires face entry
// to load PLY") and a `camera` element whose viewportx/viewporty hold width
// and height; PLYReader restores the organized shape from them. Without the
// camera it would drop the NaN points and add a `range_grid` instead. These
// are the camera's properties in PCL's order.
constexpr const char* kCameraElement =
    "element face 0\nelement camera 1\n"
    "property float view_px\nproperty float view_py\nproperty float view_pz\n"
    "property float x_axisx\nproperty float x_axisy\nproperty float x_axisz\n"
    "property float y_axisx\nproperty float y_axisy\nproperty float y_axisz\n"
    "property float z_axisx\nproperty float z_axisy\nproperty float z_axisz\n"
    "property float focal\nproperty float scalex\nproperty float scaley\n"
    "property float centerx\nproperty float centery\n"
    "property int viewportx\nproperty int viewporty\nproperty float k1\nproperty float k2\n";

// Greg Turk's PLY format: a vertex element's properties in the order its
// records store them; `object` (uint) is one more property after `label`.
std::string labelled_ply_header(const PointCloud& cloud, bool objects) {
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment LCCP Stream labelled cloud\nelement vertex " +
                       std::to_string(cloud.size()) + "\nproperty float x\nproperty float y\nproperty float z\n";
  if (cloud.has_colors()) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header += "property uint label\n";
  if (objects) header += "property uint object\n";
  return header + kCameraElement + "end_header\n";
}

void put_le32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<std::uint8_t>(value >> shift));
}

void put_float(std::vector<std::uint8_t>& out, float value) { put_le32(out, std::bit_cast<std::uint32_t>(value)); }

// The camera record as PLYWriter::writeBinary fills it for the default
// origin and orientation: position 0, axes the identity matrix (row by row),
// focal, scale and centre 0, the viewport, k1 = k2 = 0.
void put_camera(std::vector<std::uint8_t>& out, const PointCloud& cloud) {
  for (int k = 0; k < 3; ++k) put_float(out, 0.0f);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) put_float(out, row == col ? 1.0f : 0.0f);
  for (int k = 0; k < 5; ++k) put_float(out, 0.0f);
  put_le32(out, cloud.width);
  put_le32(out, cloud.height);
  for (int k = 0; k < 2; ++k) put_float(out, 0.0f);
}

}  // namespace

std::vector<std::uint8_t> encode_labelled_ply(const PointCloud& cloud, const Labels& labels, const Labels* objects) {
  check_labelled_cloud(cloud, labels, objects);
  constexpr std::uint32_t kMaxInt = 0x7FFFFFFF;
  if (cloud.width > kMaxInt || cloud.height > kMaxInt)
    throw Error("width or height beyond 2^31 - 1 (a PLY camera viewport is an int)");
  const std::string header = labelled_ply_header(cloud, objects != nullptr);
  std::vector<std::uint8_t> out(header.begin(), header.end());
  const std::size_t step = (cloud.has_colors() ? 19 : 16) + (objects ? 4 : 0);
  out.reserve(header.size() + step * cloud.size() + 21 * 4);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int k = 0; k < 3; ++k) put_float(out, cloud.points[i][k]);
    if (cloud.has_colors())
      for (int shift = 16; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(cloud.colors[i] >> shift));
    put_le32(out, labels[i]);
    if (objects) put_le32(out, (*objects)[i]);
  }
  put_camera(out, cloud);
  return out;
}

LabelledCloud parse_ply(std::span<const std::uint8_t> bytes, std::string_view name, const ReadLimits& limits) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const PlyHeader header = parse_header(text, name);
  const auto vertex = std::find_if(header.elements.begin(), header.elements.end(),
                                   [](const Element& element) { return element.name == "vertex"; });
  if (vertex == header.elements.end()) not_ply(name, "no vertex element");
  Records records;
  const std::uint64_t step = vertex_fields(*vertex, records.fields);
  const CloudLayout layout = find_cloud_fields(name, records.fields, true);
  if (vertex->count == 0) fail(name, "no points");
  if (vertex->count > std::min<std::uint64_t>(limits.max_points, 0xFFFFFFFFu))
    fail(name, "too many points (" + std::to_string(vertex->count) + ", limit " + std::to_string(limits.max_points) +
                   ")");
  records.width = static_cast<std::uint32_t>(vertex->count);
  Reader reader(name, bytes.subspan(header.data_offset), header.format);
  std::optional<std::array<std::uint64_t, 2>> viewport;
  for (auto element = header.elements.begin(); element != header.elements.end(); ++element) {
    if (element == vertex) read_vertices(reader, *vertex, step, records);
    else if (element->name == "camera" && !viewport) viewport = read_viewport(reader, *element);
    else skip_element(reader, *element);
  }
  // Organized only if the viewport covers the vertices exactly (each factor < 2^32).
  if (viewport && (*viewport)[0] != 0 && (*viewport)[1] != 0 && (*viewport)[0] <= vertex->count &&
      (*viewport)[1] <= vertex->count && (*viewport)[0] * (*viewport)[1] == vertex->count) {
    records.width = static_cast<std::uint32_t>((*viewport)[0]);
    records.height = static_cast<std::uint32_t>((*viewport)[1]);
  }
  return to_labelled_cloud(records, layout);
}

}  // namespace lccp
