// PCD reading and the labelled-PCD writer. The format is PCL's "The PCD
// (Point Cloud Data) file format" (pointclouds.org documentation, PCD v0.7):
// a text header of keyword lines up to DATA, then the points. Facts about
// data layouts that the documentation leaves out are from PCL's
// io/src/pcd_io.cpp (PCDReader::readHeader, readBodyBinary, PCDWriter).
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lzf.hpp"
#include "point_records.hpp"

namespace lccp {
namespace {

using namespace io_detail;

constexpr std::uint64_t kMaxFields = 65536;
constexpr std::uint64_t kMaxPointBytes = std::uint64_t{1} << 24;  // keeps points x bytes far from overflow

struct PcdHeader {
  std::optional<std::vector<std::string_view>> fields, sizes, types, counts;  // words after the keyword
  std::optional<std::uint64_t> width, height, points;
  bool viewpoint = false;
  std::string_view data;        // ascii, binary or binary_compressed
  std::uint64_t data_offset = 0;  // first byte after the DATA line
};

// Words of a line, separated by spaces, tabs or carriage returns.
class Words {
 public:
  explicit Words(std::string_view line) : line_(line) {}
  // The next word, or an empty view at the end of the line.
  std::string_view next() {
    const std::size_t start = line_.find_first_not_of(" \t\r", pos_);
    if (start == std::string_view::npos) {
      pos_ = line_.size();
      return {};
    }
    pos_ = std::min(line_.find_first_of(" \t\r", start), line_.size());
    return line_.substr(start, pos_ - start);
  }

 private:
  std::string_view line_;
  std::size_t pos_ = 0;
};

[[noreturn]] void bad_header(std::string_view name, const std::string& problem) {
  fail(name, "bad PCD header (" + problem + ")");
}

// The remaining words of a header line, at most kMaxFields of them (a long
// line must not become a huge vector).
std::vector<std::string_view> rest_of(std::string_view name, std::string_view key, Words& words) {
  std::vector<std::string_view> out;
  for (std::string_view word = words.next(); !word.empty(); word = words.next()) {
    if (out.size() == kMaxFields)
      bad_header(name, "more than " + std::to_string(kMaxFields) + " words in " + std::string(key));
    out.push_back(word);
  }
  return out;
}

// A whole number >= 0 (WIDTH, HEIGHT, POINTS, SIZE, COUNT); "-1", "nan" or "1e3" are not.
std::uint64_t parse_count(std::string_view name, std::string_view key, std::string_view word) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (word.empty() || ec != std::errc() || end != word.data() + word.size())
    bad_header(name, "bad number '" + one_line(word) + "' in " + std::string(key));
  return value;
}

template <typename T>
void set_once(std::string_view name, std::string_view key, std::optional<T>& slot, T value) {
  if (slot) bad_header(name, std::string(key) + " given twice");
  slot = std::move(value);
}

// VIEWPOINT tx ty tz qw qx qy qz: seven finite numbers (not used otherwise).
void check_viewpoint(std::string_view name, const std::vector<std::string_view>& values) {
  if (values.size() != 7) bad_header(name, "VIEWPOINT needs 7 numbers");
  for (const std::string_view word : values) {
    double value = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || end != word.data() + word.size() || !std::isfinite(value))
      bad_header(name, "bad number '" + one_line(word) + "' in VIEWPOINT");
  }
}

// Applies one header line; returns false if its keyword is not a PCD keyword.
bool apply_header_line(std::string_view name, std::string_view key, Words& words, PcdHeader& header) {
  const auto single = [&] {
    const std::uint64_t value = parse_count(name, key, words.next());
    if (!words.next().empty()) bad_header(name, std::string(key) + " needs one number");
    return value;
  };
  if (key == "VERSION") return true;  // 0.5 .. 0.7 share the keywords read here
  if (key == "FIELDS" || key == "COLUMNS") set_once(name, "FIELDS", header.fields, rest_of(name, key, words));
  else if (key == "SIZE") set_once(name, key, header.sizes, rest_of(name, key, words));
  else if (key == "TYPE") set_once(name, key, header.types, rest_of(name, key, words));
  else if (key == "COUNT") set_once(name, key, header.counts, rest_of(name, key, words));
  else if (key == "WIDTH") set_once(name, key, header.width, single());
  else if (key == "HEIGHT") set_once(name, key, header.height, single());
  else if (key == "POINTS") set_once(name, key, header.points, single());
  else if (key == "VIEWPOINT") {
    if (header.viewpoint) bad_header(name, "VIEWPOINT given twice");
    check_viewpoint(name, rest_of(name, key, words));
    header.viewpoint = true;
  } else {
    return false;
  }
  return true;
}

// The header: keyword lines (and # comments) up to and including DATA. The
// data section is never searched for keywords.
PcdHeader parse_header(std::string_view text, std::string_view name) {
  PcdHeader header;
  bool known = false;  // saw at least one PCD keyword
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) break;  // an unterminated line cannot be DATA
    Words words(text.substr(pos, end - pos));
    pos = end + 1;
    const std::string_view key = words.next();
    if (key.empty() || key.front() == '#') continue;
    if (key == "DATA" && known) {
      header.data = words.next();
      if (!words.next().empty()) bad_header(name, "DATA needs one word");
      header.data_offset = pos;
      return header;
    }
    if (!apply_header_line(name, key, words, header)) {
      if (!known) break;
      bad_header(name, "unknown line '" + one_line(key) + "'");
    }
    known = true;
  }
  fail(name, known ? "truncated PCD header (no DATA line)" : "not a point cloud (no PCD header)");
}

Scalar parse_type(std::string_view name, std::string_view field, std::string_view type, std::uint64_t size) {
  const std::string where = " of field '" + one_line(field) + "'";
  if (size != 1 && size != 2 && size != 4 && size != 8) bad_header(name, "SIZE " + std::to_string(size) + where);
  const auto bytes = static_cast<std::uint8_t>(size);
  if (type == "F" && (size == 4 || size == 8)) return {Kind::floating, bytes};
  if (type == "I") return {Kind::signed_int, bytes};
  if (type == "U") return {Kind::unsigned_int, bytes};
  bad_header(name, "TYPE " + one_line(type) + " with SIZE " + std::to_string(size) + where);
}

// FIELDS with SIZE (default 4), TYPE (default F) and COUNT (default 1), laid
// out one point after another; returns the bytes per point.
std::uint64_t interleaved_fields(std::string_view name, const PcdHeader& header, std::vector<RecordField>& out) {
  if (!header.fields || header.fields->empty()) bad_header(name, "no FIELDS");
  const std::vector<std::string_view>& names = *header.fields;
  for (const auto* list : {&header.sizes, &header.types, &header.counts})
    if (*list && (*list)->size() != names.size()) bad_header(name, "SIZE, TYPE or COUNT does not match FIELDS");
  std::uint64_t step = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::uint64_t size = header.sizes ? parse_count(name, "SIZE", (*header.sizes)[i]) : 4;
    const std::uint64_t count = header.counts ? parse_count(name, "COUNT", (*header.counts)[i]) : 1;
    const Scalar type = parse_type(name, names[i], header.types ? (*header.types)[i] : "F", size);
    if (count == 0 || count > kMaxPointBytes)
      bad_header(name, "COUNT " + std::to_string(count) + " of field '" + one_line(names[i]) + "'");
    out.push_back({names[i], type, count, step, 0});
    step += size * count;
    if (step > kMaxPointBytes) bad_header(name, "points of more than " + std::to_string(kMaxPointBytes) + " bytes");
  }
  for (RecordField& field : out) field.stride = step;
  return step;
}

// WIDTH x HEIGHT = POINTS, with PCL's defaults: no WIDTH and HEIGHT means
// WIDTH = POINTS, HEIGHT = 1 (readHeader). Returns the number of points.
std::uint64_t dimensions(std::string_view name, const PcdHeader& header, const ReadLimits& limits, Records& records) {
  if (!header.points) bad_header(name, "no POINTS");
  const std::uint64_t points = *header.points;
  std::uint64_t width = header.width.value_or(0);
  const std::uint64_t height = header.height.value_or(1);
  if (!header.height && width == 0) width = points;
  if (header.height && !header.width && points != 0) bad_header(name, "HEIGHT without WIDTH");
  constexpr std::uint64_t kMax = 0xFFFFFFFFu;
  if (points > kMax || width > kMax || height > kMax) bad_header(name, "more than 2^32 - 1 points, rows or columns");
  if (width * height != points)  // no overflow: both < 2^32
    bad_header(name, "WIDTH x HEIGHT = " + std::to_string(width) + " x " + std::to_string(height) +
                         " != POINTS " + std::to_string(points));
  if (points == 0) fail(name, "no points");
  if (points > limits.max_points)
    fail(name, "too many points (" + std::to_string(points) + ", limit " + std::to_string(limits.max_points) + ")");
  records.width = static_cast<std::uint32_t>(width);
  records.height = static_cast<std::uint32_t>(height);
  return points;
}

// DATA binary: points one after another, PCL's in-memory layout (host order).
void decode_binary(std::string_view name, std::span<const std::uint8_t> data, std::uint64_t points,
                   std::uint64_t step, Records& records) {
  const std::uint64_t need = points * step;
  if (data.size() < need) fail(name, truncated(data.size(), need, "bytes"));
  records.data = data.first(need);  // PCL pads the file after the data
}

// DATA binary_compressed (PCDWriter::writeBinaryCompressed): the LZF data
// expands to one array per field, in FIELDS order, `_` padding fields left
// out (they are not stored). Lays the fields out so; returns the raw size.
std::uint64_t planar_fields(std::vector<RecordField>& fields, std::uint64_t points) {
  std::erase_if(fields, [](const RecordField& field) { return field.name == "_"; });
  std::uint64_t raw = 0;
  for (RecordField& field : fields) {
    field.offset = raw;
    field.stride = field.count * field.type.size;
    raw += points * field.stride;
  }
  return raw;
}

// uint32 compressed size, uint32 raw size, then the LZF stream.
void decode_compressed(std::string_view name, std::span<const std::uint8_t> data, std::uint64_t raw_expected,
                       Records& records) {
  if (data.size() < 8) fail(name, truncated(data.size(), 8, "bytes"));
  std::uint32_t sizes[2];
  std::memcpy(sizes, data.data(), sizeof sizes);
  const std::uint64_t compressed = sizes[0], raw = sizes[1];
  if (data.size() - 8 < compressed) fail(name, truncated(data.size(), 8 + compressed, "bytes"));
  if (raw != raw_expected)
    fail(name, "corrupt compressed data (raw size " + std::to_string(raw) + ", POINTS x point size is " +
                   std::to_string(raw_expected) + ")");
  if (raw > compressed * kLzfMaxRatio)
    fail(name, "corrupt compressed data (" + std::to_string(compressed) + " bytes cannot expand to " +
                   std::to_string(raw) + ")");
  records.storage.resize(raw);
  if (const char* problem = lzf_decompress(data.subspan(8, compressed), records.storage))
    fail(name, std::string("corrupt compressed data (") + problem + ")");
  records.data = records.storage;
}

// One ASCII point line: every element of every field (`_` padding skipped).
void decode_ascii_line(std::string_view name, std::string_view line, std::uint64_t index, const Records& records,
                       std::uint8_t* record) {
  Words words(line);
  const auto malformed = [&] { fail(name, "truncated or malformed data (point " + std::to_string(index + 1) + ")"); };
  for (const RecordField& field : records.fields) {
    for (std::uint64_t c = 0; c < field.count; ++c) {
      const std::string_view word = words.next();
      if (word.empty()) malformed();
      if (field.name == "_") continue;
      if (!store_text_value(word, field.type, record + field.offset + c * field.type.size))
        fail(name, "bad value '" + one_line(word) + "' for field '" + one_line(field.name) + "' (point " +
                       std::to_string(index + 1) + ")");
    }
  }
  if (!words.next().empty()) malformed();
}

// DATA ascii: one line per point, empty lines skipped (readBodyASCII).
void decode_ascii(std::string_view name, std::string_view text, std::uint64_t points, std::uint64_t step,
                  Records& records) {
  std::uint64_t words = 0;
  for (const RecordField& field : records.fields) words += field.count;
  if (points * words * 2 > text.size() + 1)  // a value is >= 1 character and a separator
    fail(name, "truncated data (" + std::to_string(text.size()) + " bytes cannot hold " + std::to_string(points) +
                   " points)");
  records.storage.assign(points * step, 0);
  std::uint64_t read = 0;
  for (std::size_t pos = 0; read < points && pos < text.size();) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    decode_ascii_line(name, line, read, records, records.storage.data() + read * step);
    ++read;
  }
  if (read < points) fail(name, truncated(read, points, "points"));
  records.data = records.storage;
}

// ------------------------------------------------------------------ writing

// The fields of a labelled PCD: x y z [rgb] label [object], 4 bytes each.
struct PcdColumns {
  const PointCloud& cloud;
  const Labels& labels;
  const Labels* objects;  // null: no object field

  std::size_t count() const { return (cloud.has_colors() ? 5 : 4) + (objects ? 1 : 0); }
};

// The header PCL's PCDWriter::generateHeaderBinary (and ...BinaryCompressed,
// the same lines) writes for these fields, up to and including POINTS: rgb is
// a float field holding 0xAARRGGBB with alpha 255, the bytes of PCL's
// PointXYZRGB; label and object are uint32 (TYPE U, SIZE 4), as PCL's
// PointXYZRGBL label.
std::string labelled_pcd_header(const PcdColumns& columns) {
  const PointCloud& cloud = columns.cloud;
  std::string fields = "x y z", types = "F F F";
  if (cloud.has_colors()) fields += " rgb", types += " F";
  fields += " label", types += " U";
  if (columns.objects) fields += " object", types += " U";
  std::string sizes = "4", counts = "1";
  for (std::size_t k = 1; k < columns.count(); ++k) sizes += " 4", counts += " 1";
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes +
         "\nTYPE " + types + "\nCOUNT " + counts + "\nWIDTH " + std::to_string(cloud.width) + "\nHEIGHT " +
         std::to_string(cloud.height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(cloud.size()) + "\n";
}

template <typename T>
void append(std::vector<std::uint8_t>& out, T value) {
  std::uint8_t bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);
  out.insert(out.end(), bytes, bytes + sizeof value);
}

std::uint32_t packed_rgb(const PointCloud& cloud, std::size_t i) { return 0xFF000000u | cloud.colors[i]; }

// DATA binary: x y z [rgb] label [object] of each point in turn (host byte
// order, as PCL).
void append_binary(const PcdColumns& columns, std::vector<std::uint8_t>& out) {
  const PointCloud& cloud = columns.cloud;
  out.reserve(out.size() + 4 * columns.count() * cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int k = 0; k < 3; ++k) append(out, cloud.points[i][k]);
    if (cloud.has_colors()) append(out, packed_rgb(cloud, i));
    append(out, columns.labels[i]);
    if (columns.objects) append(out, (*columns.objects)[i]);
  }
}

// PCDWriter::writeBinaryCompressed refuses data whose size x 3/2 does not
// fit its uint32 sizes (io/src/pcd_io.cpp).
constexpr std::uint64_t kMaxCompressedRaw = std::uint64_t{0xFFFFFFFFu} * 2 / 3;

// The fields as writeBinaryCompressed lays them out before compressing: one
// array per field in FIELDS order, all x, then all y, z, [rgb,] label[, object].
std::vector<std::uint8_t> field_arrays(const PcdColumns& columns) {
  const PointCloud& cloud = columns.cloud;
  const std::size_t n = cloud.size();
  std::vector<std::uint8_t> raw(columns.count() * 4 * n);
  std::uint8_t* out = raw.data();
  const auto put = [&out](auto value) {
    static_assert(sizeof value == 4);
    std::memcpy(out, &value, 4);
    out += 4;
  };
  for (int k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < n; ++i) put(cloud.points[i][k]);
  if (cloud.has_colors())
    for (std::size_t i = 0; i < n; ++i) put(packed_rgb(cloud, i));
  for (std::size_t i = 0; i < n; ++i) put(columns.labels[i]);
  if (columns.objects)
    for (std::size_t i = 0; i < n; ++i) put((*columns.objects)[i]);
  return raw;
}

// DATA binary_compressed: uint32 compressed size, uint32 raw size (host
// order), then the LZF stream of field_arrays.
void append_compressed(const PcdColumns& columns, std::vector<std::uint8_t>& out) {
  const std::uint64_t raw_size = std::uint64_t{4} * columns.count() * columns.cloud.size();
  if (raw_size > kMaxCompressedRaw)
    throw Error("too many points for a binary_compressed PCD (" + std::to_string(raw_size) +
                " bytes of data, PCL's limit is " + std::to_string(kMaxCompressedRaw) + ")");
  const std::vector<std::uint8_t> lzf = lzf_compress(field_arrays(columns));
  append(out, static_cast<std::uint32_t>(lzf.size()));  // <= raw x 33/32 + 1: fits
  append(out, static_cast<std::uint32_t>(raw_size));
  out.insert(out.end(), lzf.begin(), lzf.end());
}

}  // namespace

std::vector<std::uint8_t> encode_labelled_pcd(const PointCloud& cloud, const Labels& labels, PcdEncoding encoding,
                                              const Labels* objects) {
  check_labelled_cloud(cloud, labels, objects);
  const PcdColumns columns{cloud, labels, objects};
  const bool compressed = encoding == PcdEncoding::binary_compressed;
  const std::string header = labelled_pcd_header(columns) + (compressed ? "DATA binary_compressed\n" : "DATA binary\n");
  std::vector<std::uint8_t> out(header.begin(), header.end());
  if (compressed) append_compressed(columns, out);
  else append_binary(columns, out);
  return out;
}

LabelledCloud parse_pcd(std::span<const std::uint8_t> bytes, std::string_view name, const ReadLimits& limits) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const PcdHeader header = parse_header(text, name);
  if (header.data != "ascii" && header.data != "binary" && header.data != "binary_compressed")
    bad_header(name, "unknown DATA '" + one_line(header.data) + "'");
  Records records;
  const std::uint64_t step = interleaved_fields(name, header, records.fields);
  const std::uint64_t points = dimensions(name, header, limits, records);
  const bool compressed = header.data == "binary_compressed";
  const std::uint64_t raw = compressed ? planar_fields(records.fields, points) : 0;
  const CloudLayout layout = find_cloud_fields(name, records.fields, false);
  const std::span<const std::uint8_t> data = bytes.subspan(header.data_offset);
  if (compressed) decode_compressed(name, data, raw, records);
  if (header.data == "binary") decode_binary(name, data, points, step, records);
  if (header.data == "ascii") decode_ascii(name, text.substr(header.data_offset), points, step, records);
  return to_labelled_cloud(records, layout);
}

}  // namespace lccp
