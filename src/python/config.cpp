// Configs (presets, YAML files, dicts, Config objects), paths, thread counts
// and the per-frame JSON document, as the module's functions take and give them.
#include <string>

#include "bindings.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/io/segments_json.hpp"

namespace lccp::python {
namespace {

using namespace pybind11::literals;  // "dtype"_a

// A dict is written as JSON, which is YAML, and read by parse_config like a
// file: the same keys, ranges and error messages ("unknown config key 'x'").
SceneConfig config_from_dict(const py::dict& settings) {
  const std::string text = py::module_::import("json").attr("dumps")(settings).cast<std::string>();
  return parse_config(text, "config dict");
}

// A JSON list of numbers (or of lists of them) as a float64 array; numpy
// turns JSON's null (a non-finite value, RFC 8259 Sec. 6) into NaN.
py::array float_array(py::handle values) {
  return py::module_::import("numpy").attr("asarray")(values, "dtype"_a = "float64");
}

// An object's or part's vectors and axes as arrays, its parts' too.
void geometry_as_arrays(py::dict segment) {
  for (const char* name : {"centroid", "principal_axes", "principal_extents", "mean_normal"}) {
    segment[name] = float_array(segment[name]);
  }
  py::dict box = segment["obb"];
  for (const char* name : {"center", "axes", "extents"}) box[name] = float_array(box[name]);
  if (!segment.contains("parts")) return;
  for (py::handle part : segment["parts"]) geometry_as_arrays(py::reinterpret_borrow<py::dict>(part));
}

}  // namespace

std::string path_string(py::handle path) {
  return py::module_::import("os").attr("fsdecode")(path).cast<std::string>();
}

SceneConfig config_from(py::handle config) {
  if (py::isinstance<SceneConfig>(config)) return config.cast<SceneConfig>();
  if (py::isinstance<py::dict>(config)) return config_from_dict(py::reinterpret_borrow<py::dict>(config));
  return load_preset_or_file(path_string(config));
}

std::optional<int> thread_count(const std::optional<int>& threads) {
  if (threads && *threads < 1) {
    throw py::value_error("threads: expected None (all cores) or a positive number, got " + std::to_string(*threads));
  }
  return threads;
}

py::dict json_document(std::uint64_t frame_index, std::uint64_t timestamp_us, const SceneSegmentation& scene) {
  const std::string text = encode_segments_json(frame_index, timestamp_us, scene);
  py::dict document = py::module_::import("json").attr("loads")(text);
  for (py::handle object : document["objects"]) geometry_as_arrays(py::reinterpret_borrow<py::dict>(object));
  if (!document["support_plane"].is_none()) {
    py::dict plane = document["support_plane"];
    plane["normal"] = float_array(plane["normal"]);
  }
  return document;
}

void bind_config(py::module_& module) {
  py::class_<SceneConfig>(module, "Config", R"doc(
A segmentation configuration: the parameters of one level of LCCP (objects) or
two (objects, then parts within each object), as the lccp tool's --config.

Make one with load_config(); str(config) lists every key with its unit and
value (the keys a YAML file or a config dict may set). segment(), Replay and
Live take a Config wherever they take a preset name, a YAML path or a dict.
)doc")
      .def(py::init<>(), "The defaults: the paper's parameter set P1, one level.")
      .def("__str__", &describe_config, "One line per key: name, unit and value (parts.KEY for the second level).")
      .def("__repr__", [](const SceneConfig& config) {
        return std::string("<lccp_stream.Config, ") + (config.two_levels() ? "two levels" : "one level") + ">";
      })
      .def_property_readonly("levels", [](const SceneConfig& config) { return config.two_levels() ? 2 : 1; },
                             "1 (segments) or 2 (objects, then parts within each object).");

  module.def(
      "load_config", [](ConfigArg name_or_path) { return config_from(name_or_path); }, py::arg("name_or_path"),
      R"doc(
A preset by name ("p1", "p2", "objects", "robot": see presets()) or a YAML file
by path (str or os.PathLike; anything with a folder or a suffix), or a dict of
keys (unknown keys and out-of-range values raise ValueError naming the key).
Returns a Config.
)doc");
  module.def("presets", &preset_names, "The names of the built-in presets, sorted (objects, p1, p2, paper, robot).");
}

}  // namespace lccp::python
