// The pipeline's admission gate between the capture thread and the flow graph,
// driven by plain std::threads (so ThreadSanitizer sees every hand-off: see
// scripts/tsan.sh).
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "../src/pipeline/frame_admission.hpp"

namespace lccp {
namespace {

// Frames "in the graph", released by a consumer thread in the order they entered.
class FakeGraph {
 public:
  void enter(Frame frame, std::uint64_t sequence) {
    std::lock_guard lock(mutex_);
    entered_.push_back({frame.index, sequence});
    in_flight_.fetch_add(1);
    max_in_flight_ = std::max(max_in_flight_, in_flight_.load());
  }
  bool take_one() {
    std::lock_guard lock(mutex_);
    if (taken_ == entered_.size()) return false;
    ++taken_;
    in_flight_.fetch_sub(1);
    return true;
  }
  std::vector<std::pair<std::uint64_t, std::uint64_t>> entered() {
    std::lock_guard lock(mutex_);
    return entered_;
  }
  int max_in_flight() {
    std::lock_guard lock(mutex_);
    return max_in_flight_;
  }

 private:
  std::mutex mutex_;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> entered_;  // (frame index, sequence)
  std::size_t taken_ = 0;
  std::atomic<int> in_flight_{0};
  int max_in_flight_ = 0;
};

Frame frame_with_index(std::uint64_t index) {
  Frame frame;
  frame.index = index;
  return frame;
}

TEST(FrameAdmission, BlockingGateKeepsAtMostKFramesAndLosesNone) {
  constexpr unsigned kSlots = 2;
  constexpr std::uint64_t kFrames = 2000;
  FakeGraph graph;
  detail::FrameAdmission admission(kSlots, [&](Frame f, std::uint64_t sequence) { graph.enter(std::move(f), sequence); });
  std::atomic<bool> capture_done{false};
  std::thread capture([&] {
    for (std::uint64_t i = 0; i < kFrames; ++i) ASSERT_TRUE(admission.enter_when_free(frame_with_index(i)));
    capture_done.store(true);
  });
  std::uint64_t released = 0;
  while (released < kFrames) {
    if (graph.take_one()) {
      admission.release();
      ++released;
    } else {
      std::this_thread::yield();
    }
  }
  capture.join();
  EXPECT_TRUE(capture_done.load());
  const auto entered = graph.entered();
  ASSERT_EQ(entered.size(), kFrames);
  for (std::uint64_t i = 0; i < kFrames; ++i) {
    EXPECT_EQ(entered[i].first, i);
    EXPECT_EQ(entered[i].second, i);
  }
  EXPECT_LE(graph.max_in_flight(), static_cast<int>(kSlots));
  EXPECT_EQ(admission.drop_waiting(), 0u);
}

TEST(FrameAdmission, DropOldestLetsTheNewestInAndCountsEveryDrop) {
  constexpr unsigned kSlots = 1;
  constexpr std::uint64_t kFrames = 3000;
  FakeGraph graph;
  detail::FrameAdmission admission(kSlots, [&](Frame f, std::uint64_t sequence) { graph.enter(std::move(f), sequence); });
  std::atomic<bool> capture_done{false};
  std::thread capture([&] {  // a sensor that never waits
    for (std::uint64_t i = 0; i < kFrames; ++i) admission.enter_or_wait(frame_with_index(i));
    capture_done.store(true);
  });
  std::thread consumer([&] {  // a slower graph
    while (true) {
      if (graph.take_one()) {
        std::this_thread::yield();
        admission.release();
      } else if (capture_done.load()) {
        return;
      } else {
        std::this_thread::yield();
      }
    }
  });
  capture.join();
  consumer.join();
  while (graph.take_one()) admission.release();  // the last waiting frame got in on a release
  const auto entered = graph.entered();
  const std::uint64_t dropped = admission.drop_waiting();
  EXPECT_EQ(entered.size() + dropped, kFrames);
  ASSERT_FALSE(entered.empty());
  EXPECT_EQ(entered.back().first, kFrames - 1) << "the newest frame must get through";
  for (std::size_t i = 1; i < entered.size(); ++i) {
    EXPECT_GT(entered[i].first, entered[i - 1].first);
    EXPECT_EQ(entered[i].second, i);
  }
  EXPECT_LE(graph.max_in_flight(), static_cast<int>(kSlots));
}

TEST(FrameAdmission, CloseWakesABlockedCaptureThread) {
  FakeGraph graph;
  detail::FrameAdmission admission(1, [&](Frame f, std::uint64_t sequence) { graph.enter(std::move(f), sequence); });
  ASSERT_TRUE(admission.enter_when_free(frame_with_index(0)));
  std::atomic<bool> second_admitted{true};
  std::thread capture([&] { second_admitted.store(admission.enter_when_free(frame_with_index(1))); });
  admission.close();
  capture.join();
  EXPECT_FALSE(second_admitted.load());
  EXPECT_EQ(graph.entered().size(), 1u);
  EXPECT_EQ(admission.drop_waiting(), 0u);  // refused, not taken: no drop
}

TEST(FrameAdmission, AFrameWaitingUnderDropOldestStaysOutOnceClosed) {
  FakeGraph graph;
  detail::FrameAdmission admission(1, [&](Frame f, std::uint64_t sequence) { graph.enter(std::move(f), sequence); });
  admission.enter_or_wait(frame_with_index(0));  // takes the one slot
  admission.enter_or_wait(frame_with_index(1));  // waits
  admission.close();
  admission.release();  // the slot is free, but no frame enters after close()
  EXPECT_EQ(graph.entered().size(), 1u);
  EXPECT_EQ(admission.drop_waiting(), 1u);
}

}  // namespace
}  // namespace lccp
