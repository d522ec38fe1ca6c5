#include "lccp/pipeline/background_stream.hpp"

#include <algorithm>
#include <exception>

#include <tbb/task_arena.h>

namespace lccp {

// The results the sink handed over and the consumer has not taken yet: at
// most `capacity`; a full queue makes the pipeline wait (the header's overflow
// policy) until a result is taken or a stop is requested.
class BackgroundStream::HandOff {
 public:
  explicit HandOff(std::size_t capacity) : capacity_(capacity) {}

  // Waits for room; once `stop` is requested the result is dropped (nobody will take it).
  void push(FrameResult& result, std::stop_token stop) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, stop, [&] { return items_.size() < capacity_; });
    if (stop.stop_requested()) return;
    items_.push_back(std::move(result));
    changed_.notify_all();
  }

  Next pop(FrameResult& out, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return !items_.empty() || ended_; });
    if (items_.empty()) return ended_ ? Next::ended : Next::waiting;
    out = std::move(items_.front());
    items_.pop_front();
    changed_.notify_all();
    return Next::frame;
  }

  // The run is over: no more results; `drop` also forgets the waiting ones.
  void end(bool drop) {
    const std::lock_guard lock(mutex_);
    ended_ = true;
    if (drop) items_.clear();
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable_any changed_;
  std::deque<FrameResult> items_;
  std::size_t capacity_;
  bool ended_ = false;
};

BackgroundStream::BackgroundStream(const SceneConfig& config, FrameSource& source, StreamConfig stream, Sink sink)
    : segmenter_(config),
      pipeline_(segmenter_, PipelineConfig{stream.frames_in_flight, stream.observer}),
      sink_(std::move(sink)),
      threads_(stream.threads > 0 ? stream.threads : tbb::task_arena::automatic),
      hand_off_(std::make_unique<HandOff>(std::max<std::size_t>(1, stream.hand_off_frames))),
      thread_([this, &source] { run(source); }) {}

BackgroundStream::~BackgroundStream() { stop(); }

void BackgroundStream::run(FrameSource& source) {
  try {
    tbb::task_arena arena(threads_);  // a nodelet or a Python program shares its process: no global setting
    arena.execute([&] {
      outcome_ = pipeline_.run(source, [this](FrameResult& result) { deliver(result); }, stop_.get_token(), &live_);
    });
  } catch (const std::exception& e) {  // nothing may escape a thread
    outcome_.stats = live_.snapshot();
    outcome_.error = e.what();
  }
  hand_off_->end(false);
}

void BackgroundStream::deliver(FrameResult& result) {
  if (sink_) {
    sink_(result);
  } else {
    hand_off_->push(result, stop_.get_token());
  }
}

BackgroundStream::Next BackgroundStream::next(FrameResult& out, std::chrono::milliseconds timeout) {
  return hand_off_->pop(out, timeout);
}

const PipelineOutcome& BackgroundStream::stop() {
  const std::lock_guard lock(join_mutex_);
  stop_.request_stop();  // wakes a sink waiting for room: it drops its result
  if (thread_.joinable()) thread_.join();
  hand_off_->end(true);
  return outcome_;
}

}  // namespace lccp
