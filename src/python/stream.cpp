// lccp_stream.Replay and lccp_stream.Live: the library's Pipeline over a source
// opened by open_source, run on a background thread; Python iterates over the
// frames it hands over.
//
//   background std::thread: Pipeline::run(source, sink) in the task arena
//       sink (a TBB thread) -> FrameQueue (a few frames) -> __next__ (Python) -> Frame
//
// One std::stop_source stops the run (close(), Ctrl-C, the end of a with
// block, the object's destruction); the queue's waits watch it, so the sink
// never blocks a stopping pipeline.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <stop_token>
#include <thread>

#include "bindings.hpp"
#include "lccp/capture/open_source.hpp"
#include "lccp/pipeline/pipeline.hpp"

namespace lccp::python {
namespace {

using namespace std::chrono_literals;

// The frames the sink handed over and Python has not taken yet; at most
// `capacity`, so a slow consumer holds back a lossless (recording) pipeline
// instead of piling up frames. A live source drops frames at admission itself.
class FrameQueue {
 public:
  enum class Status { frame, waiting, ended };

  explicit FrameQueue(std::size_t capacity) : capacity_(capacity) {}

  // Waits for room; once `stop` is requested the frame is dropped (nobody will take it).
  void push(FrameResult& result, std::stop_token stop) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, stop, [&] { return items_.size() < capacity_; });
    if (stop.stop_requested()) return;
    items_.push_back(std::move(result));
    changed_.notify_all();
  }

  // The next frame into `out` (Status::frame), or, after waiting up to
  // `timeout`, Status::waiting, or Status::ended once the run ended and every
  // frame was taken.
  Status pop(FrameResult& out, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return !items_.empty() || ended_; });
    if (items_.empty()) return ended_ ? Status::ended : Status::waiting;
    out = std::move(items_.front());
    items_.pop_front();
    changed_.notify_all();
    return Status::frame;
  }

  // The run is over; `error` is why it ended early (empty: the source ended or a stop).
  void end(std::string error) {
    const std::lock_guard lock(mutex_);
    ended_ = true;
    error_ = std::move(error);
    changed_.notify_all();
  }

  // Drops the frames nobody will take.
  void clear() {
    const std::lock_guard lock(mutex_);
    items_.clear();
    changed_.notify_all();
  }

  std::string error() {
    const std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable_any changed_;
  std::deque<FrameResult> items_;
  std::size_t capacity_;
  bool ended_ = false;
  std::string error_;
};

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

// One run of the pipeline over one source, on a thread of its own.
// `frames`: the run stops once that many frames were handed to Python (a
// live source drops frames at admission, so its own count would yield fewer).
class Stream {
 public:
  Stream(std::unique_ptr<FrameSource> source, const SceneConfig& config, unsigned inflight,
         std::optional<int> threads, std::optional<std::uint64_t> frames)
      : segmenter_(config), pipeline_(segmenter_, PipelineConfig{inflight}), source_(std::move(source)),
        threads_(threads), frames_to_yield_(frames), thread_([this] { run(); }) {}
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;
  ~Stream() { close(); }

  PyFrame next();
  void close();

 private:
  void run();
  [[noreturn]] void finish();

  SceneSegmenter segmenter_;
  Pipeline pipeline_;  // refers to segmenter_
  std::unique_ptr<FrameSource> source_;
  std::optional<int> threads_;
  std::optional<std::uint64_t> frames_to_yield_;
  std::uint64_t frames_yielded_ = 0;
  FrameQueue queue_{2};
  std::stop_source stop_;
  std::mutex close_mutex_;
  bool error_raised_ = false;
  std::thread thread_;  // last: it starts once everything it uses exists
};

void Stream::run() {
  std::string error;
  try {
    const std::stop_token stop = stop_.get_token();
    const PipelineOutcome outcome = with_threads(threads_, [&] {
      return pipeline_.run(*source_, [&](FrameResult& result) { queue_.push(result, stop); }, stop);
    });
    error = outcome.error;
  } catch (const std::exception& e) {  // nothing may escape a thread
    error = e.what();
  }
  queue_.end(std::move(error));
}

// Waits with the GIL released, looking for Ctrl-C every 100 ms. With the last
// of `frames` the run is asked to stop (the frames in flight are dropped).
PyFrame Stream::next() {
  if (frames_to_yield_ && frames_yielded_ == *frames_to_yield_) finish();
  FrameResult result;
  for (;;) {
    FrameQueue::Status status;
    {
      py::gil_scoped_release release;
      status = queue_.pop(result, 100ms);
    }
    if (status == FrameQueue::Status::frame) {
      if (frames_to_yield_ && ++frames_yielded_ == *frames_to_yield_) stop_.request_stop();
      return to_python(std::move(result));
    }
    if (status == FrameQueue::Status::ended) finish();
    if (PyErr_CheckSignals() != 0) {  // e.g. KeyboardInterrupt: stop the run, then raise it
      close();
      throw py::error_already_set();
    }
  }
}

// Every frame was taken: StopIteration, or once RuntimeError if the run failed.
void Stream::finish() {
  close();
  const std::string error = queue_.error();
  if (!error.empty() && !error_raised_) {
    error_raised_ = true;
    throw std::runtime_error(error);
  }
  throw py::stop_iteration();
}

// Stops the run: frames in flight are finished and dropped, the thread joined.
void Stream::close() {
  py::gil_scoped_release release;  // the thread may take a moment to finish its frames
  const std::lock_guard lock(close_mutex_);
  stop_.request_stop();  // wakes a sink waiting for room; it drops its frame
  if (thread_.joinable()) thread_.join();
  queue_.clear();
}

// Replay and Live are two faces of Stream with their own constructors.
struct Replay : Stream {
  using Stream::Stream;
};
struct Live : Stream {
  using Stream::Stream;
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
)doc") + kStreamMethodsDoc).c_str());
  replay.def(py::init([](PathArg path, ConfigArg config, unsigned inflight, std::optional<int> threads,
                         std::optional<std::uint64_t> frames) {
               const SceneConfig scene_config = config_from(config);
               threads = thread_count(threads);
               // Lossless: the first `frames` of the source are the frames yielded.
               auto source = open(path_string(path), SourceLimits{frames, std::nullopt});
               return std::make_unique<Replay>(std::move(source), scene_config, inflight, threads, frames);
             }),
             py::arg("path"), py::arg("config") = "p1", py::arg("inflight") = 2, py::arg("threads") = py::none(),
             py::arg("frames") = py::none());
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
close() or Ctrl-C.
)doc") + kStreamMethodsDoc).c_str());
  live.def(py::init([](const std::string& uri, ConfigArg config, unsigned inflight, std::optional<int> threads,
                       std::optional<std::uint64_t> frames, std::optional<double> seconds) {
             const SceneConfig scene_config = config_from(config);
             threads = thread_count(threads);
             if (frames && *frames == 0) throw py::value_error("frames: expected None or a positive number, got 0");
             // The sensor runs on while frames are dropped: the stream counts what it yields.
             auto source = open(uri, SourceLimits{std::nullopt, seconds});
             return std::make_unique<Live>(std::move(source), scene_config, inflight, threads, frames);
           }),
           py::arg("uri"), py::arg("config") = "p1", py::arg("inflight") = 2, py::arg("threads") = py::none(),
           py::arg("frames") = py::none(), py::arg("seconds") = py::none());
  bind_stream_methods(live);
}

}  // namespace

void bind_streams(py::module_& module) {
  bind_frame(module);
  bind_replay(module);
  bind_live(module);
}

}  // namespace lccp::python
