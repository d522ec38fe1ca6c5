// lccp_stream.segment(): one cloud given as numpy arrays, segmented by the
// library's SceneSegmenter exactly as `lccp segment` does it.
#include "bindings.hpp"

namespace lccp::python {
namespace {

constexpr const char* kSegmentDoc = R"doc(
Segments one point cloud into LCCP segments (or objects and parts).

points: float32 or float64 array, (N, 3) or organized (H, W, 3), metres; NaN
    marks a point without data. A C-contiguous float32 array is read in place;
    any other float array is converted to a float32 copy.
colors: optional, one per point: uint8 (..., 3) RGB, or uint32 packed 0x00RRGGBB.
normals: optional, one unit normal per point, like points.
config: a preset name ("p1", "p2", "objects", "robot"), a YAML file path, a
    dict of keys (as in a YAML file; "parts" holds a dict for the second
    level; unset keys keep the P1 defaults) or a Config.
threads: None for every core, or the number of worker threads to use.
segments: return a Segmentation (below) instead of the labels alone.

Returns uint32 labels of shape (N,) or (H, W): per point the id of its segment
(with two levels, of its part), 0 for points without data. With
segments=True returns a Segmentation, the same attributes as a Replay's or
Live's Frame: labels (as above), objects (per point, uint32 object ids; None
with one level), segments (per segment: the "objects" list of the per-frame
JSON document, README: id, points, centroid, obb, principal_axes,
principal_extents, mean_normal, grasp, adjacent, parts; vectors and axes as
numpy float64 arrays) and support_plane ({"id", "normal", "d", "noise_m"} or None).

Raises ValueError for a bad array, config or cloud (with the library's
one-line message). The GIL is released while the cloud is segmented.
)doc";

SegmentResult segment(ArrayArg points, OptionalArrayArg colors, OptionalArrayArg normals, ConfigArg config,
                      std::optional<int> threads, bool with_segments) {
  const CloudArrays arrays = cloud_arrays(points, colors, normals);
  const SceneSegmenter segmenter(config_from(config));  // validates the config
  threads = thread_count(threads);
  const CloudView view = arrays.view();
  SceneSegmentation scene;
  {
    py::gil_scoped_release release;
    scene = with_threads(threads, [&] { return segmenter.segment(view); });
  }
  if (!with_segments) return labels_array(std::move(scene.labels), arrays.shape);
  PySegmentation result;
  fill_segmentation(result, std::move(scene), arrays.shape, 0, 0);
  return py::cast(std::move(result));
}

constexpr const char* kSegmentationDoc = R"doc(
The segmentation of one cloud: segment(..., segments=True) returns one, and
every Frame of a Replay or Live is one (with the frame's fields besides).

labels: uint32, the points' leading shape (N,) or (H, W): per point the id of
    its segment (with two levels, of its part), 0 = no data.
objects: uint32 per-point object ids like labels, or None with one level.
segments: list of dicts, one per object (with its "parts"): the "objects"
    list of the per-frame JSON document (README schema); centroid, obb's
    center, axes and extents, principal_axes, principal_extents and
    mean_normal are numpy float64 arrays, (3,) or (3, 3) with one axis a row.
support_plane: {"id": int, "normal": float64 (3,), "d": float, "noise_m": float} (n . p + d = 0;
    noise_m: the robust standard deviation of its inliers, metres)
    or None.
)doc";

// segment(..., segments=True) returned (labels, objects) before it returned a
// Segmentation: unpacking one says what to use instead.
[[noreturn]] void refuse_unpacking(const PySegmentation&) {
  throw py::type_error(
      "a Segmentation is not a tuple: use its attributes labels, objects (per point), segments (per segment) "
      "and support_plane (segment(..., segments=True) no longer returns (labels, objects))");
}

void bind_segmentation_class(py::module_& module) {
  py::class_<PySegmentation>(module, "Segmentation", kSegmentationDoc)
      .def_readonly("labels", &PySegmentation::labels, "uint32 segment (part) id per point, 0 = no data.")
      .def_readonly("objects", &PySegmentation::objects, "uint32 object id per point, or None with one level.")
      .def_readonly("segments", &PySegmentation::segments,
                    "Per object a dict (its parts inside): the JSON document's \"objects\" list.")
      .def_readonly("support_plane", &PySegmentation::support_plane,
                    "{\"id\", \"normal\" (float64 (3,)), \"d\"} or None.")
      .def("__iter__", &refuse_unpacking)
      .def("__repr__", [](const PySegmentation& segmentation) {
        return "<lccp_stream.Segmentation: " + std::to_string(py::len(segmentation.segments)) + " segments>";
      });
}

}  // namespace

py::dict fill_segmentation(PySegmentation& out, SceneSegmentation&& scene, const Shape& shape,
                           std::uint64_t frame_index, std::uint64_t timestamp_us) {
  py::dict document = json_document(frame_index, timestamp_us, scene);
  out.segments = document["objects"];
  out.support_plane = document["support_plane"];
  out.labels = labels_array(std::move(scene.labels), shape);
  out.objects = scene.objects.empty() ? py::none() : py::object(labels_array(std::move(scene.objects), shape));
  return document;
}

void bind_segment(py::module_& module) {
  bind_segmentation_class(module);
  module.def("segment", &segment, py::arg("points"), py::arg("colors") = py::none(), py::arg("normals") = py::none(),
             py::arg("config") = "p1", py::arg("threads") = py::none(), py::arg("segments") = false, kSegmentDoc);
}

}  // namespace lccp::python
