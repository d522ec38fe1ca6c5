// Replaying an .oni recording: our reader (open_recording, src/capture/oni_reader.*)
// against OpenNI2's own file player in manual playback (what open_recording used
// before), both reading every depth frame of the same recording in order. Opening
// and closing are outside the timed region: the figure is the capture thread's
// work per frame. Usage: bench_oni_read [--benchmark_* flags] (recording: mosd_scenes.oni).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "../tests/openni2_player.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/process.hpp"

namespace {

const std::filesystem::path kRecording = LCCP_DEFAULT_RECORDING;

void BM_ReplayOurReader(benchmark::State& state) {
  std::int64_t frames = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto source = lccp::open_recording(kRecording);
    state.ResumeTiming();
    while (std::optional<lccp::Frame> frame = source->next({})) {
      benchmark::DoNotOptimize(frame->depth->depth_mm.data());
      ++frames;
    }
    state.PauseTiming();
    source.reset();
    state.ResumeTiming();
  }
  state.SetItemsProcessed(frames);
}

void BM_ReplayOpenNI2Player(benchmark::State& state) {
  std::int64_t frames = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto player = std::make_unique<lccp::test::OpenNI2Player>(kRecording);
    state.ResumeTiming();
    for (int i = 0; i < player->frames(); ++i) {
      std::optional<lccp::Frame> frame = player->next();
      if (!frame) throw std::runtime_error("OpenNI2's player stopped early");
      benchmark::DoNotOptimize(frame->depth->depth_mm.data());
      ++frames;
    }
    state.PauseTiming();
    player.reset();
    state.ResumeTiming();
  }
  state.SetItemsProcessed(frames);
}

BENCHMARK(BM_ReplayOurReader)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReplayOpenNI2Player)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  lccp::keep_freed_memory_for_next_frames();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
