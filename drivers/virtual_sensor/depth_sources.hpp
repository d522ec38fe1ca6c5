#pragma once
// What the virtual sensor sees: depth images in millimetres, one per frame index.
// No OpenNI2 types here; virtual_sensor_driver.cpp wraps a source as a device.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

#include "virtual_uri.hpp"

namespace lccp::virtual_sensor {

// Farther depths are reported as 0 (no return), as a Kinect does beyond its range.
// Also the stream's MAX_VALUE, which sizes the 16zT codec's table in recordings.
inline constexpr std::uint16_t kMaxDepthMm = 10000;

struct DepthMode {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int fps = 0;
  bool operator==(const DepthMode&) const = default;
};

struct FieldOfView {
  float horizontal_rad = 0;
  float vertical_rad = 0;
};

class DepthSource {
 public:
  virtual ~DepthSource() = default;

  // The modes the sensor offers; the first is the default.
  virtual const std::vector<DepthMode>& modes() const = 0;

  // The same for every mode (a mode changes the resolution, not the lens).
  virtual FieldOfView field_of_view() const = 0;

  // Writes the image of frame `frame_index` of a stream at `mode` (one of modes()),
  // timestamped `timestamp_us`, into depth_mm (width * height pixels, row-major,
  // 0 = no return). Safe to call from any thread: sources are immutable.
  virtual void render(std::uint64_t frame_index, std::uint64_t timestamp_us, const DepthMode& mode,
                      std::span<std::uint16_t> depth_mm) const = 0;
};

// virtual://synthetic: TabletopScene at 640x480 @ 30 fps (default) or 320x240 @ 60 fps.
// A frame shows the scene at its timestamp: render(frame_of_timestamp_us(timestamp_us)).
std::unique_ptr<DepthSource> make_synthetic_source(std::uint64_t seed);

// virtual://clouds: reads every cloud now (one file, or the folder's .pcd files in name
// order), keeps z as millimetres: round(z * 1000) for finite points with z > 0, else 0.
// Frame k shows cloud k mod count, at the clouds' size @ 30 fps. Throws lccp::Error for an
// unreadable, unorganized or differently sized cloud, or no points to fit the lens to.
std::unique_ptr<DepthSource> make_cloud_source(const std::filesystem::path& path);

std::unique_ptr<DepthSource> make_source(const VirtualUri& uri);

// Depth in millimetres of a point at z metres, as the clouds source stores it.
std::uint16_t depth_mm_of_z(float z_m);

}  // namespace lccp::virtual_sensor
