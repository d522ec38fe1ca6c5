// The Python module lccp_stream: LCCP segmentation of numpy point clouds and of
// recordings and sensors, through the same library calls as the lccp tool.
#include "bindings.hpp"
#include "lccp/error.hpp"

namespace {

constexpr const char* kModuleDoc = R"doc(
LCCP Stream: object and part segmentation of point clouds with Locally
Convex Connected Patches (Stein et al., ICRA 2014), the library behind the
lccp command-line tool.

segment(points, ...)        one cloud (numpy arrays) -> labels [, segments]
Replay(path, ...)           iterate over the segmented frames of a recording
Live(uri, ...)              iterate over the segmented frames of a sensor
evaluate(pred, gt, ...)     the paper's Appendix B scores
load_config(), presets()    configurations (Config)
read_cloud(), write_label_png()   .pcd/.ply clouds and label images

Errors the caller can cause (a bad file, parameter or array) raise ValueError
with a one-line message; a stream that fails raises RuntimeError.
)doc";

// lccp::Error is a problem with the caller's input: ValueError, same message.
void translate_errors(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const lccp::Error& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  }
}

}  // namespace

PYBIND11_MODULE(lccp_stream, module) {
  module.doc() = kModuleDoc;
  pybind11::register_exception_translator(&translate_errors);
  lccp::python::bind_config(module);
  lccp::python::bind_segment(module);
  lccp::python::bind_files(module);
  lccp::python::bind_evaluate(module);
  lccp::python::bind_streams(module);
}
