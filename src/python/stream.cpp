// lccp_stream.Replay and lccp_stream.Live: the library's BackgroundStream over
// a source opened by open_source; Python iterates over the frames it hands over.
//
//   BackgroundStream (the library's thread and hand-off) -> __next__ (Python) -> Frame
//
// close(), Ctrl-C, the end of a with block and the object's destruction stop
// the stream (BackgroundStream::stop); waits release the GIL.
#include <chrono>
#include <mutex>

#include "bindings.hpp"
#include "lccp/capture/open_source.hpp"
#include "lccp/pipeline/background_stream.hpp"
#include "lccp/pipeline/push_source.hpp"
#include "lccp/view/view_server.hpp"

namespace lccp::python {
namespace {

using namespace std::chrono_literals;

// What Python sees of a FrameResult: a Segmentation (labels, objects,
// segments, support_plane) with the frame's own fields.
struct PyFrame : PySegmentation {
  std::uint64_t index = 0;
  std::uint64_t timestamp_us = 0;
  py::object points, new_ids, gone_ids;
  std::string error;
};

PyFrame to_python(FrameResult&& result) {
  PyFrame frame;
  frame.index = result.frame.index;
  frame.timestamp_us = result.frame.timestamp_us;
  PointCloud& cloud = result.frame.cloud;
  const Shape shape = cloud_shape(cloud);
  const py::dict document = fill_segmentation(frame, std::move(result.segmentation), shape, frame.index,
                                              frame.timestamp_us);
  frame.new_ids = document["new_ids"];
  frame.gone_ids = document["gone_ids"];
  frame.points = points_array(std::move(cloud.points), shape);
  frame.error = std::move(result.error);
  return frame;
}

// One BackgroundStream over one source. `frames`: the stream is stopped once
// that many frames were handed to Python (a live source drops frames at
// admission, so its own count would yield fewer).
class Stream {
 public:
  Stream(std::unique_ptr<FrameSource> source, const SceneConfig& config, unsigned inflight,
         std::optional<int> threads, std::optional<std::uint64_t> frames, const std::optional<std::string>& view)
      : source_(std::move(source)),
        view_(start_view(view)),
        stream_(config, *source_, StreamConfig{inflight, threads.value_or(0), 2, view_.get()}),
        frames_to_yield_(frames) {}
  ~Stream() { close(); }

  PyFrame next();
  void close();
  std::optional<std::string> view_url() const { return view_ ? std::optional(view_->url()) : std::nullopt; }

 private:
  [[noreturn]] void finish();

  // The live view on view = "[HOST:]PORT" (as lccp's --view); its URL printed.
  static std::unique_ptr<view::ViewServer> start_view(const std::optional<std::string>& address) {
    if (!address) return nullptr;
    auto server = std::make_unique<view::ViewServer>(view::parse_view_address(*address));
    py::print("view:", server->url());
    return server;
  }

  std::unique_ptr<FrameSource> source_;
  std::unique_ptr<view::ViewServer> view_;  // watches stream_: outlives it
  BackgroundStream stream_;  // runs on *source_
  std::optional<std::uint64_t> frames_to_yield_;
  std::uint64_t frames_yielded_ = 0;
  bool error_raised_ = false;
};

// Waits with the GIL released, looking for Ctrl-C every 100 ms. With the last
// of `frames` the stream is asked to stop (the frames in flight are dropped).
PyFrame Stream::next() {
  if (frames_to_yield_ && frames_yielded_ == *frames_to_yield_) finish();
  FrameResult result;
  for (;;) {
    BackgroundStream::Next status;
    {
      py::gil_scoped_release release;
      status = stream_.next(result, 100ms);
    }
    if (status == BackgroundStream::Next::frame) {
      if (frames_to_yield_ && ++frames_yielded_ == *frames_to_yield_) stream_.request_stop();
      return to_python(std::move(result));
    }
    if (status == BackgroundStream::Next::ended) finish();
    if (PyErr_CheckSignals() != 0) {  // e.g. KeyboardInterrupt: stop the stream, then raise it
      close();
      throw py::error_already_set();
    }
  }
}

// Every frame was taken: StopIteration, or once RuntimeError if the run failed.
void Stream::finish() {
  close();
  const std::string error = stream_.stop().error;
  if (!error.empty() && !error_raised_) {
    error_raised_ = true;
    throw std::runtime_error(error);
  }
  throw py::stop_iteration();
}

// Stops the stream: frames in flight are finished and dropped, its thread joined.
void Stream::close() {
  py::gil_scoped_release release;  // the stream may take a moment to finish its frames
  stream_.stop();
}

// Replay and Live are two faces of Stream with their own constructors.
struct Replay : Stream {
  using Stream::Stream;
};
struct Live : Stream {
  using Stream::Stream;
};

// A Stream over a PushSource: arrays pushed from Python are its frames.
class Push : public Stream {
 public:
  Push(std::unique_ptr<PushSource> source, PushSource& pushed, const SceneConfig& config, unsigned inflight,
       std::optional<int> threads, const std::optional<std::string>& view)
      : Stream(std::move(source), config, inflight, threads, std::nullopt, view), pushed_(pushed) {}

  std::uint64_t push(const CloudArrays& arrays, std::uint64_t timestamp_us) {
    Frame frame;
    frame.cloud = owned_cloud(arrays);
    frame.timestamp_us = timestamp_us;
    frame.captured = Clock::now();
    return pushed_.push(std::move(frame));
  }
  void end() { pushed_.close(); }

 private:
  PushSource& pushed_;  // the Stream's source
};

std::unique_ptr<FrameSource> open(const std::string& spec, const SourceLimits& limits) {
  py::gil_scoped_release release;  // a recording is checked frame by frame first
  SourceOptions options;  // the defaults: a recording replays every frame, in order
  options.limits = limits;
  return open_source({spec}, options);
}

constexpr const char* kFrameDoc = R"doc(
One segmented frame of a Replay or Live stream: a Segmentation (labels,
objects, segments, support_plane, as segment(..., segments=True) returns)
with the frame's own fields.

index, timestamp_us: the frame's position in the source and its time stamp
    (a live source's dropped frames leave gaps in index).
points: float32 (H, W, 3) (depth frames) or (N, 3), metres, NaN = no data.
labels: uint32, the points' leading shape: per point the id of its segment
    (with two levels, of its part); ids stay with a segment from frame to frame.
objects: uint32 per-point object ids like labels, or None with one level.
segments: per object a dict (its parts inside): the "objects" list of the
    frame's JSON document (README schema), vectors and axes as float64 arrays.
support_plane: {"id", "normal", "d"} or None. new_ids, gone_ids: lists of ids.
error: "" or why this frame failed (its labels are then all 0).
)doc";

constexpr const char* kStreamMethodsDoc = R"doc(
Iterate to get Frames in order; close() (or leaving a with block, or deleting
the object) stops the run and waits for its thread. Ctrl-C while waiting for
a frame stops the run and raises KeyboardInterrupt. If the run fails (e.g. a
device disappears) the iteration raises RuntimeError after the last frame.
)doc";

void bind_frame(py::module_& module) {
  // Its labels, objects, segments and support_plane are the Segmentation's.
  py::class_<PyFrame, PySegmentation>(module, "Frame", kFrameDoc)
      .def_readonly("index", &PyFrame::index, "The frame's index in the source (a gap means lost frames).")
      .def_readonly("timestamp_us", &PyFrame::timestamp_us, "The source's time stamp, microseconds (0 if none).")
      .def_readonly("points", &PyFrame::points, "float32 (H, W, 3) or (N, 3) points, NaN = no data.")
      .def_readonly("new_ids", &PyFrame::new_ids, "Ids first seen in this frame.")
      .def_readonly("gone_ids", &PyFrame::gone_ids, "Ids of the previous frame not seen in this one.")
      .def_readonly("error", &PyFrame::error, "Why this frame failed, or \"\".")
      .def("__repr__", [](const PyFrame& frame) {
        return "<lccp_stream.Frame " + std::to_string(frame.index) + ": " + std::to_string(py::len(frame.segments)) +
               " segments" + (frame.error.empty() ? "" : ", error: " + frame.error) + ">";
      });
}

// The iterator and context manager methods Replay and Live share.
template <class Face>
void bind_stream_methods(py::class_<Face>& face) {
  face.def("__iter__", [](py::object self) { return self; })
      .def("__next__", &Face::next, "The next Frame; StopIteration at the end of the stream.")
      .def("close", &Face::close, "Stops the run and waits for its thread (frames not taken are dropped).")
      .def_property_readonly("view_url", &Face::view_url, "The live view's URL (view=...), else None.")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](Face& self, const py::args&) {
        self.close();
        return false;
      });
}

void bind_replay(py::module_& module) {
  py::class_<Replay> replay(module, "Replay", (std::string(R"doc(
Segments every frame of a recording (.oni) in order, none dropped, with the
library's pipeline on a background thread (as lccp replay); also takes .pcd
or .ply files or a folder of them.

path: the recording (str or os.PathLike). config: as segment()'s.
inflight: frames segmented at once. threads: None for every core, or a
count. frames: yield this many frames, the first of the recording (None: all).
view: "[HOST:]PORT" to watch the run in a browser, as lccp replay --view (None: no view).
)doc") + kStreamMethodsDoc).c_str());
  replay.def(py::init([](PathArg path, ConfigArg config, unsigned inflight, std::optional<int> threads,
                         std::optional<std::uint64_t> frames, const std::optional<std::string>& view) {
               const SceneConfig scene_config = config_from(config);
               threads = thread_count(threads);
               // Lossless: the first `frames` of the source are the frames yielded.
               auto source = open(path_string(path), SourceLimits{frames, std::nullopt});
               return std::make_unique<Replay>(std::move(source), scene_config, inflight, threads, frames, view);
             }),
             py::arg("path"), py::arg("config") = "p1", py::arg("inflight") = 2, py::arg("threads") = py::none(),
             py::arg("frames") = py::none(), py::arg("view") = py::none());
  bind_stream_methods(replay);
}

void bind_live(py::module_& module) {
  py::class_<Live> live(module, "Live", (std::string(R"doc(
Segments a live OpenNI2 sensor's frames as they come (as lccp live): the
sensor does not wait, so frames that come while the pipeline (or a slow
consumer of this iterator) has no room are dropped, the oldest first; the
frames yielded show them as gaps in Frame.index.

uri: the device's URI (lccp devices lists them; "virtual://synthetic" is the
built-in virtual sensor). config: as segment()'s. inflight: frames segmented
at once. threads: None for every core, or a count. frames: yield this many
frames (dropped frames do not count: frames=10 yields 10 frames, whatever
their indices; lccp live --frames counts frames taken from the sensor).
seconds: stop this long after the first frame was asked for. None: until
close() or Ctrl-C. view: "[HOST:]PORT" to watch the run in a browser (None: no view).
)doc") + kStreamMethodsDoc).c_str());
  live.def(py::init([](const std::string& uri, ConfigArg config, unsigned inflight, std::optional<int> threads,
                       std::optional<std::uint64_t> frames, std::optional<double> seconds,
                       const std::optional<std::string>& view) {
             const SceneConfig scene_config = config_from(config);
             threads = thread_count(threads);
             if (frames && *frames == 0) throw py::value_error("frames: expected None or a positive number, got 0");
             // The sensor runs on while frames are dropped: the stream counts what it yields.
             auto source = open(uri, SourceLimits{std::nullopt, seconds});
             return std::make_unique<Live>(std::move(source), scene_config, inflight, threads, frames, view);
           }),
           py::arg("uri"), py::arg("config") = "p1", py::arg("inflight") = 2, py::arg("threads") = py::none(),
           py::arg("frames") = py::none(), py::arg("seconds") = py::none(), py::arg("view") = py::none());
  bind_stream_methods(live);
}

void bind_push(py::module_& module) {
  py::class_<Push> push(module, "Push", (std::string(R"doc(
Segments clouds you push (from your own driver or another library), in the
background, as a live source: push() never waits, and when frames come faster
than they are segmented the oldest waiting ones are dropped (`waiting` frames
wait at most; Frame.index shows the gaps). Iterate to get the Frames; end()
says no more frames come, and the iteration stops after the last one.

config: as segment()'s. inflight: frames segmented at once. threads: None for
every core, or a count. waiting: frames kept waiting for the pipeline (>= 1).
view: "[HOST:]PORT" to watch the run in a browser (None: no view).
)doc") + kStreamMethodsDoc).c_str());
  push.def(py::init([](ConfigArg config, unsigned inflight, std::optional<int> threads, std::size_t waiting,
                       const std::optional<std::string>& view) {
             const SceneConfig scene_config = config_from(config);
             threads = thread_count(threads);
             if (waiting == 0) throw py::value_error("waiting: expected a positive number, got 0");
             auto source = std::make_unique<PushSource>(waiting);
             PushSource& pushed = *source;
             return std::make_unique<Push>(std::move(source), pushed, scene_config, inflight, threads, view);
           }),
           py::arg("config") = "p1", py::arg("inflight") = 2, py::arg("threads") = py::none(),
           py::arg("waiting") = 1, py::arg("view") = py::none());
  push.def(
      "push",
      [](Push& self, ArrayArg points, OptionalArrayArg colors, OptionalArrayArg normals, std::uint64_t timestamp_us) {
        return self.push(cloud_arrays(points, colors, normals), timestamp_us);
      },
      py::arg("points"), py::arg("colors") = py::none(), py::arg("normals") = py::none(),
      py::arg("timestamp_us") = 0,
      "Queues a copy of the cloud (arrays as segment() takes them); returns its frame index.");
  push.def("end", &Push::end, "No more frames: the iteration stops after the last one pushed.");
  bind_stream_methods(push);
}

}  // namespace

void bind_streams(py::module_& module) {
  bind_frame(module);
  bind_replay(module);
  bind_live(module);
  bind_push(module);
}

}  // namespace lccp::python
