#include "lccp/synthetic/tabletop_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "kinect_model.hpp"
#include "lccp/error.hpp"
#include "ray_cast.hpp"
#include "scene_layout.hpp"

namespace lccp::synthetic {

namespace {

using detail::CameraPose;
using detail::Hit;
using detail::Part;
using detail::Ray;

// Pixel (u, v) looks along ((u - W/2) x_per_pixel, (v - H/2) y_per_pixel, 1) in
// the optical frame: back_project's model, computed the same way (in float),
// so a noise-free depth back-projects onto the surface it came from.
struct PixelGrid {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  double x_per_pixel = 0;  // 1 / fx
  double y_per_pixel = 0;  // 1 / fy
  double cx = 0;
  double cy = 0;
  double x(std::uint32_t u) const { return (static_cast<double>(u) - cx) * x_per_pixel; }
  double y(std::uint32_t v) const { return (static_cast<double>(v) - cy) * y_per_pixel; }
};

PixelGrid pixel_grid(const Camera& camera) {
  PixelGrid grid;
  grid.width = camera.width;
  grid.height = camera.height;
  grid.x_per_pixel = 2.0f * std::tan(camera.horizontal_fov_rad / 2) / static_cast<float>(camera.width);
  grid.y_per_pixel = 2.0f * std::tan(camera.vertical_fov_rad / 2) / static_cast<float>(camera.height);
  grid.cx = static_cast<float>(camera.width) / 2;
  grid.cy = static_cast<float>(camera.height) / 2;
  return grid;
}

// What each pixel's ray meets first, before the sensor measures it.
struct SurfaceImage {
  std::vector<float> depth_m;         // along the optical axis; infinite if nothing
  std::vector<std::uint8_t> grazing;  // seen at more than 80 deg from its normal
  Labels labels;
};

bool is_grazing(const Eigen::Vector3d& direction, const Eigen::Vector3d& normal) {
  const double along = direction.dot(normal);
  return along * along < detail::kCosMaxIncidenceSquared * direction.squaredNorm();
}

// Inclusive pixel bounds.
struct PixelRect {
  std::uint32_t u_min = 0, u_max = 0, v_min = 0, v_max = 0;
};

// A part as the camera sees it: the camera's position and axes in the part's
// frame (so that a pixel's local ray is a sum of three columns) and the pixels
// its bounding box covers.
struct PartView {
  const Part* part = nullptr;
  Eigen::Vector3d origin;
  Eigen::Matrix3d axes;
  PixelRect pixels;
};

PartView view_of(const Part& part, const CameraPose& pose, const PixelGrid& grid) {
  const double c = std::cos(part.yaw_rad), s = std::sin(part.yaw_rad);
  Eigen::Matrix3d world_from_part;
  world_from_part << c, -s, 0, s, c, 0, 0, 0, 1;
  PartView view;
  view.part = &part;
  view.origin = world_from_part.transpose() * (pose.position - part.position);
  view.axes = world_from_part.transpose() * pose.axes;

  // Project the corners of the local bounds; a corner behind the camera means
  // the whole image.
  double u_lo = grid.width, u_hi = -1, v_lo = grid.height, v_hi = -1;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d local((corner & 1) ? part.local_max.x() : part.local_min.x(),
                                (corner & 2) ? part.local_max.y() : part.local_min.y(),
                                (corner & 4) ? part.local_max.z() : part.local_min.z());
    const Eigen::Vector3d in_camera = view.axes.transpose() * (local - view.origin);
    if (in_camera.z() < 0.01) {
      view.pixels = PixelRect{0, grid.width - 1, 0, grid.height - 1};
      return view;
    }
    const double u = in_camera.x() / in_camera.z() / grid.x_per_pixel + grid.cx;
    const double v = in_camera.y() / in_camera.z() / grid.y_per_pixel + grid.cy;
    u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u);
    v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
  }
  const auto clamp_to = [](double value, std::uint32_t size) {
    return static_cast<std::uint32_t>(std::clamp(value, 0.0, static_cast<double>(size - 1)));
  };
  view.pixels = PixelRect{clamp_to(std::floor(u_lo) - 1, grid.width), clamp_to(std::ceil(u_hi) + 1, grid.width),
                          clamp_to(std::floor(v_lo) - 1, grid.height), clamp_to(std::ceil(v_hi) + 1, grid.height)};
  return view;
}

// The first hit of a ray (in the part's frame) with the part.
Hit intersect(const Part& part, const Ray& ray, std::span<const Eigen::Vector3d> handle_centre_line) {
  using namespace detail;
  switch (part.shape) {
    case Shape::box:
      return intersect_box(ray, part.local_min, part.local_max);
    case Shape::cylinder:
      return intersect_cylinder(ray, part.size.x(), part.size.z());
    case Shape::cup:
      return intersect_cup(ray, kMugOuterRadiusM, kMugInnerRadiusM, kMugHeightM, kMugBottomM);
    case Shape::handle:
      return intersect_tube(ray, handle_centre_line, kHandleTubeRadiusM);
  }
  return {};
}

// A plane of the static scene facing the camera, perpendicular to a world
// axis, and the rectangle of it that is solid (unbounded for the floor and
// wall). Along a pixel's ray d its inverse depth is linear,
// w = d[axis] / (plane - o[axis]), and the hit o + d / w lies in the rectangle
// iff (lo_j - o_j) w <= d_j <= (hi_j - o_j) w on the other two axes.
struct FacingPlane {
  int axis = 0;
  double inverse_distance = 0;  // 1 / (plane - o[axis])
  Eigen::Vector3d lo_from_camera = Eigen::Vector3d::Constant(-detail::kNoHit);  // lo - o
  Eigen::Vector3d hi_from_camera = Eigen::Vector3d::Constant(detail::kNoHit);   // hi - o
  std::uint32_t label = 0;
};

// The planes of the static scene that face the camera: the faces of the table
// slab on the camera's side, the floor and the wall.
std::vector<FacingPlane> facing_planes(const Eigen::Vector3d& o) {
  std::vector<FacingPlane> planes;
  const Part table = detail::table();
  const Eigen::Vector3d lo = table.position + table.local_min;  // the table is not turned
  const Eigen::Vector3d hi = table.position + table.local_max;
  for (int axis = 0; axis < 3; ++axis) {
    if (o[axis] >= lo[axis] && o[axis] <= hi[axis]) continue;  // both faces turned away
    FacingPlane face;
    face.axis = axis;
    face.inverse_distance = 1.0 / ((o[axis] < lo[axis] ? lo[axis] : hi[axis]) - o[axis]);
    face.lo_from_camera = lo - o;
    face.hi_from_camera = hi - o;
    face.label = table.label;
    planes.push_back(face);
  }
  FacingPlane floor;
  floor.axis = 2;
  floor.inverse_distance = 1.0 / (detail::kFloorZ - o.z());
  floor.label = kBackgroundLabel;
  planes.push_back(floor);
  FacingPlane wall;
  wall.axis = 1;
  wall.inverse_distance = 1.0 / (detail::kWallY - o.y());
  wall.label = kBackgroundLabel;
  planes.push_back(wall);
  return planes;
}

// Pixels [begin, end) of a row.
struct PixelSpan {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
};

// Where in a row (rays d = x across + row) a plane is hit in front of the
// camera and inside its rectangle: each condition is linear in x, so
// together they hold on an interval of x, i.e. a span of pixels.
PixelSpan span_on_plane(const FacingPlane& plane, const Eigen::Vector3d& across, const Eigen::Vector3d& row,
                        const PixelGrid& grid) {
  double x_min = -std::numeric_limits<double>::infinity(), x_max = std::numeric_limits<double>::infinity();
  const auto require = [&](double c0, double c1) {  // c0 + c1 x >= 0
    if (c1 > 0) {
      x_min = std::max(x_min, -c0 / c1);
    } else if (c1 < 0) {
      x_max = std::min(x_max, -c0 / c1);
    } else if (c0 < 0) {
      x_max = -std::numeric_limits<double>::infinity();
    }
  };
  const int a = plane.axis;
  const double w0 = row[a] * plane.inverse_distance, w1 = across[a] * plane.inverse_distance;  // w = w0 + w1 x
  require(w0, w1);
  for (const int j : {(a + 1) % 3, (a + 2) % 3}) {
    const double lo = plane.lo_from_camera[j], hi = plane.hi_from_camera[j];
    if (std::isfinite(lo)) require(row[j] - lo * w0, across[j] - lo * w1);  // d_j - lo w >= 0
    if (std::isfinite(hi)) require(hi * w0 - row[j], hi * w1 - across[j]);  // hi w - d_j >= 0
  }
  // x(u) = (u - cx) x_per_pixel.
  const double width = grid.width;
  const double first = std::clamp(std::ceil(x_min / grid.x_per_pixel + grid.cx), 0.0, width);
  const double last = std::clamp(std::floor(x_max / grid.x_per_pixel + grid.cx) + 1, 0.0, width);
  return PixelSpan{static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(std::max(first, last))};
}

// The static scene (table, floor, wall) in every pixel: the nearest facing
// plane, the one with the largest inverse depth where it is hit.
SurfaceImage cast_static_scene(const PixelGrid& grid, const CameraPose& pose) {
  const std::vector<FacingPlane> planes = facing_planes(pose.position);
  SurfaceImage image;
  const std::size_t pixels = std::size_t{grid.width} * grid.height;
  image.depth_m.resize(pixels);
  image.grazing.resize(pixels);
  image.labels.resize(pixels);
  std::vector<double> x(grid.width);
  for (std::uint32_t u = 0; u < grid.width; ++u) x[u] = grid.x(u);
  std::vector<double> nearest_w(grid.width);
  std::vector<const FacingPlane*> nearest(grid.width);
  const Eigen::Vector3d& across = pose.axes.col(0);
  for (std::uint32_t v = 0; v < grid.height; ++v) {
    const Eigen::Vector3d row = grid.y(v) * pose.axes.col(1) + pose.axes.col(2);
    std::fill(nearest_w.begin(), nearest_w.end(), 0.0);
    std::fill(nearest.begin(), nearest.end(), nullptr);
    for (const FacingPlane& plane : planes) {
      const PixelSpan span = span_on_plane(plane, across, row, grid);
      const double w0 = row[plane.axis] * plane.inverse_distance, w1 = across[plane.axis] * plane.inverse_distance;
      for (std::uint32_t u = span.begin; u < span.end; ++u) {
        const double w = w0 + w1 * x[u];
        if (w > nearest_w[u]) {
          nearest_w[u] = w;
          nearest[u] = &plane;
        }
      }
    }
    for (std::uint32_t u = 0; u < grid.width; ++u) {
      const std::size_t i = std::size_t{v} * grid.width + u;
      if (nearest[u] == nullptr) {  // nothing there: no return
        image.depth_m[i] = std::numeric_limits<float>::infinity();
        image.labels[i] = kBackgroundLabel;
        continue;
      }
      const Eigen::Vector3d d = x[u] * across + row;
      const int axis = nearest[u]->axis;  // the plane's normal: (d . n)^2 = d[axis]^2
      image.depth_m[i] = static_cast<float>(1.0 / nearest_w[u]);
      image.grazing[i] = d[axis] * d[axis] < detail::kCosMaxIncidenceSquared * d.squaredNorm();
      image.labels[i] = nearest[u]->label;
    }
  }
  return image;
}

// Casts the pixels a part may cover; it wins where it is nearer.
void cast_part(const PartView& view, const PixelGrid& grid, std::span<const Eigen::Vector3d> handle_centre_line,
               SurfaceImage& image) {
  Ray ray{view.origin, Eigen::Vector3d::Zero()};
  for (std::uint32_t v = view.pixels.v_min; v <= view.pixels.v_max; ++v) {
    const Eigen::Vector3d row = grid.y(v) * view.axes.col(1) + view.axes.col(2);
    for (std::uint32_t u = view.pixels.u_min; u <= view.pixels.u_max; ++u) {
      const std::size_t i = std::size_t{v} * grid.width + u;
      ray.direction = grid.x(u) * view.axes.col(0) + row;
      const Hit hit = intersect(*view.part, ray, handle_centre_line);
      if (!(hit.t < image.depth_m[i])) continue;
      image.depth_m[i] = static_cast<float>(hit.t);
      image.grazing[i] = is_grazing(ray.direction, hit.normal);
      image.labels[i] = view.part->label;
    }
  }
}

// The sensor's measurement of each pixel's surface, row by row from the right:
// a point is in the projector's shadow if a point to its right (the side the
// projector is on) maps to a projector column at or left of its own, i.e. lies
// on its ray to the projector; the projector column of (u, z) is u - fx b / z.
// Shadowed, grazing, out-of-range and dropped-out pixels read 0 and get label 0;
// the others get axial noise, then disparity quantization, in millimetres.
SyntheticFrame measure(SurfaceImage image, const PixelGrid& grid, const Camera& camera,
                       const detail::NormalDeviates& normal, std::uint64_t key) {
  SyntheticFrame frame;
  frame.depth.width = camera.width;
  frame.depth.height = camera.height;
  frame.depth.horizontal_fov_rad = camera.horizontal_fov_rad;
  frame.depth.vertical_fov_rad = camera.vertical_fov_rad;
  frame.depth.depth_mm.resize(image.depth_m.size());
  frame.labels = std::move(image.labels);
  const double projector_offset_px = detail::kProjectorOffsetM / grid.x_per_pixel;  // at 1 m
  for (std::uint32_t v = 0; v < grid.height; ++v) {
    double leftmost_projector_u = std::numeric_limits<double>::infinity();  // of the points right of u
    for (std::uint32_t u = grid.width; u-- > 0;) {
      const std::size_t i = std::size_t{v} * grid.width + u;
      const double z = image.depth_m[i];
      const double projector_u = static_cast<double>(u) - projector_offset_px / z;
      const bool shadowed = projector_u >= leftmost_projector_u;
      leftmost_projector_u = std::min(leftmost_projector_u, projector_u);
      std::uint16_t mm = 0;
      if (!shadowed && !image.grazing[i] && z >= detail::kMinRangeM && z <= detail::kMaxRangeM) {
        const detail::PixelNoise noise = detail::pixel_noise(key, i, normal);
        if (!noise.dropout) {
          const double measured = detail::quantize_depth_m(z + detail::axial_noise_sigma_m(z) * noise.gaussian);
          mm = static_cast<std::uint16_t>(std::clamp(detail::round_positive(measured * 1000.0), 1.0, 65535.0));
        }
      }
      frame.depth.depth_mm[i] = mm;
      if (mm == 0) frame.labels[i] = kNoReturnLabel;
    }
  }
  return frame;
}

void check(const Camera& camera) {
  const bool fov_ok = camera.horizontal_fov_rad > 0 && camera.horizontal_fov_rad < std::numbers::pi &&
                      camera.vertical_fov_rad > 0 && camera.vertical_fov_rad < std::numbers::pi;
  if (camera.width == 0 || camera.height == 0 || !fov_ok) {
    throw Error("synthetic camera of " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                " pixels with fields of view " + std::to_string(camera.horizontal_fov_rad) + " x " +
                std::to_string(camera.vertical_fov_rad) + " rad: need pixels and fields of view in (0, pi)");
  }
}

}  // namespace

// What every frame shares: the noise model's table, and the static scene as
// the camera sees it (the camera does not move: detail::camera_pose()).
struct TabletopScene::Fixed {
  detail::NormalDeviates normal;
  SurfaceImage static_scene;
};

TabletopScene::TabletopScene(Camera camera, std::uint64_t noise_seed) : camera_(camera), noise_seed_(noise_seed) {
  check(camera_);
  fixed_ = std::make_shared<const Fixed>(Fixed{{}, cast_static_scene(pixel_grid(camera_), detail::camera_pose())});
}

SyntheticFrame TabletopScene::render(std::uint64_t frame_index) const {
  const double t_s = static_cast<double>(frame_index % detail::kPeriodFrames) / kFrameRateHz;
  const PixelGrid grid = pixel_grid(camera_);
  const CameraPose pose = detail::camera_pose();
  const auto handle = detail::handle_centre_line();

  SurfaceImage surface = fixed_->static_scene;
  const auto parts = detail::object_parts_at(t_s);
  for (const Part& part : parts) cast_part(view_of(part, pose, grid), grid, handle, surface);
  return measure(std::move(surface), grid, camera_, fixed_->normal, detail::frame_key(noise_seed_, frame_index));
}

}  // namespace lccp::synthetic
