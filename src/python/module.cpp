// The Python module lccp_stream: LCCP segmentation of numpy point clouds and of
// recordings and sensors, through the same library calls as the lccp tool.
#include "bindings.hpp"
#include "lccp/error.hpp"
#include "lccp/process.hpp"

namespace {

constexpr const char* kKeepMemoryDoc = R"doc(
Keeps freed heap memory in the process (glibc: no mmap for large blocks, no
trimming), so each call reuses the pages of the previous one instead of
faulting in fresh zeroed pages; the lccp tool does this at start. A setting
of the whole process (the interpreter), so it is never made on import: call
it once if this process segments many clouds.
)doc";

constexpr const char* kModuleDoc = R"doc(
LCCP Stream: object and part segmentation of point clouds with Locally
Convex Connected Patches (Stein et al., ICRA 2014), the library behind the
lccp command-line tool.

segment(points, ...)        one cloud (numpy arrays) -> labels, or a Segmentation
Replay(path, ...)           iterate over the segmented frames of a recording
Live(uri, ...)              iterate over the segmented frames of a sensor
evaluate(pred, gt, ...)     the paper's Appendix B scores
load_config(), presets()    configurations (Config)
read_cloud(), write_label_png()   .pcd/.ply clouds and label images
keep_freed_memory_for_next_frames()   opt-in process setting for long runs

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
  module.def("keep_freed_memory_for_next_frames", &lccp::keep_freed_memory_for_next_frames, kKeepMemoryDoc);
}
