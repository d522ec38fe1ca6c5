// Point cloud input (PCD, PLY through PCL io) and labelled outputs (PCD, PNG).
#include "lccp/io/cloud_io.hpp"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "lccp/error.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, const std::string& problem) {
  throw Error(path.string() + ": " + problem);
}

// Keeps user-visible text on one short line.
std::string one_line(std::string_view text) {
  std::string out(text.substr(0, 60));
  std::replace_if(out.begin(), out.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; }, '?');
  return out;
}

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Silences PCL's console output for the lifetime of the guard. PCL keeps the
// verbosity in a process-wide variable, so the old level is restored after.
class QuietPcl {
 public:
  QuietPcl() : previous_(pcl::console::getVerbosityLevel()) {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  }
  ~QuietPcl() { pcl::console::setVerbosityLevel(previous_); }
  QuietPcl(const QuietPcl&) = delete;
  QuietPcl& operator=(const QuietPcl&) = delete;

 private:
  pcl::console::VERBOSITY_LEVEL previous_;
};

// ---------------------------------------------------------------------------
// PCD pre-check. PCL 1.13 segfaults on a header without FIELDS (empty or text
// files), hangs on a directory and accepts a truncated ascii line, so the
// header and the length of the data section are checked here first.

struct PcdHeader {
  std::size_t fields = 0;
  std::vector<std::uint64_t> sizes;   // bytes per element, per field
  std::vector<std::uint64_t> counts;  // elements per field
  std::uint64_t width = 0;
  std::uint64_t height = 0;
  std::uint64_t points = 0;
  bool has_points = false;
  std::string data;              // ascii, binary or binary_compressed
  std::uint64_t data_offset = 0;  // first byte after the DATA line
};

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t pos = 0;
  while (true) {
    pos = line.find_first_not_of(" \t\r", pos);
    if (pos == std::string_view::npos) return words;
    const std::size_t end = std::min(line.find_first_of(" \t\r", pos), line.size());
    words.push_back(line.substr(pos, end - pos));
    pos = end;
  }
}

std::uint64_t parse_number(const fs::path& path, std::string_view key, std::string_view word) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc() || end != word.data() + word.size())
    fail(path, "bad PCD header (bad number '" + one_line(word) + "' in " + std::string(key) + ")");
  return value;
}

std::vector<std::uint64_t> parse_numbers(const fs::path& path, const std::vector<std::string_view>& words) {
  std::vector<std::uint64_t> values;
  for (std::size_t i = 1; i < words.size(); ++i) values.push_back(parse_number(path, words[0], words[i]));
  return values;
}

// Applies one header line; returns false if the keyword is unknown.
bool apply_header_line(const fs::path& path, const std::vector<std::string_view>& words, PcdHeader& header) {
  const std::string_view key = words[0];
  const auto single = [&] { return parse_number(path, key, words.size() > 1 ? words[1] : ""); };
  if (key == "VERSION" || key == "TYPE" || key == "VIEWPOINT") {
    return true;  // left to PCL
  } else if (key == "FIELDS" || key == "COLUMNS") {
    header.fields = words.size() - 1;
  } else if (key == "SIZE") {
    header.sizes = parse_numbers(path, words);
  } else if (key == "COUNT") {
    header.counts = parse_numbers(path, words);
  } else if (key == "WIDTH") {
    header.width = single();
  } else if (key == "HEIGHT") {
    header.height = single();
  } else if (key == "POINTS") {
    header.points = single();
    header.has_points = true;
  } else {
    return false;
  }
  return true;
}

std::uint64_t point_step(const PcdHeader& header) {
  std::uint64_t step = 0;
  for (std::size_t i = 0; i < header.fields; ++i) step += header.sizes[i] * header.counts[i];
  return step;
}

void validate_header(const fs::path& path, PcdHeader& header) {
  if (header.fields == 0) fail(path, "bad PCD header (no FIELDS)");
  if (header.sizes.empty()) header.sizes.assign(header.fields, 4);  // PCL's default
  if (header.counts.empty()) header.counts.assign(header.fields, 1);
  if (header.sizes.size() != header.fields || header.counts.size() != header.fields)
    fail(path, "bad PCD header (SIZE or COUNT does not match FIELDS)");
  for (std::size_t i = 0; i < header.fields; ++i) {
    const std::uint64_t size = header.sizes[i];
    if ((size != 1 && size != 2 && size != 4 && size != 8) || header.counts[i] > (1u << 20))
      fail(path, "bad PCD header (bad SIZE or COUNT)");
  }
  if (!header.has_points) fail(path, "bad PCD header (no POINTS)");
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint32_t>::max();
  if (header.points > kMax || header.width > kMax || header.height > kMax)
    fail(path, "bad PCD header (too many points)");
  if (header.width != 0 && header.width * std::max<std::uint64_t>(header.height, 1) != header.points)
    fail(path, "bad PCD header (WIDTH x HEIGHT != POINTS)");
  if (header.data != "ascii" && header.data != "binary" && header.data != "binary_compressed")
    fail(path, "bad PCD header (unknown DATA '" + one_line(header.data) + "')");
}

// Parses the header from the first bytes of the file, up to the DATA line.
PcdHeader parse_pcd_header(const fs::path& path, std::string_view head) {
  PcdHeader header;
  bool known = false;  // saw at least one PCD keyword
  std::size_t pos = 0;
  while (pos < head.size()) {
    const std::size_t end = head.find('\n', pos);
    if (end == std::string_view::npos) break;  // unterminated last line
    const auto words = split_words(head.substr(pos, end - pos));
    pos = end + 1;
    if (words.empty() || words[0].front() == '#') continue;
    if (words[0] == "DATA") {
      if (!known) break;
      header.data = words.size() > 1 ? std::string(words[1]) : "";
      header.data_offset = pos;
      validate_header(path, header);
      return header;
    }
    if (!apply_header_line(path, words, header)) {
      if (!known) break;
      fail(path, "bad PCD header (unknown line '" + one_line(words[0]) + "')");
    }
    known = true;
  }
  fail(path, known ? "truncated PCD header" : "not a point cloud (no PCD header)");
}

std::string truncated(std::uint64_t have, std::uint64_t need, const char* unit) {
  return "truncated data (" + std::to_string(have) + " of " + std::to_string(need) + " " + unit + ")";
}

void check_binary(const fs::path& path, const PcdHeader& header, std::uint64_t available) {
  const std::uint64_t need = header.points * point_step(header);
  if (available < need) fail(path, truncated(available, need, "bytes"));
}

// binary_compressed: uint32 compressed size, uint32 raw size, LZF bytes.
void check_binary_compressed(const fs::path& path, const PcdHeader& header, std::uint64_t available) {
  std::uint32_t sizes[2] = {0, 0};
  if (available >= sizeof sizes) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(header.data_offset));
    in.read(reinterpret_cast<char*>(sizes), sizeof sizes);
    if (!in) fail(path, "cannot read the data section");
  }
  const std::uint64_t need = sizeof sizes + std::uint64_t{sizes[0]};
  if (available < need) fail(path, truncated(available, need, "bytes"));
  if (sizes[1] != header.points * point_step(header)) fail(path, "corrupt compressed data (size does not match POINTS)");
}

// ascii: one line per point with one word per element; PCL only warns about a
// short line, which is what a file cut in the middle of its last line has.
void check_ascii(const fs::path& path, const PcdHeader& header) {
  std::uint64_t words_per_point = 0;
  for (const std::uint64_t count : header.counts) words_per_point += count;
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(header.data_offset));
  std::uint64_t read = 0;
  for (std::string line; read < header.points && std::getline(in, line);) {
    const auto words = split_words(line);
    if (words.empty()) continue;
    if (words.size() != words_per_point)
      fail(path, "truncated or malformed data (point " + std::to_string(read + 1) + ")");
    ++read;
  }
  if (read < header.points) fail(path, truncated(read, header.points, "points"));
}

void precheck_pcd(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  std::string head(64 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const PcdHeader header = parse_pcd_header(path, head);
  if (header.points == 0) fail(path, "no points");
  std::error_code ec;
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) fail(path, "cannot read (" + ec.message() + ")");
  const std::uint64_t available = size - std::min(size, header.data_offset);
  if (header.data == "binary") check_binary(path, header, available);
  if (header.data == "binary_compressed") check_binary_compressed(path, header, available);
  if (header.data == "ascii") check_ascii(path, header);
}

// ---------------------------------------------------------------------------
// PCL read into a blob.

pcl::PCLPointCloud2 load_blob(const fs::path& path, const std::string& ext) {
  pcl::PCLPointCloud2 blob;
  int status = -1;
  try {
    const QuietPcl quiet;
    if (ext == ".pcd") status = pcl::PCDReader().read(path.string(), blob);
    else status = pcl::PLYReader().read(path.string(), blob);
  } catch (const std::exception& e) {
    fail(path, "cannot read (" + one_line(e.what()) + ")");
  }
  if (status != 0)
    fail(path, ext == ".pcd" ? "not a readable PCD file (corrupt data?)"
                             : "not a readable PLY point cloud (bad header or truncated data)");
  return blob;
}

// ---------------------------------------------------------------------------
// Blob fields, found by name.

using pcl::PCLPointField;

std::uint32_t type_size(std::uint8_t type) {
  switch (type) {
    case PCLPointField::INT8: case PCLPointField::UINT8: return 1;
    case PCLPointField::INT16: case PCLPointField::UINT16: return 2;
    case PCLPointField::INT32: case PCLPointField::UINT32: case PCLPointField::FLOAT32: return 4;
    case PCLPointField::FLOAT64: return 8;
    default: return 0;
  }
}

bool is_float(std::uint8_t type) { return type == PCLPointField::FLOAT32 || type == PCLPointField::FLOAT64; }

struct Field {
  std::uint32_t offset;
  std::uint8_t type;
};

std::optional<Field> find_field(const fs::path& path, const pcl::PCLPointCloud2& blob, const std::string& name) {
  for (const PCLPointField& field : blob.fields) {
    if (field.name != name) continue;
    const std::uint32_t size = type_size(field.datatype);
    if (size == 0 || std::uint64_t{field.offset} + size > blob.point_step)
      fail(path, "bad layout or type of field '" + one_line(name) + "'");
    return Field{field.offset, field.datatype};
  }
  return std::nullopt;
}

template <typename T>
T load(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

float read_float(const std::uint8_t* p, std::uint8_t type) {
  return type == PCLPointField::FLOAT32 ? load<float>(p) : static_cast<float>(load<double>(p));
}

std::uint32_t read_integer(const std::uint8_t* p, std::uint8_t type) {
  switch (type) {
    case PCLPointField::INT8: return static_cast<std::uint32_t>(load<std::int8_t>(p));
    case PCLPointField::UINT8: return load<std::uint8_t>(p);
    case PCLPointField::INT16: return static_cast<std::uint32_t>(load<std::int16_t>(p));
    case PCLPointField::UINT16: return load<std::uint16_t>(p);
    case PCLPointField::INT32: return static_cast<std::uint32_t>(load<std::int32_t>(p));
    default: return load<std::uint32_t>(p);  // UINT32, or the bits of a packed float rgb
  }
}

// Three float fields (x y z or normal_x normal_y normal_z), all or none.
std::optional<std::array<Field, 3>> find_vector(const fs::path& path, const pcl::PCLPointCloud2& blob,
                                                const std::array<const char*, 3>& names) {
  std::array<Field, 3> fields{};
  for (std::size_t k = 0; k < 3; ++k) {
    const auto field = find_field(path, blob, names[k]);
    if (!field) return std::nullopt;
    if (!is_float(field->type)) fail(path, std::string("field '") + names[k] + "' is not floating point");
    fields[k] = *field;
  }
  return fields;
}

std::vector<Eigen::Vector3f> read_vectors(const pcl::PCLPointCloud2& blob, std::size_t n,
                                          const std::array<Field, 3>& fields) {
  std::vector<Eigen::Vector3f> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* point = blob.data.data() + i * blob.point_step;
    for (int k = 0; k < 3; ++k) out[i][k] = read_float(point + fields[k].offset, fields[k].type);
  }
  return out;
}

// `rgb` as a packed float or uint32, or `rgba` as uint32; alpha is dropped.
std::vector<std::uint32_t> read_colors(const fs::path& path, const pcl::PCLPointCloud2& blob, std::size_t n) {
  auto field = find_field(path, blob, "rgb");
  if (!field) field = find_field(path, blob, "rgba");
  if (!field) return {};
  if (type_size(field->type) != 4) fail(path, "colour field is not 4 bytes wide");
  std::vector<std::uint32_t> colors(n);
  for (std::size_t i = 0; i < n; ++i)
    colors[i] = read_integer(blob.data.data() + i * blob.point_step + field->offset, field->type) & 0xFFFFFFu;
  return colors;
}

std::optional<Labels> read_labels(const fs::path& path, const pcl::PCLPointCloud2& blob, std::size_t n) {
  const auto field = find_field(path, blob, "label");
  if (!field) return std::nullopt;
  if (is_float(field->type)) fail(path, "field 'label' is not an integer type");
  Labels labels(n);
  for (std::size_t i = 0; i < n; ++i)
    labels[i] = read_integer(blob.data.data() + i * blob.point_step + field->offset, field->type);
  return labels;
}

LabelledCloud to_labelled_cloud(const fs::path& path, const pcl::PCLPointCloud2& blob) {
  const std::uint64_t n = std::uint64_t{blob.width} * blob.height;
  if (n == 0) fail(path, "no points");
  if (blob.data.size() < n * blob.point_step) fail(path, truncated(blob.data.size(), n * blob.point_step, "bytes"));
  const auto xyz = find_vector(path, blob, {"x", "y", "z"});
  if (!xyz) fail(path, "no x/y/z fields");
  LabelledCloud out;
  out.cloud.width = blob.width;
  out.cloud.height = blob.height;
  out.cloud.points = read_vectors(blob, n, *xyz);
  out.cloud.colors = read_colors(path, blob, n);
  if (const auto normals = find_vector(path, blob, {"normal_x", "normal_y", "normal_z"}))
    out.cloud.normals = read_vectors(blob, n, *normals);
  out.labels = read_labels(path, blob, n);
  return out;
}

// ---------------------------------------------------------------------------
// Writers.

void check_labels(const fs::path& path, const PointCloud& cloud, const Labels& labels) {
  if (labels.size() != cloud.size()) fail(path, "labels and points differ in number");
  if (std::uint64_t{cloud.width} * cloud.height != cloud.size()) fail(path, "width x height != number of points");
  if (cloud.has_colors() && cloud.colors.size() != cloud.size()) fail(path, "colours and points differ in number");
  if (cloud.size() == 0) fail(path, "no points to write");
}

std::string why_not_written(const fs::path& path, const std::error_code& ec) {
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ignored;
  if (!fs::is_directory(folder, ignored)) return "cannot write (folder '" + folder.string() + "' does not exist)";
  return ec ? "cannot write (" + ec.message() + ")" : "cannot write";
}

// Writes to "<path>.tmp-<pid>" with write_to(temp) -> bool, then renames, so
// the file appears only when complete. The temp file never outlives a failure.
template <typename WriteTo>
void write_atomically(const fs::path& path, WriteTo&& write_to) {
  const fs::path temp = path.string() + ".tmp-" + std::to_string(::getpid());
  bool written = false;
  try {
    written = write_to(temp);
  } catch (const std::exception&) {
    written = false;
  }
  std::error_code ec;
  if (written) fs::rename(temp, path, ec);
  if (written && !ec) return;
  std::error_code ignored;
  fs::remove(temp, ignored);
  fail(path, why_not_written(path, ec));
}

template <typename T>
void store(std::uint8_t* p, T value) {
  std::memcpy(p, &value, sizeof value);
}

PCLPointField make_field(const std::string& name, std::uint32_t offset, std::uint8_t type) {
  PCLPointField field;
  field.name = name;
  field.offset = offset;
  field.datatype = type;
  field.count = 1;
  return field;
}

// x y z [rgb] label. rgb is a float holding 0xAARRGGBB with alpha 255, the
// bytes PCL's PointXYZRGB writes.
pcl::PCLPointCloud2 to_blob(const PointCloud& cloud, const Labels& labels) {
  pcl::PCLPointCloud2 blob;
  blob.width = cloud.width;
  blob.height = cloud.height;
  blob.fields = {make_field("x", 0, PCLPointField::FLOAT32), make_field("y", 4, PCLPointField::FLOAT32),
                 make_field("z", 8, PCLPointField::FLOAT32)};
  const std::uint32_t label_offset = cloud.has_colors() ? 16 : 12;
  if (cloud.has_colors()) blob.fields.push_back(make_field("rgb", 12, PCLPointField::FLOAT32));
  blob.fields.push_back(make_field("label", label_offset, PCLPointField::UINT32));
  blob.point_step = label_offset + 4;
  blob.row_step = blob.point_step * blob.width;
  blob.data.resize(std::size_t{blob.point_step} * cloud.size());
  blob.is_dense = std::all_of(cloud.points.begin(), cloud.points.end(), is_finite);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    std::uint8_t* point = blob.data.data() + i * blob.point_step;
    for (int k = 0; k < 3; ++k) store(point + 4 * k, cloud.points[i][k]);
    if (cloud.has_colors()) store(point + 12, 0xFF000000u | cloud.colors[i]);
    store(point + label_offset, labels[i]);
  }
  return blob;
}

// Minimal PNG encoder: 8-bit RGB, no interlace, filter type 0 on every row.
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(value >> shift));
}

void put_chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_u32(out, static_cast<std::uint32_t>(crc32(0, out.data() + start, static_cast<uInt>(out.size() - start))));
}

std::vector<std::uint8_t> deflate(const std::vector<std::uint8_t>& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> packed(size);
  if (compress2(packed.data(), &size, raw.data(), static_cast<uLong>(raw.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
    throw std::runtime_error("zlib compress2 failed");
  packed.resize(size);
  return packed;
}

std::vector<std::uint8_t> encode_png(std::uint32_t width, std::uint32_t height, const Labels& labels) {
  std::vector<std::uint8_t> raw;
  raw.reserve((1 + std::size_t{width} * 3) * height);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (i % width == 0) raw.push_back(0);  // filter type: none
    const auto rgb = label_color(labels[i]);
    raw.insert(raw.end(), rgb.begin(), rgb.end());
  }
  std::vector<std::uint8_t> header;
  put_u32(header, width);
  put_u32(header, height);
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bit, RGB, deflate, filter 0, no interlace
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  put_chunk(png, "IHDR", header);
  put_chunk(png, "IDAT", deflate(raw));
  put_chunk(png, "IEND", {});
  return png;
}

bool write_bytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.close();
  return !out.fail();
}

}  // namespace

LabelledCloud read_cloud(const std::filesystem::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) fail(path, "no such file");
  if (fs::is_directory(status)) fail(path, "is a directory, not a point cloud file");
  const std::string ext = lower_extension(path);
  if (ext != ".pcd" && ext != ".ply") fail(path, "unsupported format '" + ext + "' (expected .pcd or .ply)");
  if (ext == ".pcd") precheck_pcd(path);
  return to_labelled_cloud(path, load_blob(path, ext));
}

void write_labelled_pcd(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels) {
  check_labels(path, cloud, labels);
  const pcl::PCLPointCloud2 blob = to_blob(cloud, labels);
  write_atomically(path, [&](const fs::path& temp) {
    const QuietPcl quiet;
    return pcl::PCDWriter().writeBinary(temp.string(), blob) == 0;
  });
}

void write_label_png(const std::filesystem::path& path, const PointCloud& cloud, const Labels& labels) {
  if (!cloud.organized()) fail(path, "a label image needs an organized cloud");
  check_labels(path, cloud, labels);
  const std::vector<std::uint8_t> png = encode_png(cloud.width, cloud.height, labels);
  write_atomically(path, [&](const fs::path& temp) { return write_bytes(temp, png); });
}

// Hue steps by the golden ratio (Fibonacci hashing, exact in integers), so
// neighbouring ids land about 137 degrees apart; saturation cycles over three
// levels; value is fixed and high, so no label is ever black.
std::array<std::uint8_t, 3> label_color(std::uint32_t label) {
  if (label == 0) return {0, 0, 0};
  const double hue = static_cast<std::uint32_t>(label * 2654435769u) / 4294967296.0 * 6.0;  // [0, 6)
  const double saturation = 0.95 - 0.2 * (label % 3);
  const double value = 0.95;
  const double f = hue - std::floor(hue);
  const double p = value * (1 - saturation), q = value * (1 - saturation * f), t = value * (1 - saturation * (1 - f));
  const double rgb[6][3] = {{value, t, p}, {q, value, p}, {p, value, t}, {p, q, value}, {t, p, value}, {value, p, q}};
  const auto& c = rgb[static_cast<int>(hue) % 6];
  const auto byte = [](double x) { return static_cast<std::uint8_t>(std::lround(x * 255.0)); };
  return {byte(c[0]), byte(c[1]), byte(c[2])};
}

}  // namespace lccp
