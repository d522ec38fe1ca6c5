// Point records to LabelledCloud, and text numbers, shared by the PCD and PLY
// readers; the labelled-cloud check shared by the writers.
#include "point_records.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstring>
#include <system_error>

#include "lccp/error.hpp"

namespace lccp::io_detail {
namespace {

const RecordField* find_field(const std::vector<RecordField>& fields, std::string_view wanted) {
  for (const RecordField& field : fields)
    if (field.name == wanted) return &field;
  return nullptr;
}

// One element of `field`: the readers only use single-element fields.
const RecordField* single(std::string_view name, const RecordField* field) {
  if (field && field->count != 1)
    fail(name, "field '" + one_line(field->name) + "' has " + std::to_string(field->count) + " elements (expected 1)");
  return field;
}

// Three floating-point fields (x y z or normal_x normal_y normal_z), all or none.
std::vector<const RecordField*> find_vector(std::string_view name, const std::vector<RecordField>& fields,
                                            const std::array<std::string_view, 3>& names) {
  std::vector<const RecordField*> found;
  for (const std::string_view wanted : names) {
    const RecordField* field = single(name, find_field(fields, wanted));
    if (!field) return {};
    if (field->type.kind != Kind::floating)
      fail(name, "field '" + std::string(wanted) + "' is not floating point");
    found.push_back(field);
  }
  return found;
}

std::vector<const RecordField*> find_color(std::string_view name, const std::vector<RecordField>& fields,
                                           bool channels) {
  const RecordField* packed = single(name, find_field(fields, "rgb"));
  if (!packed) packed = single(name, find_field(fields, "rgba"));
  if (packed) {
    if (packed->type.size != 4) fail(name, "colour field is not 4 bytes wide");
    return {packed};
  }
  if (!channels) return {};
  std::vector<const RecordField*> found;
  for (const std::string_view wanted : {"red", "green", "blue"}) {
    const RecordField* field = single(name, find_field(fields, wanted));
    if (!field) return {};
    if (field->type.size != 1 || field->type.kind == Kind::floating)
      fail(name, "colour property '" + std::string(wanted) + "' is not uchar");
    found.push_back(field);
  }
  return found;
}

template <typename T>
T load(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

float read_float(const std::uint8_t* p, Scalar type) {
  return type.size == 4 ? load<float>(p) : static_cast<float>(load<double>(p));
}

// An integer field, or the bits of a packed float rgb, as uint32 (wrapping
// like a C cast, as PCL's readers do).
std::uint32_t read_integer(const std::uint8_t* p, Scalar type) {
  const bool is_signed = type.kind == Kind::signed_int;
  switch (type.size) {
    case 1: return is_signed ? static_cast<std::uint32_t>(load<std::int8_t>(p)) : load<std::uint8_t>(p);
    case 2: return is_signed ? static_cast<std::uint32_t>(load<std::int16_t>(p)) : load<std::uint16_t>(p);
    case 4: return load<std::uint32_t>(p);
    default: return static_cast<std::uint32_t>(load<std::uint64_t>(p));
  }
}

// Point i's value of `field`.
const std::uint8_t* at(const Records& records, const RecordField* field, std::size_t i) {
  return records.data.data() + field->offset + i * field->stride;
}

Labels read_labels(const Records& records, std::size_t n, const RecordField* field) {
  Labels labels(n);
  for (std::size_t i = 0; i < n; ++i) labels[i] = read_integer(at(records, field, i), field->type);
  return labels;
}

std::vector<Eigen::Vector3f> read_vectors(const Records& records, std::size_t n,
                                          const std::vector<const RecordField*>& fields) {
  std::vector<Eigen::Vector3f> out(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = read_float(at(records, fields[k], i), fields[k]->type);
  return out;
}

// Packed rgb/rgba (alpha dropped) or red/green/blue channels, as 0x00RRGGBB.
std::vector<std::uint32_t> read_colors(const Records& records, std::size_t n,
                                       const std::vector<const RecordField*>& fields) {
  if (fields.empty()) return {};
  std::vector<std::uint32_t> colors(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (fields.size() == 1) {
      colors[i] = read_integer(at(records, fields[0], i), fields[0]->type) & 0xFFFFFFu;
    } else {
      colors[i] = std::uint32_t{*at(records, fields[0], i)} << 16 | std::uint32_t{*at(records, fields[1], i)} << 8 |
                  *at(records, fields[2], i);
    }
  }
  return colors;
}

// The whole word as a T (integer or floating point; "nan" and "inf" for the
// latter); false if it is not one or out of T's range.
template <typename T>
bool parse_number(std::string_view word, std::uint8_t* out) {
  T value{};
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc() || end != word.data() + word.size()) return false;
  std::memcpy(out, &value, sizeof value);
  return true;
}

}  // namespace

CloudLayout find_cloud_fields(std::string_view name, const std::vector<RecordField>& fields, bool channels) {
  CloudLayout layout;
  layout.xyz = find_vector(name, fields, {"x", "y", "z"});
  if (layout.xyz.empty()) fail(name, "no x/y/z fields");
  layout.normals = find_vector(name, fields, {"normal_x", "normal_y", "normal_z"});
  layout.color = find_color(name, fields, channels);
  layout.label = single(name, find_field(fields, "label"));
  if (layout.label && layout.label->type.kind == Kind::floating) fail(name, "field 'label' is not an integer type");
  layout.object = single(name, find_field(fields, "object"));
  if (layout.object && layout.object->type.kind == Kind::floating) fail(name, "field 'object' is not an integer type");
  return layout;
}

LabelledCloud to_labelled_cloud(const Records& records, const CloudLayout& layout) {
  const std::size_t n = std::size_t{records.width} * records.height;
  for (const RecordField& field : records.fields) {  // the readers' job; checked here once more
    const std::uint64_t end = field.offset + (n - 1) * field.stride + field.count * field.type.size;
    if (n == 0 || end > records.data.size()) throw Error("internal: point records out of bounds");
  }
  LabelledCloud out;
  out.cloud.width = records.width;
  out.cloud.height = records.height;
  out.cloud.points = read_vectors(records, n, layout.xyz);
  out.cloud.colors = read_colors(records, n, layout.color);
  if (!layout.normals.empty()) out.cloud.normals = read_vectors(records, n, layout.normals);
  if (layout.label) out.labels = read_labels(records, n, layout.label);
  if (layout.object) out.objects = read_labels(records, n, layout.object);
  return out;
}

bool store_text_value(std::string_view word, Scalar type, std::uint8_t* out) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-') word.remove_prefix(1);  // from_chars takes no '+'
  if (type.kind == Kind::floating)
    return type.size == 4 ? parse_number<float>(word, out) : parse_number<double>(word, out);
  if (type.kind == Kind::signed_int) {
    switch (type.size) {
      case 1: return parse_number<std::int8_t>(word, out);
      case 2: return parse_number<std::int16_t>(word, out);
      case 4: return parse_number<std::int32_t>(word, out);
      default: return parse_number<std::int64_t>(word, out);
    }
  }
  switch (type.size) {
    case 1: return parse_number<std::uint8_t>(word, out);
    case 2: return parse_number<std::uint16_t>(word, out);
    case 4: return parse_number<std::uint32_t>(word, out);
    default: return parse_number<std::uint64_t>(word, out);
  }
}

void fail(std::string_view name, const std::string& problem) {
  throw Error(std::string(name) + ": " + problem);
}

std::string one_line(std::string_view text) {
  std::string out(text.substr(0, 60));
  std::replace_if(out.begin(), out.end(), [](unsigned char c) { return c < 0x20 || c >= 0x7f; }, '?');
  return out;
}

std::string truncated(std::uint64_t have, std::uint64_t need, const char* unit) {
  return "truncated data (" + std::to_string(have) + " of " + std::to_string(need) + " " + unit + ")";
}

void check_labelled_cloud(const PointCloud& cloud, const Labels& labels, const Labels* objects) {
  if (labels.size() != cloud.size()) throw Error("labels and points differ in number");
  if (objects && objects->size() != cloud.size()) throw Error("objects and points differ in number");
  if (std::uint64_t{cloud.width} * cloud.height != cloud.size()) throw Error("width x height != number of points");
  if (cloud.has_colors() && cloud.colors.size() != cloud.size()) throw Error("colours and points differ in number");
  if (cloud.size() == 0) throw Error("no points to write");
}

}  // namespace lccp::io_detail
