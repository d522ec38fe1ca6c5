// Label images: label_color, the label and overlay renderings of an organized
// cloud, and a minimal PNG encoder (zlib for the deflate stream and CRCs).
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>  // cross

#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "point_records.hpp"

namespace lccp {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

// ------------------------------------------------------------- PNG encoder
// PNG (ISO/IEC 15948): signature, IHDR, IDAT (zlib stream), IEND; each chunk
// is length, type, data, CRC-32 of type and data, numbers big-endian.

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

// An 8-bit RGB PNG, no interlace, filter type 0 (none) on every row.
std::vector<std::uint8_t> encode_png(std::uint32_t width, std::uint32_t height, const std::vector<Rgb>& pixels) {
  std::vector<std::uint8_t> raw;
  raw.reserve((1 + std::size_t{width} * 3) * height);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    if (i % width == 0) raw.push_back(0);  // filter type: none
    raw.insert(raw.end(), pixels[i].begin(), pixels[i].end());
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

// ---------------------------------------------------------- overlay shading

// The finite point at pixel (x, y), if (x, y) is inside the image.
std::optional<Eigen::Vector3f> finite_at(const PointCloud& cloud, std::int64_t x, std::int64_t y) {
  if (x < 0 || y < 0 || x >= cloud.width || y >= cloud.height) return std::nullopt;
  const Eigen::Vector3f& p = cloud.points[static_cast<std::size_t>(y) * cloud.width + static_cast<std::size_t>(x)];
  if (!is_finite(p)) return std::nullopt;
  return p;
}

// The surface's direction along the image axis (dx, dy) at the finite point
// of pixel (x, y): next minus previous neighbour (a central difference), or
// one-sided where a neighbour is missing; nothing if both are.
std::optional<Eigen::Vector3f> tangent(const PointCloud& cloud, std::int64_t x, std::int64_t y, int dx, int dy) {
  const std::optional<Eigen::Vector3f> next = finite_at(cloud, x + dx, y + dy);
  const std::optional<Eigen::Vector3f> prev = finite_at(cloud, x - dx, y - dy);
  if (!next && !prev) return std::nullopt;
  const Eigen::Vector3f here = *finite_at(cloud, x, y);
  return next.value_or(here) - prev.value_or(here);
}

// Lambert shading with the light at the camera (the origin of the sensor
// frame the points are in): grey = 255 (0.15 + 0.85 |cos a|), a the angle
// between the surface normal (the cross product of the horizontal and
// vertical tangents) and the ray from the point to the camera. Surfaces
// facing the camera are bright, grazing ones dark, and depth edges (where the
// tangents span a jump) come out as dark outlines. A point without a normal
// (no finite neighbour along a row or a column, or parallel tangents) is
// shaded as facing the camera.
std::uint8_t shade(const PointCloud& cloud, std::int64_t x, std::int64_t y) {
  const std::optional<Eigen::Vector3f> u = tangent(cloud, x, y, 1, 0), v = tangent(cloud, x, y, 0, 1);
  const Eigen::Vector3f to_camera = -*finite_at(cloud, x, y);
  float cosine = 1.0f;
  if (u && v) {
    const Eigen::Vector3f normal = u->cross(*v);
    const float scale = normal.norm() * to_camera.norm();
    if (scale > 0 && std::isfinite(scale)) cosine = std::min(1.0f, std::abs(normal.dot(to_camera)) / scale);
  }
  return static_cast<std::uint8_t>(std::lround(255.0f * (0.15f + 0.85f * cosine)));
}

// Half the grey level, half the colour, rounded half up.
Rgb blend(std::uint8_t grey, const Rgb& color) {
  Rgb out{};
  for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>((grey + color[c] + 1) / 2);
  return out;
}

// The colour of point i: label_color of its label, or with objects part_color.
Rgb point_color(const Labels& labels, const Labels* objects, std::size_t i) {
  return objects ? part_color((*objects)[i], labels[i]) : label_color(labels[i]);
}

std::vector<Rgb> overlay_pixels(const PointCloud& cloud, const Labels& labels, const Labels* objects) {
  std::vector<Rgb> pixels(cloud.size(), Rgb{0, 0, 0});  // NaN points stay black
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!is_finite(cloud.points[i])) continue;
    const std::uint8_t grey = shade(cloud, static_cast<std::int64_t>(i % cloud.width),
                                    static_cast<std::int64_t>(i / cloud.width));
    pixels[i] = labels[i] == 0 ? Rgb{grey, grey, grey} : blend(grey, point_color(labels, objects, i));
  }
  return pixels;
}

// An id's hue in [0, 6) (sextants of the colour wheel): the id times 2^32 / phi
// modulo 2^32 (Fibonacci hashing, Knuth TAOCP vol. 3, 6.4; exact in
// integers), so neighbouring ids land about 137 degrees apart.
double id_hue(std::uint32_t id) { return static_cast<std::uint32_t>(id * 2654435769u) / 4294967296.0 * 6.0; }

// Red, green and blue in [0, 1] of a hue in [0, 6) with the given chroma,
// plus m added to each (the hexcone model: Smith, "Color gamut transform
// pairs", SIGGRAPH 1978).
Rgb hexcone(double hue, double chroma, double m) {
  const double x = chroma * (1 - std::abs(std::fmod(hue, 2.0) - 1));
  const double rgb[6][3] = {{chroma, x, 0}, {x, chroma, 0}, {0, chroma, x},
                            {0, x, chroma}, {x, 0, chroma}, {chroma, 0, x}};
  const auto& c = rgb[static_cast<int>(hue) % 6];
  const auto byte = [m](double v) { return static_cast<std::uint8_t>(std::lround((v + m) * 255.0)); };
  return {byte(c[0]), byte(c[1]), byte(c[2])};
}

}  // namespace

std::vector<std::uint8_t> encode_label_png(const PointCloud& cloud, const Labels& labels, LabelImageStyle style,
                                           const Labels* objects) {
  if (!cloud.organized()) throw Error("a label image needs an organized cloud");
  io_detail::check_labelled_cloud(cloud, labels, objects);
  return encode_png(cloud.width, cloud.height,
                    style == LabelImageStyle::overlay ? overlay_pixels(cloud, labels, objects)
                                                      : label_rgb(labels, objects));
}

std::vector<std::array<std::uint8_t, 3>> label_rgb(const Labels& labels, const Labels* objects) {
  if (objects && objects->size() != labels.size()) throw Error("label colours: labels and objects differ in number");
  std::vector<Rgb> pixels(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) pixels[i] = point_color(labels, objects, i);
  return pixels;
}

// Hue from id_hue; saturation cycles over three levels; value is fixed and
// high, so no label is ever black.
std::array<std::uint8_t, 3> label_color(std::uint32_t label) {
  if (label == 0) return {0, 0, 0};
  const double hue = id_hue(label);
  const double saturation = 0.95 - 0.2 * (label % 3);
  const double value = 0.95;
  const double f = hue - std::floor(hue);
  const double p = value * (1 - saturation), q = value * (1 - saturation * f), t = value * (1 - saturation * (1 - f));
  const double rgb[6][3] = {{value, t, p}, {q, value, p}, {p, value, t}, {p, q, value}, {t, p, value}, {value, p, q}};
  const auto& c = rgb[static_cast<int>(hue) % 6];
  const auto byte = [](double x) { return static_cast<std::uint8_t>(std::lround(x * 255.0)); };
  return {byte(c[0]), byte(c[1]), byte(c[2])};
}

// A part's own hue within 60 deg either side of its object's (id_hue), HSL
// saturation 0.85, lightness 0.42, 0.54 or 0.66 by part id mod 3. Objects stay
// recognisable: each is one family of hues, and the objects' own hues are
// spread by Fibonacci hashing (neighbouring ids 137 deg apart, so two bands of
// 120 deg rarely cover the same hues). Parts are told apart by hue, which the eye
// separates better than lightness (a shade of one hue reads as shading of one
// surface): the offset is the part id times 1 / phi modulo 1 over the band,
// the same low-discrepancy sequence, so consecutive part ids (an object's parts
// get consecutive ids when it is first seen) land 0.38 or 0.62 of the band (46
// or 74 deg) apart and any five consecutive ones at least 0.146 of it (17 deg;
// the three-distance theorem). The colour follows the stable ids, so a part
// keeps it from frame to frame.
std::array<std::uint8_t, 3> part_color(std::uint32_t object, std::uint32_t part) {
  if (part == 0) return {0, 0, 0};
  if (object == 0 || object == part) return label_color(part);
  constexpr double kBandSextants = 2.0;  // 120 deg
  const double offset = static_cast<std::uint32_t>(part * 2654435769u) / 4294967296.0 - 0.5;
  const double hue = std::fmod(id_hue(object) + kBandSextants * offset + 6.0, 6.0);
  const double lightness = 0.42 + 0.12 * (part % 3);
  const double chroma = (1 - std::abs(2 * lightness - 1)) * 0.85;
  return hexcone(hue, chroma, lightness - chroma / 2);
}

}  // namespace lccp
