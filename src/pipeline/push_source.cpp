#include "lccp/pipeline/push_source.hpp"

#include "lccp/error.hpp"

namespace lccp {

PushSource::PushSource(std::size_t capacity) : capacity_(capacity) {
  if (capacity_ == 0) throw Error("a push source needs room for at least one frame");
}

std::uint64_t PushSource::push(Frame frame) {
  std::uint64_t index = 0;
  {
    const std::lock_guard lock(mutex_);
    index = next_index_++;
    frame.index = index;
    if (waiting_.size() == capacity_) waiting_.pop_front();
    waiting_.push_back(std::move(frame));
  }
  ready_.notify_one();
  return index;
}

void PushSource::close() {
  {
    const std::lock_guard lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
}

std::optional<Frame> PushSource::next(std::stop_token stop) {
  std::unique_lock lock(mutex_);
  ready_.wait(lock, stop, [&] { return !waiting_.empty() || closed_; });
  if (waiting_.empty()) return std::nullopt;  // closed, or a stop
  Frame frame = std::move(waiting_.front());
  waiting_.pop_front();
  return frame;
}

}  // namespace lccp
