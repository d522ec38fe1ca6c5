#pragma once
// Internal: the gate between the capture thread and the flow graph. At most
// `slots` frames are in the graph at once; frames are numbered 0, 1, 2, ... in
// the order they enter, which is the order the sequencer restores.
//
// DropPolicy::block: the capture thread waits for a free slot (lossless).
// DropPolicy::drop_oldest: a frame that finds no free slot waits in the gate;
// a newer one takes its place and the older one counts as dropped (spdlog's
// overrun_oldest with a queue of one). The waiting frame enters as soon as a
// frame leaves the graph.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <utility>

#include "lccp/frame.hpp"

namespace lccp::detail {

class FrameAdmission {
 public:
  // Puts the frame into the graph (never blocks).
  using Enter = std::function<void(Frame frame, std::uint64_t sequence)>;

  FrameAdmission(unsigned slots, Enter enter) : free_(slots), enter_(std::move(enter)) {}

  // DropPolicy::block: waits for a free slot, then lets the frame in. Returns
  // false after close(): the frame is refused (not taken, so not dropped).
  bool enter_when_free(Frame frame) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return free_ > 0 || closed_; });
    if (closed_) return false;
    --free_;
    const std::uint64_t sequence = next_sequence_++;
    lock.unlock();
    enter_(std::move(frame), sequence);
    return true;
  }

  // DropPolicy::drop_oldest: lets the frame in if a slot is free; otherwise it
  // waits, and the frame that was waiting is dropped. Returns false after
  // close(): the frame is refused (not taken, so not dropped).
  bool enter_or_wait(Frame frame) {
    std::unique_lock lock(mutex_);
    if (closed_) return false;
    if (waiting_) ++dropped_;
    waiting_ = std::move(frame);
    admit_waiting(lock);
    return true;
  }

  // A frame left the graph: its slot goes to the waiting frame, if any.
  void release() {
    std::unique_lock lock(mutex_);
    ++free_;
    changed_.notify_all();
    admit_waiting(lock);
  }

  // No frame enters from now on (a stop): a waiting enter_when_free() returns
  // false, and a frame waiting under drop_oldest stays out.
  void close() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
  }

  // Drops the frame still waiting (run() has ended) and returns every drop so far:
  // frames replaced under drop_oldest, and this one.
  std::uint64_t drop_waiting() {
    std::lock_guard lock(mutex_);
    if (waiting_) ++dropped_;
    waiting_.reset();
    return dropped_;
  }

 private:
  void admit_waiting(std::unique_lock<std::mutex>& lock) {
    if (!waiting_ || free_ == 0 || closed_) return;
    --free_;
    Frame frame = std::move(*waiting_);
    waiting_.reset();
    const std::uint64_t sequence = next_sequence_++;
    lock.unlock();
    enter_(std::move(frame), sequence);
  }

  std::mutex mutex_;
  std::condition_variable changed_;
  unsigned free_;
  std::uint64_t next_sequence_ = 0;
  std::optional<Frame> waiting_;
  std::uint64_t dropped_ = 0;
  bool closed_ = false;
  Enter enter_;
};

}  // namespace lccp::detail
