#include "lccp/core/back_projection.hpp"

#include <cmath>
#include <limits>

#include "lccp/error.hpp"
#include "parallel.hpp"

namespace lccp {

PointCloud back_project(const DepthImage& depth) {
  const std::size_t pixels = std::size_t{depth.width} * depth.height;
  if (pixels == 0 || depth.depth_mm.size() != pixels) {
    throw Error("depth image of " + std::to_string(depth.width) + "x" + std::to_string(depth.height) +
                " has " + std::to_string(depth.depth_mm.size()) + " pixels");
  }
  if (!(depth.horizontal_fov_rad > 0 && depth.vertical_fov_rad > 0)) {
    throw Error("depth image has no field of view");
  }
  // Per metre of depth, the offset of one pixel from the centre (1 / focal length).
  const float x_per_pixel = 2.0f * std::tan(depth.horizontal_fov_rad / 2) / static_cast<float>(depth.width);
  const float y_per_pixel = 2.0f * std::tan(depth.vertical_fov_rad / 2) / static_cast<float>(depth.height);
  const float cx = static_cast<float>(depth.width) / 2;
  const float cy = static_cast<float>(depth.height) / 2;
  const float nan = std::numeric_limits<float>::quiet_NaN();

  PointCloud cloud;
  cloud.width = depth.width;
  cloud.height = depth.height;
  cloud.points.resize(pixels);
  detail::parallel_for_each_index(depth.height, [&](std::size_t row) {
    const float y_factor = (static_cast<float>(row) - cy) * y_per_pixel;
    for (std::uint32_t col = 0; col < depth.width; ++col) {
      const std::size_t i = row * depth.width + col;
      const std::uint16_t mm = depth.depth_mm[i];
      if (mm == 0) {
        cloud.points[i] = Eigen::Vector3f(nan, nan, nan);
        continue;
      }
      const float z = static_cast<float>(mm) * 0.001f;
      cloud.points[i] = Eigen::Vector3f((static_cast<float>(col) - cx) * x_per_pixel * z, y_factor * z, z);
    }
  });
  return cloud;
}

}  // namespace lccp
