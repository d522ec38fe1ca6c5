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
segments: also return the objects' and parts' geometry.

Returns uint32 labels of shape (N,) or (H, W): per point the id of its segment
(with two levels, of its part), 0 for points without data. With
segments=True returns (labels, objects), objects the "objects" list of the
per-frame JSON document (README: ids, points, centroid, obb,
principal_axes, principal_extents, mean_normal, grasp, adjacent, parts).

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
  py::object segments = py::none();
  if (with_segments) segments = json_document(0, 0, scene)["objects"];
  py::array labels = labels_array(std::move(scene.labels), arrays.shape);
  if (!with_segments) return labels;
  return py::make_tuple(labels, segments);
}

}  // namespace

void bind_segment(py::module_& module) {
  module.def("segment", &segment, py::arg("points"), py::arg("colors") = py::none(), py::arg("normals") = py::none(),
             py::arg("config") = "p1", py::arg("threads") = py::none(), py::arg("segments") = false, kSegmentDoc);
}

}  // namespace lccp::python
