#pragma once
// What the parts of the Python module share: numpy arrays to and from the
// library's types (one way for every entry point), configs, paths, thread
// counts and the JSON document. The module is a thin face of the library: it
// converts arguments, calls the same functions as the lccp tool, and converts
// the results back.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // std::optional arguments, std::vector results
#include <tbb/task_arena.h>

#include "lccp/cloud.hpp"
#include "lccp/config.hpp"
#include "lccp/objects/scene.hpp"

namespace lccp::python {

namespace py = pybind11;

// Shapes of numpy arrays: the leading shape of a cloud is (N,) or (H, W).
using Shape = std::vector<py::ssize_t>;

// --- argument and result types for signatures ---------------------------------------
// Any Python object, checked by the module's own code (so that a bad value raises
// its ValueError naming the argument, not pybind11's TypeError), shown in
// signatures (help()) under the name its Tag's handle_type_name gives (below).
template <class Tag>
class Typed : public py::object {
 public:
  using py::object::object;
  Typed(py::object value) : py::object(std::move(value)) {}  // NOLINT: results convert implicitly
  static bool check_(py::handle) { return true; }
};
using ArrayArg = Typed<struct ArrayTag>;                  // numpy.ndarray
using OptionalArrayArg = Typed<struct OptionalArrayTag>;  // numpy.ndarray or None
using ConfigArg = Typed<struct ConfigTag>;                // preset, path, dict or Config
using PathArg = Typed<struct PathTag>;                    // str or os.PathLike
using IgnoreArg = Typed<struct IgnoreTag>;                // range, (first, last) or None
using SegmentResult = Typed<struct SegmentResultTag>;     // labels, or a Segmentation

// --- numpy -> library (arrays.cpp) ----------------------------------------------
// A cloud's arrays, held alive as long as the CloudView made from them is used.
// Points and normals are float32 C-contiguous (..., 3) arrays: the caller's
// own array when it already is one (read in place), else a float32 copy.
// Colors are packed uint32 0x00RRGGBB, one per point, or none.
struct CloudArrays {
  Shape shape;  // leading shape of points: (N,) or (H, W)
  py::array points;
  py::object colors = py::none();   // an array, or None when the cloud has no colours
  py::object normals = py::none();  // an array, or None when the cloud has no normals

  std::size_t size() const;
  CloudView view() const;  // valid while this object lives
};

// Checks and converts segment()'s arrays; raises ValueError naming the
// argument and what is wrong (dtype, shape, point count, no points).
CloudArrays cloud_arrays(py::handle points, py::handle colors = py::none(), py::handle normals = py::none());

// An owning cloud (for the library's writers): a copy of the arrays.
PointCloud owned_cloud(const CloudArrays& arrays);

// Labels of any integer dtype, any shape, as uint32 in C order; `name` for errors.
Labels labels_from(py::handle labels, const char* name);

// --- library -> numpy, without copying: the vector moves into the array --------
template <class Scalar, class Element>
py::array_t<Scalar> adopt_vector(std::vector<Element>&& values, Shape shape) {
  static_assert(sizeof(Element) % sizeof(Scalar) == 0);
  auto owner = std::make_unique<std::vector<Element>>(std::move(values));
  const auto* data = reinterpret_cast<const Scalar*>(owner->data());
  py::capsule keeper(owner.get(), [](void* p) { delete static_cast<std::vector<Element>*>(p); });
  owner.release();  // the capsule frees it, with the array
  return py::array_t<Scalar>(std::move(shape), data, keeper);
}

// (N,) or (H, W) for a cloud of width x height points.
Shape cloud_shape(const PointCloud& cloud);
// `leading` with one more axis of `last` entries, e.g. (H, W) -> (H, W, 3).
Shape with_axis(Shape leading, py::ssize_t last);

// Points as float32 (..., 3), labels as uint32 of the leading shape.
py::array points_array(std::vector<Eigen::Vector3f>&& points, const Shape& shape);
py::array labels_array(Labels&& labels, const Shape& shape);

// --- arguments -------------------------------------------------------------------
// str, bytes or os.PathLike as a file name (os.fsdecode); TypeError otherwise.
std::string path_string(py::handle path);

// A Config, a preset name or YAML path, or a dict of keys (parse_config: unknown
// keys are refused naming the key, as in files).
SceneConfig config_from(py::handle config);

// None (every core) or a positive thread count; ValueError otherwise.
std::optional<int> thread_count(const std::optional<int>& threads);

// Runs `work` on `threads` worker threads: in a task arena of its own (no
// global setting changes), or in the calling thread's default arena (None).
template <class Work>
auto with_threads(std::optional<int> threads, Work&& work) {
  if (!threads) return work();
  tbb::task_arena arena(*threads);
  return arena.execute(std::forward<Work>(work));
}

// The frame's JSON document (encode_segments_json, the schema of the
// segments.json files) as Python objects: one schema for files and Python.
// Its vectors and axes (centroid, obb center/axes/extents, principal_axes,
// principal_extents, mean_normal, the support plane's normal) are numpy
// float64 arrays of shape (3,) and (3, 3), NaN where the file has null.
py::dict json_document(std::uint64_t frame_index, std::uint64_t timestamp_us, const SceneSegmentation& scene);

// What Python sees of a SceneSegmentation, under the same names in segment()'s
// result (the class Segmentation) and in every Frame (a Segmentation too):
// per point `labels` (finest level) and `objects` (None with one level), per
// segment `segments` (the JSON document's "objects" list) and `support_plane`.
struct PySegmentation {
  py::object labels, objects, segments, support_plane;
};

// Fills `out` from `scene`, whose label vectors move into numpy arrays of
// `shape`; returns the frame's JSON document (for the rest of its fields).
py::dict fill_segmentation(PySegmentation& out, SceneSegmentation&& scene, const Shape& shape,
                           std::uint64_t frame_index, std::uint64_t timestamp_us);

// --- the parts of the module -------------------------------------------------------
void bind_config(py::module_& module);
void bind_segment(py::module_& module);
void bind_files(py::module_& module);
void bind_evaluate(py::module_& module);
void bind_streams(py::module_& module);

}  // namespace lccp::python

namespace pybind11::detail {
#define LCCP_PYTHON_TYPE_NAME(type, text)                    \
  template <>                                                \
  struct handle_type_name<lccp::python::type> {              \
    static constexpr auto name = const_name(text);           \
  }
LCCP_PYTHON_TYPE_NAME(ArrayArg, "numpy.ndarray");
LCCP_PYTHON_TYPE_NAME(OptionalArrayArg, "Optional[numpy.ndarray]");
LCCP_PYTHON_TYPE_NAME(ConfigArg, "Union[str, os.PathLike, dict, Config]");
LCCP_PYTHON_TYPE_NAME(PathArg, "Union[str, os.PathLike]");
LCCP_PYTHON_TYPE_NAME(IgnoreArg, "Optional[Union[range, Tuple[int, int]]]");
LCCP_PYTHON_TYPE_NAME(SegmentResult, "Union[numpy.ndarray, Segmentation]");
#undef LCCP_PYTHON_TYPE_NAME
}  // namespace pybind11::detail
