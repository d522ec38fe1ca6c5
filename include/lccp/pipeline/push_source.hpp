#pragma once
// A live FrameSource for frames that arrive from outside the library (ROS
// messages, arrays from Python): the caller pushes, the pipeline takes.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <stop_token>

#include "lccp/frame_source.hpp"

namespace lccp {

// At most `capacity` frames wait; a frame pushed when they are all taken up
// pushes out the oldest waiting one (spdlog's overrun_oldest), whose index the
// pipeline then sees as a gap and counts as dropped. Live: the sender does not
// wait, so the pipeline's admission drops the oldest too (DropPolicy::drop_oldest).
class PushSource final : public FrameSource {
 public:
  explicit PushSource(std::size_t capacity = 1);

  // Numbers the frame (0, 1, 2, ... in push order: Frame::index) and queues
  // it; returns its index. Any thread; never blocks.
  std::uint64_t push(Frame frame);

  // No more frames: next() returns the waiting ones, then nullopt.
  void close();

  std::optional<Frame> next(std::stop_token stop) override;
  std::optional<std::uint64_t> frame_count() const override { return std::nullopt; }
  bool is_live() const override { return true; }

 private:
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable_any ready_;
  std::deque<Frame> waiting_;
  std::uint64_t next_index_ = 0;
  bool closed_ = false;
};

}  // namespace lccp
