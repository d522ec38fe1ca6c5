// The streaming pipeline as a oneTBB flow graph:
//
//   capture thread --(admission: K slots)--> entry (async_node gateway)
//     -> back-projection -> one node per kPipelineNodes entry but the last
//        (consecutive stages of kStages) -> sequencer
//     -> deliver (serial, in frame order: stable ids with the run's tracker, then the sink)
//     -> the slot goes back to admission
//
// The source is read on a thread of its own, never on a TBB thread: a blocking
// next() (a sensor between frames) would otherwise hold a worker that the
// frames in flight need, and with one thread stall them until the next frame.
// Admission is the one bound on frames in flight.
#include "lccp/pipeline/pipeline.hpp"

#include <chrono>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <thread>
#include <vector>

#include <tbb/flow_graph.h>
#include <tbb/task_arena.h>

#include "frame_admission.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/error.hpp"
#include "lccp/synthetic/tabletop_scene.hpp"

namespace lccp {
namespace {

namespace flow = tbb::flow;

// One frame on its way through the graph. The stages move their results along
// in `work`, so clouds are never copied.
struct FrameInFlight {
  std::uint64_t sequence = 0;  // 0, 1, 2, ... in the order frames entered the graph
  FrameResult result;
  std::optional<SceneWork> work;  // over result.frame.cloud, once it exists
};
using Message = std::shared_ptr<FrameInFlight>;
using Entry = flow::async_node<flow::continue_msg, Message>;
using Node = flow::function_node<Message, Message>;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The message of what `f` threw, or nullopt if it returned.
template <typename F>
std::optional<std::string> error_of(F&& f) {
  try {
    f();
    return std::nullopt;
  } catch (const std::exception& e) {
    return *e.what() ? e.what() : "unknown error";
  } catch (...) {
    return "unknown error";
  }
}

// Runs one step of a frame unless an earlier one failed; an exception becomes
// the frame's error instead of cancelling the graph. Isolated: a thread
// waiting inside the stage's parallel loops does not start another frame's
// stage, or the user's sink, on top of it.
template <typename Step>
void run_guarded(FrameInFlight& f, Step&& step) {
  if (!f.result.error.empty()) return;
  if (auto error = error_of([&] { tbb::this_task_arena::isolate(step); })) f.result.error = std::move(*error);
}

Message back_project_frame(const Message& message) {
  FrameInFlight& f = *message;
  Frame& frame = f.result.frame;
  if (frame.depth) {
    const Clock::time_point begin = Clock::now();
    run_guarded(f, [&] {
      frame.cloud = back_project(*frame.depth);
      frame.depth.reset();
    });
    f.result.back_projection_ms = ms_since(begin);
  }
  if (f.result.error.empty()) f.work.emplace(frame.cloud);
  return message;
}

// After the last stage: the result leaves `work`, which is freed. A failed
// frame has no segment: every point unlabelled, the stage times kept.
void finish_frame(FrameInFlight& f) {
  SceneSegmentation& segmentation = f.result.segmentation;
  if (f.work) segmentation = f.work->take_result();
  f.work.reset();
  if (!f.result.error.empty()) {
    const StageTimes times = segmentation.times;
    segmentation = SceneSegmentation{};
    segmentation.labels.assign(f.result.frame.cloud.size(), 0);
    segmentation.times = times;
  }
  f.result.labels_ready = Clock::now();
}

// Calls f when the scope ends, however it ends.
template <typename F>
class OnExit {
 public:
  explicit OnExit(F f) : f_(std::move(f)) {}
  OnExit(const OnExit&) = delete;
  OnExit& operator=(const OnExit&) = delete;
  ~OnExit() { f_(); }

 private:
  F f_;
};

// One run(): the graph, the capture thread's loop, the counts and the first error.
class Run {
 public:
  Run(const SceneSegmenter& segmenter, FrameSource& source, const std::function<void(FrameResult&)>& sink,
      const PipelineConfig& config, std::stop_token stop, LiveStats* live);
  PipelineOutcome execute();

 private:
  Message run_node(const PipelineNode& node, const Message& message) const;
  void warm_up();
  void capture_frames();
  void take(Frame frame);
  void deliver(const Message& message);
  void fail(std::string error);

  const SceneSegmenter& segmenter_;
  SegmentTracker tracker_;  // the ids stage's, in deliver_ only
  FrameSource& source_;
  const std::function<void(FrameResult&)>& sink_;
  RunObserver* const observer_;  // sees each frame before the sink
  const DropPolicy policy_;
  const std::uint64_t warm_up_frames_;  // the first sequence numbers: thrown away at the end
  std::stop_source halt_;  // no more frames: the caller's stop or a sink error
  detail::FrameAdmission admission_;
  flow::graph graph_;
  Entry entry_;
  Node back_projection_;
  std::vector<std::unique_ptr<Node>> stage_nodes_;  // one per kPipelineNodes entry but the last (deliver_'s)
  flow::sequencer_node<Message> in_order_;
  flow::function_node<Message> deliver_;
  std::stop_callback<std::function<void()>> close_on_halt_;
  std::stop_callback<std::function<void()>> halt_on_stop_;

  std::mutex error_mutex_;
  std::string error_;                      // the first error, under error_mutex_
  std::optional<std::uint64_t> last_index_;  // the capture thread's
  LiveStats own_stats_;
  LiveStats& stats_;                       // received, gaps: capture thread; the rest: deliver_
  bool sink_failed_ = false;               // deliver_ only (a serial node)
};

Run::Run(const SceneSegmenter& segmenter, FrameSource& source, const std::function<void(FrameResult&)>& sink,
         const PipelineConfig& config, std::stop_token stop, LiveStats* live)
    : segmenter_(segmenter),
      tracker_(segmenter.new_tracker()),
      source_(source),
      sink_(sink),
      observer_(config.observer),
      policy_(drop_policy_for(source)),
      warm_up_frames_(config.warm_up && source.is_live() ? config.frames_in_flight : 0),
      admission_(config.frames_in_flight,
                 [this](Frame frame, std::uint64_t sequence) {
                   auto message = std::make_shared<FrameInFlight>();
                   message->sequence = sequence;
                   message->result.frame = std::move(frame);
                   // Admission holds a slot for it: the graph takes it at once.
                   if (!entry_.gateway().try_put(message)) throw Error("pipeline: the graph refused a frame");
                 }),
      // Frames come in through this node's gateway, put by the capture thread (or
      // by deliver_, for a frame waiting under drop_oldest). Its body never runs.
      entry_(graph_, flow::serial, [](const flow::continue_msg&, Entry::gateway_type&) {}),
      back_projection_(graph_, flow::unlimited, back_project_frame),
      in_order_(graph_, [](const Message& message) { return message->sequence; }),
      deliver_(graph_, flow::serial, [this](const Message& message) {
        deliver(message);
        return flow::continue_msg{};
      }),
      close_on_halt_(halt_.get_token(), [this] { admission_.close(); }),
      halt_on_stop_(std::move(stop), [this] { halt_.request_stop(); }),
      stats_(live ? *live : own_stats_) {
  flow::make_edge(entry_, back_projection_);
  flow::sender<Message>* previous = &back_projection_;
  for (const PipelineNode& node : std::span(kPipelineNodes).first(kPipelineNodes.size() - 1)) {
    stage_nodes_.push_back(std::make_unique<Node>(
        graph_, flow::unlimited, [this, &node](const Message& message) { return run_node(node, message); }));
    flow::make_edge(*previous, *stage_nodes_.back());
    previous = stage_nodes_.back().get();
  }
  flow::make_edge(*previous, in_order_);
  flow::make_edge(in_order_, deliver_);
}

Message Run::run_node(const PipelineNode& node, const Message& message) const {
  FrameInFlight& f = *message;
  for (const StageInfo& info : kStages) {
    if (node.contains(info.stage)) run_guarded(f, [&] { segmenter_.run_stage(info.stage, *f.work); });
  }
  return message;
}

void Run::fail(std::string error) {
  std::lock_guard lock(error_mutex_);
  if (error_.empty()) error_ = std::move(error);
}

// A live source's first frames would otherwise cost twice the rest: each of
// the K slots faults in its memory, and the workers start, on them. So K
// frames of the synthetic table-top scene (VGA, with a Kinect's noise) go
// through the graph first, and deliver() throws them away. The K slots are
// free, so none waits; this thread then works on them (wait_for_all) until
// they are done: with one thread it is the only one that can.
void Run::warm_up() {
  const synthetic::TabletopScene scene;
  for (std::uint64_t i = 0; i < warm_up_frames_; ++i) {
    Frame frame;
    frame.depth = scene.render(i).depth;
    if (!admission_.enter_when_free(std::move(frame))) break;
  }
  graph_.wait_for_all();
}

// The capture thread: reads the source until it ends or fails or a halt, and
// hands every frame to admission. The graph stays busy until this returns.
void Run::capture_frames() {
  const OnExit done([&] { entry_.gateway().release_wait(); });
  const std::stop_token halted = halt_.get_token();
  const auto error = error_of([&] {
    while (!halted.stop_requested()) {
      std::optional<Frame> frame = source_.next(halted);
      if (!frame) return;
      take(std::move(*frame));
    }
  });
  if (error) fail(*error);  // the frames taken so far, a waiting one included, still complete
}

// A frame the source hands over once the run is stopping (admission closed) is
// not received: the stop came first, as if it had come a moment earlier. So a
// replay stopped by Ctrl-C drops nothing, and a live run counts as dropped only
// the frames it had no room for.
void Run::take(Frame frame) {
  const std::uint64_t index = frame.index;
  const bool entered = policy_ == DropPolicy::drop_oldest ? admission_.enter_or_wait(std::move(frame))
                                                          : admission_.enter_when_free(std::move(frame));
  if (!entered) return;
  const std::uint64_t gap = last_index_ && index > *last_index_ + 1 ? index - *last_index_ - 1 : 0;
  last_index_ = index;
  stats_.update([&](PipelineStats& s) {
    ++s.frames_received;
    s.sensor_gaps += gap;
    s.frames_dropped += gap;  // never handed to the sink
  });
}

void Run::deliver(const Message& message) {
  FrameInFlight& f = *message;
  const bool warming_up = f.sequence < warm_up_frames_;
  // A warm-up frame's tracker is thrown away, but touches what the stream's will;
  // a batch of files: ids 1..K per frame.
  std::optional<SegmentTracker> thrown_away;
  if (warming_up) thrown_away.emplace(segmenter_.new_tracker());
  SegmentTracker* tracker = warming_up ? &*thrown_away : source_.is_stream() ? &tracker_ : nullptr;
  run_guarded(f, [&] { segmenter_.assign_ids(*f.work, tracker); });
  finish_frame(f);
  if (warming_up) {
    f.result = FrameResult{};
    admission_.release();
    return;
  }
  FrameResult& result = f.result;
  const bool stage_failed = !result.error.empty();  // before the sink, which may move the result
  std::uint64_t PipelineStats::*count = &PipelineStats::frames_dropped;
  if (!sink_failed_) {
    if (auto error = error_of([&] {
          if (observer_) observer_->publish(result, stats_.snapshot());
          sink_(result);
        })) {
      sink_failed_ = true;
      fail(std::move(*error));
      halt_.request_stop();  // no more frames: the sink cannot take them
    }
    count = sink_failed_ || stage_failed ? &PipelineStats::frames_failed : &PipelineStats::frames_completed;
  }
  stats_.update([&](PipelineStats& s) { ++(s.*count); });
  result = FrameResult{};  // free the frame now, not when the last copy of the pointer goes
  admission_.release();
}

PipelineOutcome Run::execute() {
  const Clock::time_point start = Clock::now();
  warm_up();
  entry_.gateway().reserve_wait();  // released by the capture thread when it ends
  std::thread capture;
  try {
    capture = std::thread([this] { capture_frames(); });
  } catch (...) {
    entry_.gateway().release_wait();
    throw;
  }
  const OnExit join_if_failed([&] {  // only if wait_for_all() threw
    if (!capture.joinable()) return;
    halt_.request_stop();
    capture.join();
  });
  graph_.wait_for_all();
  capture.join();
  // Joined: a frame still waiting at the end never entered.
  const std::uint64_t waiting = admission_.drop_waiting();
  stats_.update([&](PipelineStats& s) {
    s.frames_dropped += waiting;
    s.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  });
  std::lock_guard lock(error_mutex_);
  return {stats_.snapshot(), error_};
}

}  // namespace

Pipeline::Pipeline(const SceneSegmenter& segmenter, PipelineConfig config) : segmenter_(segmenter), config_(config) {
  if (config_.frames_in_flight == 0) throw Error("frames_in_flight must be at least 1");
}

PipelineOutcome Pipeline::run(FrameSource& source, const std::function<void(FrameResult&)>& sink,
                              std::stop_token stop, LiveStats* live) const {
  Run run(segmenter_, source, sink, config_, std::move(stop), live);
  PipelineOutcome outcome = run.execute();
  if (config_.observer) config_.observer->finish(outcome.stats);
  return outcome;
}

}  // namespace lccp
