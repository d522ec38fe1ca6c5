#pragma once
// Internal to src/io: fixed-size point records as the PCD and PLY readers
// decode them, their conversion into a LabelledCloud by field name, and the
// input check the labelled-cloud writers share.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lccp/io/cloud_io.hpp"

namespace lccp::io_detail {

enum class Kind : std::uint8_t { floating, signed_int, unsigned_int };

// One scalar type: PCD TYPE F/I/U with SIZE 1, 2, 4 or 8; PLY char .. double.
struct Scalar {
  Kind kind = Kind::floating;
  std::uint8_t size = 4;
};

// Point i's value of a field starts at data[offset + i x stride]: stride is
// the record size for interleaved data (PCD binary/ascii, PLY) and the
// field's own size for PCD binary_compressed's one array per field.
struct RecordField {
  std::string_view name;  // points into the parsed bytes
  Scalar type;
  std::uint64_t count = 1;  // elements
  std::uint64_t offset = 0;
  std::uint64_t stride = 0;
};

// width x height points, values in host byte order.
struct Records {
  std::uint32_t width = 0;
  std::uint32_t height = 1;
  std::vector<RecordField> fields;
  std::span<const std::uint8_t> data;
  std::vector<std::uint8_t> storage;  // owns `data` unless it points into the input
};

// Where the cloud's attributes are in a record; found before any data is
// decoded, so a file without x/y/z is rejected before anything is allocated.
struct CloudLayout {
  std::vector<const RecordField*> xyz;      // 3 or none
  std::vector<const RecordField*> normals;  // 3 or none
  std::vector<const RecordField*> color;    // none, 1 packed rgb/rgba, or red/green/blue
  const RecordField* label = nullptr;
  const RecordField* object = nullptr;  // a two-level result's objects (our writers' `object` field)
};

// The names PCL's PCDReader exposes: x y z, rgb or rgba, normal_x/y/z, label;
// and `object`, which our writers add after `label`.
// `channels` also accepts PLY's red/green/blue (uchar) for the colour.
CloudLayout find_cloud_fields(std::string_view name, const std::vector<RecordField>& fields, bool channels);

// Reads every record through `layout` (which must point into records.fields).
LabelledCloud to_labelled_cloud(const Records& records, const CloudLayout& layout);

// Parses one text number (ASCII PCD or PLY) as `type` into out[0, type.size).
// Returns false if the word is not a number of that type or out of its range.
bool store_text_value(std::string_view word, Scalar type, std::uint8_t* out);

[[noreturn]] void fail(std::string_view name, const std::string& problem);

// User-visible text from a file, kept on one short line.
std::string one_line(std::string_view text);

// "truncated data (HAVE of NEED UNIT)"
std::string truncated(std::uint64_t have, std::uint64_t need, const char* unit);

// Throws lccp::Error (one line, no path) if the labels, the objects (if
// given), colours or width x height do not match the points, or there are none.
void check_labelled_cloud(const PointCloud& cloud, const Labels& labels, const Labels* objects = nullptr);

}  // namespace lccp::io_detail
