#pragma once
// The streaming pipeline: a oneTBB flow graph that segments a stream of frames
// with several frames in flight and hands results over in frame order.
//
//   source (read on a capture thread) -> limiter(K) -> back-projection
//          -> voxelize + normals -> supervoxels -> classify + label + filter
//          -> sequencer -> sink -> limiter decrement
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "lccp/capture/frame_source.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/frame.hpp"

namespace lccp {

// What happens to a frame that arrives while K frames are already in flight.
enum class DropPolicy {
  block,        // wait: lossless (recordings, files)
  drop_oldest,  // a live source keeps running: the oldest waiting frame is dropped, the newest gets through
};

struct PipelineConfig {
  unsigned frames_in_flight = 2;  // K >= 1
  DropPolicy drop_policy = DropPolicy::block;
};

struct FrameResult {
  Frame frame;                      // its cloud is filled (back-projected if it came as depth)
  SegmentationResult segmentation;  // labels per point of frame.cloud
  double back_projection_ms = 0;
  Clock::time_point labels_ready{};  // when the last stage finished
  // Empty if every stage succeeded. Otherwise the failing stage's message (e.g.
  // "no finite points"): the frame still reaches the sink, in order, with
  // every label 0 (one per point of frame.cloud) and the stage times measured
  // up to the failure; the stream goes on.
  std::string error;
  double end_to_end_ms() const {     // frame captured -> labels ready
    return std::chrono::duration<double, std::milli>(labels_ready - frame.captured).count();
  }
};

// When run() returns normally: frames_received + (index gaps) ==
// frames_completed + frames_dropped, i.e. every frame taken from the source is
// either handed to the sink or dropped by the policy (drop_oldest only).
struct PipelineStats {
  std::uint64_t frames_received = 0;  // taken from the source
  std::uint64_t frames_completed = 0; // handed to the sink (calls that returned)
  std::uint64_t frames_dropped = 0;   // dropped by the policy (including a frame left waiting at stop),
                                      // plus gaps in the source's frame index (b - a - 1 for index a then b)
  double wall_seconds = 0;
};

class Pipeline {
 public:
  // Throws lccp::Error for frames_in_flight == 0.
  Pipeline(const LccpSegmenter& segmenter, PipelineConfig config);

  // Pulls frames until the source ends (or stop()); calls `sink` for every
  // completed frame in frame order, one call at a time, on a TBB thread.
  // A stage error stays with its frame (FrameResult::error). If the source
  // throws, frames already in flight are finished and handed to the sink,
  // then the source's exception is rethrown. If the sink throws, no new
  // frames are taken, frames in flight are finished without calling the sink
  // again, and the sink's exception is rethrown.
  PipelineStats run(FrameSource& source, const std::function<void(FrameResult&)>& sink);

  // Ends run() soon: no new frames are taken (the source's request_stop()
  // unblocks a waiting next()), frames in flight complete and reach the sink.
  // Called while no run() is active, it makes the next run() take no frames.
  // Thread-safe and lock-free (atomics only).
  void stop();

 private:
  const LccpSegmenter& segmenter_;
  PipelineConfig config_;
  std::atomic<bool> stop_requested_{false};
  std::atomic<FrameSource*> running_source_{nullptr};  // set while run() is active
  std::atomic<int> stops_in_progress_{0};               // run() waits for these before returning
};

}  // namespace lccp
