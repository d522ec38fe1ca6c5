#pragma once
// The streaming pipeline: a oneTBB flow graph that segments a stream of frames
// with several frames in flight and hands results over in frame order.
//
//   source -> limiter(K) -> back-projection -> voxelize + normals
//          -> supervoxels -> classify + label + filter -> sequencer -> sink
//                                                              \-> limiter decrement
#include <atomic>
#include <cstdint>
#include <functional>

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
  double end_to_end_ms() const {     // frame captured -> labels ready
    return std::chrono::duration<double, std::milli>(labels_ready - frame.captured).count();
  }
};

struct PipelineStats {
  std::uint64_t frames_received = 0;  // taken from the source
  std::uint64_t frames_completed = 0; // handed to the sink
  std::uint64_t frames_dropped = 0;   // dropped by the policy, plus gaps in the source's frame index
  double wall_seconds = 0;
};

class Pipeline {
 public:
  // Throws lccp::Error for frames_in_flight == 0.
  Pipeline(const LccpSegmenter& segmenter, PipelineConfig config);

  // Pulls frames until the source ends (or stop()); calls `sink` for every
  // completed frame in frame order, one call at a time. If the source or a
  // stage throws, frames already in flight are finished and handed to the
  // sink, then the error is rethrown.
  PipelineStats run(FrameSource& source, const std::function<void(FrameResult&)>& sink);

  // Ends run() soon: no new frames are taken, frames in flight complete.
  // Thread-safe.
  void stop();

 private:
  const LccpSegmenter& segmenter_;
  PipelineConfig config_;
  std::atomic<bool> stop_requested_{false};
};

}  // namespace lccp
