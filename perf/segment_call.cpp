// The C++ side of perf/python_overhead.py: times SceneSegmenter::segment on one
// cloud, called through the shared library lccp_stream as the Python module
// calls it, and prints one time per call (ms), after one warm-up call. KEEP
// (1) calls keep_freed_memory_for_next_frames first, as the lccp tool does.
//   segment_call CLOUD CONFIG CALLS THREADS [KEEP]
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <tbb/task_arena.h>

#include "lccp/io/cloud_io.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/objects/scene.hpp"
#include "lccp/process.hpp"
#include "statistics.hpp"

int main(int argc, char** argv) try {
  if (argc != 5 && argc != 6) {
    std::fprintf(stderr, "usage: segment_call CLOUD CONFIG CALLS THREADS [KEEP]\n");
    return 2;
  }
  if (argc == 6 && std::atoi(argv[5]) == 1) lccp::keep_freed_memory_for_next_frames();
  const lccp::PointCloud cloud = lccp::read_cloud(argv[1]).cloud;
  const lccp::SceneSegmenter segmenter(lccp::load_preset_or_file(argv[2]));
  const int calls = std::atoi(argv[3]);
  tbb::task_arena arena(std::atoi(argv[4]));
  arena.execute([&] {
    segmenter.segment(cloud);
    for (int i = 0; i < calls; ++i) {
      const auto start = std::chrono::steady_clock::now();
      const lccp::SceneSegmentation scene = segmenter.segment(cloud);
      std::printf("%.4f\n", lccp::perf::ms_since(start));
    }
  });
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "segment_call: %s\n", e.what());
  return 1;
}
