#include "depth_sources.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>

#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/synthetic/tabletop_scene.hpp"

namespace lccp::virtual_sensor {
namespace {

namespace fs = std::filesystem;

std::string size_text(std::uint32_t width, std::uint32_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

class SyntheticSource final : public DepthSource {
 public:
  explicit SyntheticSource(std::uint64_t seed) : seed_(seed) {}

  const std::vector<DepthMode>& modes() const override { return modes_; }

  FieldOfView field_of_view() const override {
    const synthetic::Camera lens;
    return {lens.horizontal_fov_rad, lens.vertical_fov_rad};
  }

  void render(std::uint64_t /*frame_index*/, std::uint64_t timestamp_us, const DepthMode& mode,
              std::span<std::uint16_t> depth_mm) const override {
    synthetic::Camera camera;
    camera.width = mode.width;
    camera.height = mode.height;
    const synthetic::TabletopScene scene(camera, seed_);
    const std::vector<std::uint16_t> image =
        scene.render(synthetic::frame_of_timestamp_us(timestamp_us)).depth.depth_mm;
    if (image.size() != depth_mm.size()) {
      throw Error("synthetic scene rendered " + std::to_string(image.size()) + " pixels for a " +
                  size_text(mode.width, mode.height) + " frame");
    }
    std::transform(image.begin(), image.end(), depth_mm.begin(),
                   [](std::uint16_t mm) { return mm > kMaxDepthMm ? std::uint16_t{0} : mm; });
  }

 private:
  std::uint64_t seed_;
  std::vector<DepthMode> modes_{{640, 480, 30}, {320, 240, 60}};
};

// Least-squares focal lengths over the finite points of organized clouds, from the
// pinhole model with the principal point at the image centre (what an .oni stores):
// x = (u - W/2) z / fx, i.e. x = a s with s = (u - W/2) z and a = 1/fx = sum(x s) / sum(s s).
class LensFit {
 public:
  LensFit(std::uint32_t width, std::uint32_t height) : width_(width), height_(height) {}

  void add(const PointCloud& cloud) {
    for (std::uint32_t v = 0; v < height_; ++v) {
      for (std::uint32_t u = 0; u < width_; ++u) {
        const Eigen::Vector3f& p = cloud.points[std::size_t{v} * width_ + u];
        if (!is_finite(p) || p.z() <= 0) continue;
        const double sx = (u - width_ / 2.0) * p.z();
        const double sy = (v - height_ / 2.0) * p.z();
        x_dot_s_ += p.x() * sx;
        s_dot_s_x_ += sx * sx;
        y_dot_s_ += p.y() * sy;
        s_dot_s_y_ += sy * sy;
      }
    }
  }

  // Throws if no point constrains a focal length.
  FieldOfView field_of_view(const fs::path& path) const {
    if (x_dot_s_ == 0 || y_dot_s_ == 0) {
      throw Error(path.string() + ": no finite points to estimate the field of view from");
    }
    const double fx = std::abs(s_dot_s_x_ / x_dot_s_);  // |.|: a cloud may have y (or x) flipped
    const double fy = std::abs(s_dot_s_y_ / y_dot_s_);
    return {static_cast<float>(2 * std::atan(width_ / (2 * fx))),
            static_cast<float>(2 * std::atan(height_ / (2 * fy)))};
  }

 private:
  std::uint32_t width_;
  std::uint32_t height_;
  double x_dot_s_ = 0, s_dot_s_x_ = 0, y_dot_s_ = 0, s_dot_s_y_ = 0;
};

std::vector<fs::path> cloud_files(const fs::path& path) {
  std::error_code error;
  if (!fs::is_directory(path, error)) return {path};  // read_cloud reports a missing file
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(path, error)) {
    if (entry.is_regular_file() && entry.path().extension() == ".pcd") files.push_back(entry.path());
  }
  if (error) throw Error(path.string() + ": cannot list the folder: " + error.message());
  if (files.empty()) throw Error(path.string() + ": no .pcd files in the folder");
  std::sort(files.begin(), files.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });
  return files;
}

class CloudSource final : public DepthSource {
 public:
  explicit CloudSource(const fs::path& path) {
    std::optional<LensFit> lens;
    fs::path first;
    for (const fs::path& file : cloud_files(path)) {
      const PointCloud cloud = read_cloud(file).cloud;
      if (!cloud.organized()) {
        throw Error(file.string() + ": not an organized cloud (" + size_text(cloud.width, cloud.height) +
                    "), so it has no depth image");
      }
      if (!lens) {
        first = file;
        mode_ = {cloud.width, cloud.height, 30};
        lens.emplace(cloud.width, cloud.height);
      } else if (cloud.width != mode_.width || cloud.height != mode_.height) {
        throw Error(file.string() + ": " + size_text(cloud.width, cloud.height) + " but " + first.string() + " is " +
                    size_text(mode_.width, mode_.height) + "; all clouds must have one size");
      }
      std::vector<std::uint16_t>& image = images_.emplace_back(cloud.size());
      std::transform(cloud.points.begin(), cloud.points.end(), image.begin(),
                     [](const Eigen::Vector3f& p) { return is_finite(p) ? depth_mm_of_z(p.z()) : std::uint16_t{0}; });
      lens->add(cloud);
    }
    field_of_view_ = lens->field_of_view(path);
    modes_ = {mode_};
  }

  const std::vector<DepthMode>& modes() const override { return modes_; }
  FieldOfView field_of_view() const override { return field_of_view_; }

  void render(std::uint64_t frame_index, std::uint64_t /*timestamp_us*/, const DepthMode& /*mode*/,
              std::span<std::uint16_t> depth_mm) const override {
    const std::vector<std::uint16_t>& image = images_[frame_index % images_.size()];
    std::copy(image.begin(), image.end(), depth_mm.begin());
  }

 private:
  DepthMode mode_;
  std::vector<DepthMode> modes_;
  FieldOfView field_of_view_;
  std::vector<std::vector<std::uint16_t>> images_;
};

}  // namespace

std::uint16_t depth_mm_of_z(float z_m) {
  if (!(z_m > 0)) return 0;
  const double mm = std::round(static_cast<double>(z_m) * 1000.0);
  return mm > kMaxDepthMm ? std::uint16_t{0} : static_cast<std::uint16_t>(mm);
}

std::unique_ptr<DepthSource> make_synthetic_source(std::uint64_t seed) {
  return std::make_unique<SyntheticSource>(seed);
}

std::unique_ptr<DepthSource> make_cloud_source(const std::filesystem::path& path) {
  return std::make_unique<CloudSource>(path);
}

std::unique_ptr<DepthSource> make_source(const VirtualUri& uri) {
  switch (uri.kind) {
    case SourceKind::synthetic: return make_synthetic_source(uri.seed);
    case SourceKind::clouds: return make_cloud_source(uri.path);
  }
  throw Error("virtual sensor: unknown source kind");
}

}  // namespace lccp::virtual_sensor
