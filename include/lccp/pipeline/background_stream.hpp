#pragma once
// A stream run in the background: frames from a source through the Pipeline on
// a thread the stream owns, in a oneTBB task arena of its own. The faces that
// must not block on a run (the Python module, the ROS node) use it and hold no
// thread, queue or stop source of their own; `lccp replay` and `live` call
// Pipeline::run on their main thread instead.
//
//   stream thread: Pipeline::run(source, ...) in the arena
//     with a sink:  sink(result) on a TBB thread, in frame order, one at a time
//     without one:  result -> hand-off queue (at most hand_off_frames) -> next()
//
// Overflow of the hand-off queue: the pipeline waits for room, so a consumer
// that does not keep up slows the run and loses nothing; a live source then
// drops its oldest frames at the pipeline's admission (DropPolicy::drop_oldest),
// as it would behind a slow stage, and the stats count them.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <stop_token>
#include <string>
#include <thread>

#include "lccp/frame_source.hpp"
#include "lccp/objects/scene.hpp"
#include "lccp/pipeline/pipeline.hpp"

namespace lccp {

struct StreamConfig {
  unsigned frames_in_flight = 2;    // K, as PipelineConfig
  int threads = 0;                  // threads of the stream's task arena; 0: every core
  std::size_t hand_off_frames = 2;  // results waiting for next(), at most (no sink)
  RunObserver* observer = nullptr;  // as PipelineConfig (the live view); outlives the stream
};

class BackgroundStream {
 public:
  using Sink = std::function<void(FrameResult&)>;
  enum class Next { frame, waiting, ended };

  // Starts the run over `source`, which must outlive the stream. Throws
  // lccp::Error for a bad config or frames_in_flight == 0.
  BackgroundStream(const SceneConfig& config, FrameSource& source, StreamConfig stream, Sink sink = {});
  ~BackgroundStream();  // stop()
  BackgroundStream(const BackgroundStream&) = delete;
  BackgroundStream& operator=(const BackgroundStream&) = delete;

  // Without a sink: the next result into `out` (Next::frame), or Next::waiting
  // after `timeout`, or Next::ended once the run is over and every result taken.
  Next next(FrameResult& out, std::chrono::milliseconds timeout);

  // No more frames are taken; returns at once.
  void request_stop() { stop_.request_stop(); }

  // Requests a stop and waits for the run to end: the frames in flight are
  // finished (a sink gets them; without one they are dropped, as are the
  // results not taken). How the run ended: its counts (they add up) and the
  // source's or the sink's error.
  const PipelineOutcome& stop();

  // The counts so far (LiveStats), from any thread.
  PipelineStats stats() const { return live_.snapshot(); }

 private:
  class HandOff;
  void run(FrameSource& source);
  void deliver(FrameResult& result);

  SceneSegmenter segmenter_;
  Pipeline pipeline_;  // refers to segmenter_
  Sink sink_;
  int threads_;
  std::unique_ptr<HandOff> hand_off_;
  std::stop_source stop_;
  LiveStats live_;
  PipelineOutcome outcome_;  // the stream thread's until joined
  std::mutex join_mutex_;
  std::thread thread_;  // last: it starts once everything it uses exists
};

}  // namespace lccp
