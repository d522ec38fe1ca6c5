// Thin wrappers over the library's cloud reader and label image writer, for
// scripts that read clouds and look at their labels.
#include "bindings.hpp"
#include "lccp/io/cloud_io.hpp"

namespace lccp::python {
namespace {

// Packed 0x00RRGGBB colours as uint8 (..., 3) RGB.
py::array rgb_array(const std::vector<std::uint32_t>& colors, const Shape& shape) {
  py::array_t<std::uint8_t> rgb(with_axis(shape, 3));
  std::uint8_t* out = rgb.mutable_data();
  for (const std::uint32_t color : colors) {
    *out++ = static_cast<std::uint8_t>(color >> 16);
    *out++ = static_cast<std::uint8_t>(color >> 8);
    *out++ = static_cast<std::uint8_t>(color);
  }
  return rgb;
}

py::dict read_cloud_dict(PathArg path) {
  const std::string file = path_string(path);
  LabelledCloud read;
  {
    py::gil_scoped_release release;
    read = lccp::read_cloud(file);
  }
  PointCloud& cloud = read.cloud;
  const Shape shape = cloud_shape(cloud);
  py::dict result;
  result["colors"] = cloud.has_colors() ? py::object(rgb_array(cloud.colors, shape)) : py::none();
  result["normals"] = cloud.has_normals() ? py::object(points_array(std::move(cloud.normals), shape)) : py::none();
  result["labels"] = read.labels ? py::object(labels_array(std::move(*read.labels), shape)) : py::none();
  result["points"] = points_array(std::move(cloud.points), shape);
  return result;
}

// The label image of `labels` (H, W), or of labels in the layout of `points`.
void write_png(PathArg path, ArrayArg labels, OptionalArrayArg points, OptionalArrayArg objects) {
  const std::string file = path_string(path);
  Labels label_values = labels_from(labels, "labels");
  const py::array label_array = py::array::ensure(labels);
  PointCloud cloud;
  if (!points.is_none()) {
    cloud = owned_cloud(cloud_arrays(points));
  } else if (label_array.ndim() == 2) {
    cloud.height = static_cast<std::uint32_t>(label_array.shape(0));
    cloud.width = static_cast<std::uint32_t>(label_array.shape(1));
    cloud.points.assign(label_values.size(), Eigen::Vector3f::Zero());  // the image shows labels only
  } else {
    throw py::value_error("labels: expected an (H, W) array, or points (H, W, 3) to give the image's shape");
  }
  const Labels object_values = objects.is_none() ? Labels{} : labels_from(objects, "objects");
  py::gil_scoped_release release;
  lccp::write_label_png(file, cloud, label_values, LabelImageStyle::labels, objects.is_none() ? nullptr : &object_values);
}

}  // namespace

void bind_files(py::module_& module) {
  module.def("read_cloud", &read_cloud_dict, py::arg("path"), R"doc(
Reads a .pcd or .ply file (the library's own readers, as the lccp tool).

Returns a dict: "points" float32 (N, 3) or organized (H, W, 3) (NaN = no data),
"colors" uint8 RGB of the same leading shape or None, "normals" like points
or None, "labels" uint32 (N,) or (H, W) (the file's label field) or None.
Raises ValueError with the reader's message for a missing or bad file.
)doc");
  module.def("write_label_png", &write_png, py::arg("path"), py::arg("labels"), py::arg("points") = py::none(),
             py::arg("objects") = py::none(), R"doc(
Writes a PNG of the labels, one pixel per point (as lccp segment --png): a
fixed colour per label, black for 0.

labels: (H, W) integer labels, or any shape with points (H, W, 3) giving the
    image's shape. objects: optional per-point object ids (Frame.objects):
    each object gets its hue and each part a hue of its own near it.
The file appears only when complete. Raises ValueError for an unorganized
cloud or mismatched sizes.
)doc");
}

}  // namespace lccp::python
