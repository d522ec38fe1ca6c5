// numpy arrays to and from the library's clouds and labels: the one place where
// the module checks and converts arrays.
#include <cstdint>
#include <string>

#include "bindings.hpp"

namespace lccp::python {
namespace {

// Eigen::Vector3f is three packed floats, so an (N, 3) float32 array is N of them.
static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float) && alignof(Eigen::Vector3f) == alignof(float));

// "(480, 640, 3)"
std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t axis = 0; axis < array.ndim(); ++axis) {
    text += (axis ? ", " : "") + std::to_string(array.shape(axis));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

// "float64 array of shape (5, 2)"
std::string describe(const py::array& array) {
  return py::str(array.dtype()).cast<std::string>() + " array of shape " + shape_text(array);
}

py::array as_array(py::handle object, const char* name) {
  py::array array = py::array::ensure(object);
  if (!array) throw py::value_error(std::string(name) + ": expected a numpy array, got " + py::str(py::type::of(object)).cast<std::string>());
  return array;
}

Shape leading_shape(const py::array& array) { return Shape(array.shape(), array.shape() + array.ndim() - 1); }

std::size_t count(const Shape& shape) {
  std::size_t n = 1;
  for (const py::ssize_t extent : shape) n *= static_cast<std::size_t>(extent);
  return n;
}

// The array itself when numpy can hand it over as it is (C order, native
// type, aligned), else a C-ordered copy converted to T.
template <class T>
py::array c_array_of(const py::array& array) {
  const bool in_place = py::isinstance<py::array_t<T>>(array) && (array.flags() & py::array::c_style) &&
                        reinterpret_cast<std::uintptr_t>(array.data()) % alignof(T) == 0;
  if (in_place) return array;
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
}

// Points or normals: float32 or float64, (N, 3) or (H, W, 3), at least one point.
py::array xyz_array(py::handle object, const char* name) {
  const py::array array = as_array(object, name);
  const bool float_type = array.dtype().kind() == 'f' && (array.itemsize() == 4 || array.itemsize() == 8);
  const bool xyz_shape = (array.ndim() == 2 || array.ndim() == 3) && array.shape(array.ndim() - 1) == 3;
  if (!float_type || !xyz_shape) {
    throw py::value_error(std::string(name) + ": expected an (N, 3) or (H, W, 3) float32/float64 array, got " +
                          describe(array));
  }
  if (array.size() == 0) throw py::value_error(std::string(name) + ": no points (shape " + shape_text(array) + ")");
  return c_array_of<float>(array);
}

// uint8 (..., 3) RGB packed into 0x00RRGGBB.
py::array pack_rgb(const py::array& rgb, std::size_t n) {
  const auto bytes = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(rgb);
  const std::uint8_t* in = bytes.data();
  py::array_t<std::uint32_t> packed(static_cast<py::ssize_t>(n));
  std::uint32_t* out = packed.mutable_data();
  for (std::size_t i = 0; i < n; ++i, in += 3) {
    out[i] = std::uint32_t{in[0]} << 16 | std::uint32_t{in[1]} << 8 | std::uint32_t{in[2]};
  }
  return packed;
}

// Colours: uint8 RGB (..., 3) or uint32 packed 0x00RRGGBB, one per point.
py::array color_array(py::handle object, std::size_t n) {
  const py::array array = as_array(object, "colors");
  const bool rgb = py::isinstance<py::array_t<std::uint8_t>>(array) && array.ndim() >= 2 &&
                   array.shape(array.ndim() - 1) == 3 && count(leading_shape(array)) == n;
  const bool packed = array.dtype().kind() == 'u' && array.itemsize() == 4 && static_cast<std::size_t>(array.size()) == n;
  if (rgb) return pack_rgb(array, n);
  if (packed) return c_array_of<std::uint32_t>(array);
  throw py::value_error("colors: expected a uint8 (..., 3) RGB or uint32 packed 0x00RRGGBB array for " +
                        std::to_string(n) + " points, got " + describe(array));
}

// The elements of an array from the functions above, or none for None.
template <class T>
std::span<const T> span_of(const py::object& array, std::size_t elements) {
  if (array.is_none()) return {};
  return {static_cast<const T*>(py::reinterpret_borrow<py::array>(array).data()), elements};
}

}  // namespace

std::size_t CloudArrays::size() const { return count(shape); }

CloudView CloudArrays::view() const {
  CloudView view;
  const bool organized = shape.size() == 2;
  view.width = static_cast<std::uint32_t>(organized ? shape[1] : shape[0]);
  view.height = static_cast<std::uint32_t>(organized ? shape[0] : 1);
  view.points = span_of<Eigen::Vector3f>(points, size());
  view.colors = span_of<std::uint32_t>(colors, size());
  view.normals = span_of<Eigen::Vector3f>(normals, size());
  return view;
}

CloudArrays cloud_arrays(py::handle points, py::handle colors, py::handle normals) {
  CloudArrays arrays;
  arrays.points = xyz_array(points, "points");
  arrays.shape = leading_shape(arrays.points);
  const std::size_t n = arrays.size();
  if (n > std::uint32_t(-1) || arrays.shape.back() > py::ssize_t{std::uint32_t(-1)}) {
    throw py::value_error("points: " + std::to_string(n) + " points are more than a cloud can hold");
  }
  if (!colors.is_none()) arrays.colors = color_array(colors, n);
  if (!normals.is_none()) {
    const py::array normal_array = xyz_array(normals, "normals");
    if (count(leading_shape(normal_array)) != n) {
      throw py::value_error("normals: expected one normal per point (" + std::to_string(n) + "), got " +
                            describe(normal_array));
    }
    arrays.normals = normal_array;
  }
  return arrays;
}

PointCloud owned_cloud(const CloudArrays& arrays) {
  const CloudView view = arrays.view();
  PointCloud cloud;
  cloud.width = view.width;
  cloud.height = view.height;
  cloud.points.assign(view.points.begin(), view.points.end());
  cloud.colors.assign(view.colors.begin(), view.colors.end());
  cloud.normals.assign(view.normals.begin(), view.normals.end());
  return cloud;
}

Labels labels_from(py::handle object, const char* name) {
  const py::array array = as_array(object, name);
  const char kind = array.dtype().kind();
  if (kind != 'u' && kind != 'i') {
    throw py::value_error(std::string(name) + ": expected an array of integer labels, got " + describe(array));
  }
  if (kind == 'i' && array.size() > 0 && array.attr("min")() < py::int_(0)) {
    throw py::value_error(std::string(name) + ": labels must not be negative");
  }
  const auto values = py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast>::ensure(array);
  return Labels(values.data(), values.data() + values.size());
}

Shape cloud_shape(const PointCloud& cloud) {
  if (cloud.organized()) return {py::ssize_t(cloud.height), py::ssize_t(cloud.width)};
  return {py::ssize_t(cloud.size())};
}

Shape with_axis(Shape leading, py::ssize_t last) {
  leading.push_back(last);
  return leading;
}

py::array points_array(std::vector<Eigen::Vector3f>&& points, const Shape& shape) {
  return adopt_vector<float>(std::move(points), with_axis(shape, 3));
}

py::array labels_array(Labels&& labels, const Shape& shape) {
  return adopt_vector<std::uint32_t>(std::move(labels), shape);
}

}  // namespace lccp::python
