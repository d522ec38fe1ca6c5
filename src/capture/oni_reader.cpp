#include "oni_reader.hpp"

#include <string>

#include "depth_units.hpp"
#include "lccp/error.hpp"
#include "oni_16zt.hpp"

namespace lccp::detail {
namespace {

// Uncompressed depth: little-endian 16-bit pixels.
void copy_uncompressed(const std::vector<std::uint8_t>& in, std::vector<std::uint16_t>& out) {
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = static_cast<std::uint16_t>(in[2 * i] | in[2 * i + 1] << 8);
  }
}

}  // namespace

OniReader::OniReader(const std::filesystem::path& path)
    : path_(path), facts_(check_oni_file(path)), file_(path, std::ios::binary) {
  if (!file_) throw Error("cannot open " + path.string());
}

Frame OniReader::read(std::uint64_t number) {
  const OniFrameRecord& record = facts_.frame_records.at(number);
  const std::string where = path_.string() + ": frame " + std::to_string(number) + ": ";
  payload_.resize(record.payload_size);
  file_.seekg(static_cast<std::streamoff>(record.payload_offset));
  file_.read(reinterpret_cast<char*>(payload_.data()), static_cast<std::streamsize>(payload_.size()));
  if (!file_ || file_.gcount() != static_cast<std::streamsize>(payload_.size())) {
    throw Error(where + "cannot be read (the file was cut or changed since it was opened?)");
  }
  DepthImage image;
  image.width = static_cast<std::uint32_t>(facts_.width);
  image.height = static_cast<std::uint32_t>(facts_.height);
  image.horizontal_fov_rad = facts_.horizontal_fov_rad;
  image.vertical_fov_rad = facts_.vertical_fov_rad;
  image.depth_mm.resize(std::size_t{image.width} * image.height);
  if (!is_16zt(facts_.codec)) {
    copy_uncompressed(payload_, image.depth_mm);  // its size, 2 bytes a pixel, was checked
  } else if (const auto problem = decode_16zt(payload_, image.depth_mm)) {
    throw Error(where + *problem + " (the file changed since it was opened?)");
  }
  to_millimetres(image.depth_mm, facts_.pixel_format);
  Frame frame;
  frame.index = number;
  frame.timestamp_us = record.timestamp_us;
  frame.depth = std::move(image);
  return frame;
}

}  // namespace lccp::detail
