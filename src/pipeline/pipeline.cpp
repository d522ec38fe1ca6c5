// The streaming pipeline as a oneTBB flow graph:
//
//   capture thread --(admission: K slots)--> entry (async_node gateway)
//     -> limiter(K) -> back-projection -> voxelize + normals -> supervoxels
//     -> classify + label + filter -> sequencer -> deliver (serial: the sink)
//     -> limiter decrement, then the slot goes back to admission
//
// The source is read on a thread of its own, never on a TBB thread: a blocking
// next() (a sensor between frames) would otherwise hold a worker that the
// frames in flight need, and with one thread stall them until the next frame.
#include "lccp/pipeline/pipeline.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include <tbb/flow_graph.h>
#include <tbb/task_arena.h>

#include "frame_admission.hpp"
#include "lccp/core/back_projection.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

namespace flow = tbb::flow;

// One frame on its way through the graph. Each stage moves the previous
// stage's output on and frees it, so clouds are never copied.
struct FrameInFlight {
  std::uint64_t sequence = 0;  // 0, 1, 2, ... in the order frames entered the graph
  FrameResult result;
  StageTimes times;
  std::optional<VoxelizedCloud> voxels;
  std::optional<GrownSupervoxels> grown;
};
using Message = std::shared_ptr<FrameInFlight>;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Runs one stage of a frame unless an earlier stage failed; an exception
// becomes the frame's error instead of cancelling the graph. Isolated: a
// thread waiting inside the stage's parallel loops does not start another
// frame's stage, or the user's sink, on top of it.
template <typename Stage>
void run_stage(FrameInFlight& frame, Stage&& stage) {
  if (!frame.result.error.empty()) return;
  try {
    tbb::this_task_arena::isolate(stage);
  } catch (const std::exception& e) {
    frame.result.error = *e.what() ? e.what() : "unknown error";
  } catch (...) {
    frame.result.error = "unknown error";
  }
}

// The first exception of one kind (source or sink), kept for run() to rethrow.
class ErrorSlot {
 public:
  void set(std::exception_ptr error) {
    std::lock_guard lock(mutex_);
    if (!error_) error_ = std::move(error);
  }
  std::exception_ptr get() const {
    std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  mutable std::mutex mutex_;
  std::exception_ptr error_;
};

// Counts the frames taken from the source and the source's own lost frames:
// index a followed by b > a + 1 means b - a - 1 frames never arrived. Used by
// the capture thread only, read after it has been joined.
class ReceivedFrames {
 public:
  void count(std::uint64_t index) {
    ++received_;
    if (last_index_ && index > *last_index_ + 1) lost_ += index - *last_index_ - 1;
    last_index_ = index;
  }
  std::uint64_t received() const { return received_; }
  std::uint64_t lost() const { return lost_; }

 private:
  std::optional<std::uint64_t> last_index_;
  std::uint64_t received_ = 0;
  std::uint64_t lost_ = 0;
};

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

using Entry = flow::async_node<flow::continue_msg, Message>;

// The capture thread: reads the source outside the TBB threads (next() may
// block for a sensor's next frame) and hands every frame to the admission
// gate, until the source ends or fails or `halted` says no more frames are
// wanted. The graph stays busy until this returns.
void capture_frames(FrameSource& source, DropPolicy policy, const std::function<bool()>& halted,
                    ReceivedFrames& received, ErrorSlot& source_error, detail::FrameAdmission& admission,
                    Entry::gateway_type& gateway) {
  const OnExit done([&] { gateway.release_wait(); });
  try {
    while (!halted()) {
      std::optional<Frame> frame = source.next();
      if (!frame) break;
      received.count(frame->index);
      if (policy == DropPolicy::drop_oldest) {
        admission.enter_or_wait(std::move(*frame));
      } else if (!admission.enter_when_free(std::move(*frame))) {
        break;
      }
    }
  } catch (...) {
    source_error.set(std::current_exception());
  }
}

}  // namespace

Pipeline::Pipeline(const LccpSegmenter& segmenter, PipelineConfig config) : segmenter_(segmenter), config_(config) {
  if (config_.frames_in_flight == 0) throw Error("frames_in_flight must be at least 1");
}

void Pipeline::stop() {
  stop_requested_.store(true);
  stops_in_progress_.fetch_add(1);
  if (FrameSource* source = running_source_.load()) source->request_stop();
  stops_in_progress_.fetch_sub(1);
}

PipelineStats Pipeline::run(FrameSource& source, const std::function<void(FrameResult&)>& sink) {
  const Clock::time_point start = Clock::now();
  // stop() reaches this source until run() returns; a stop() that came before
  // run() is honoured, and consumed when run() returns.
  running_source_.store(&source);
  const OnExit unregister([&] {
    running_source_.store(nullptr);
    while (stops_in_progress_.load() != 0) std::this_thread::yield();
    stop_requested_.store(false);
  });

  ReceivedFrames received;
  std::atomic<std::uint64_t> completed{0};
  std::uint64_t dropped = 0;
  ErrorSlot source_error;
  ErrorSlot sink_error;
  std::atomic<bool> sink_failed{false};
  const std::function<bool()> halted = [&] { return stop_requested_.load() || sink_failed.load(); };
  {
    flow::graph graph;

    // Frames come in through this node's gateway, put by the capture thread
    // (or by the sink, for a frame waiting under drop_oldest): no TBB thread
    // ever waits for the source. Its body is never called.
    Entry entry(graph, flow::serial, [](const flow::continue_msg&, Entry::gateway_type&) {});

    flow::limiter_node<Message> in_flight(graph, config_.frames_in_flight);

    flow::function_node<Message, Message> back_projection(graph, flow::unlimited, [](const Message& message) {
      FrameInFlight& f = *message;
      Frame& frame = f.result.frame;
      if (!frame.depth) return message;
      const Clock::time_point begin = Clock::now();
      run_stage(f, [&] {
        frame.cloud = back_project(*frame.depth);
        frame.depth.reset();
      });
      f.result.back_projection_ms = ms_since(begin);
      return message;
    });

    flow::function_node<Message, Message> voxelize(graph, flow::unlimited, [this](const Message& message) {
      FrameInFlight& f = *message;
      run_stage(f, [&] { f.voxels = segmenter_.voxelize_with_normals(f.result.frame.cloud, f.times); });
      return message;
    });

    flow::function_node<Message, Message> supervoxels(graph, flow::unlimited, [this](const Message& message) {
      FrameInFlight& f = *message;
      run_stage(f, [&] { f.grown = segmenter_.grow(std::move(*f.voxels), f.times); });
      f.voxels.reset();
      return message;
    });

    flow::function_node<Message, Message> label(graph, flow::unlimited, [this](const Message& message) {
      FrameInFlight& f = *message;
      SegmentationResult& segmentation = f.result.segmentation;
      run_stage(f, [&] { segmentation = segmenter_.label(*f.grown, f.times); });
      f.grown.reset();
      if (!f.result.error.empty()) {  // a failed frame: no segment, every point unlabelled
        segmentation = SegmentationResult{};
        segmentation.labels.assign(f.result.frame.cloud.size(), 0);
        segmentation.times = f.times;
      }
      f.result.labels_ready = Clock::now();
      return message;
    });

    flow::sequencer_node<Message> in_order(graph, [](const Message& message) { return message->sequence; });

    detail::FrameAdmission admission(config_.frames_in_flight, halted, [&](Frame frame, std::uint64_t sequence) {
      auto message = std::make_shared<FrameInFlight>();
      message->sequence = sequence;
      message->result.frame = std::move(frame);
      // Admission holds a slot for it, so the limiter has room.
      if (!entry.gateway().try_put(message)) throw Error("pipeline: the limiter refused an admitted frame");
    });

    flow::function_node<Message> deliver(graph, flow::serial, [&](const Message& message) {
      if (!sink_failed.load()) {
        try {
          sink(message->result);
          completed.fetch_add(1, std::memory_order_relaxed);
        } catch (...) {
          sink_error.set(std::current_exception());
          sink_failed.store(true);
          source.request_stop();  // unblocks a waiting next(): no more frames are taken
        }
      }
      message->result = FrameResult{};  // free the frame now, not when the last copy of the pointer goes
      // The limiter first, then the gate: a frame the gate lets in always finds room.
      in_flight.decrementer().try_put(flow::continue_msg{});
      admission.release();
      return flow::continue_msg{};
    });

    flow::make_edge(entry, in_flight);
    flow::make_edge(in_flight, back_projection);
    flow::make_edge(back_projection, voxelize);
    flow::make_edge(voxelize, supervoxels);
    flow::make_edge(supervoxels, label);
    flow::make_edge(label, in_order);
    flow::make_edge(in_order, deliver);

    entry.gateway().reserve_wait();  // released by the capture thread when it ends
    std::thread capture;
    try {
      capture = std::thread(capture_frames, std::ref(source), config_.drop_policy, std::cref(halted),
                            std::ref(received), std::ref(source_error), std::ref(admission),
                            std::ref(entry.gateway()));
    } catch (...) {
      entry.gateway().release_wait();
      throw;
    }
    const OnExit join_if_failed([&] {  // only if wait_for_all() threw
      if (!capture.joinable()) return;
      admission.abort();
      source.request_stop();
      capture.join();
    });
    graph.wait_for_all();
    capture.join();
    dropped = admission.drop_waiting();  // a frame still waiting after stop() never entered
  }

  PipelineStats stats;
  stats.frames_received = received.received();
  stats.frames_completed = completed.load();
  stats.frames_dropped = dropped + received.lost();
  stats.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (std::exception_ptr error = source_error.get()) std::rethrow_exception(error);
  if (std::exception_ptr error = sink_error.get()) std::rethrow_exception(error);
  return stats;
}

}  // namespace lccp
