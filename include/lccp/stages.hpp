#pragma once
// The one list of a frame's stages: the method in the paper's order (Section
// II.B and Appendix A, stages 0-8: LccpSegmenter), then the robot
// application's (Section III.C: parts, geometry and stable ids, SceneSegmenter).
// Every timing report names and orders its columns from this table; the
// streaming pipeline groups the stages into its own nodes
// (lccp/pipeline/pipeline.hpp).
#include <array>
#include <chrono>
#include <cstddef>
#include <numeric>
#include <string_view>

namespace lccp {

enum class Stage : unsigned char {
  support,     // 0. points outside the region of interest, then the support plane (Sec. III.C), left out if the config asks
  voxelize,    // 1. voxel grid with 26-adjacency (A.1, VCCS)
  normals,     // 2. one normal per voxel
  seeds,       // 3. supervoxel seeds on a grid of R_seed
  growth,      // 4. supervoxel growth (VCCS, or the flood)
  adjacency,   // 5. the supervoxel adjacency graph (A.1)
  classify,    // 6. every edge convex or not: CC and SC, eq. (1)-(5) (A.2)
  components,  // 7. connected components over convex edges (A.3)
  filter,      // 8. small segments merged into their largest neighbour (A.4), a label per point
  parts,       // 9. each object partitioned into parts with the part-level config (Fig. 5 C)
  geometry,    // 10. per-segment geometry: size, pose, boundaries, grasp hint
  ids,         // 11. ids matched to the previous frame's (in frame order)
};

struct StageInfo {
  Stage stage;
  std::string_view name;  // column and key names in reports: "<name>_ms"
};

inline constexpr std::array<StageInfo, 12> kStages{{
    {Stage::support, "support"},
    {Stage::voxelize, "voxelize"},
    {Stage::normals, "normals"},
    {Stage::seeds, "seeds"},
    {Stage::growth, "growth"},
    {Stage::adjacency, "adjacency"},
    {Stage::classify, "classify"},
    {Stage::components, "components"},
    {Stage::filter, "filter"},
    {Stage::parts, "parts"},
    {Stage::geometry, "geometry"},
    {Stage::ids, "ids"},
}};
inline constexpr std::size_t kStageCount = kStages.size();

// Stages 0-8: one level of LCCP on one cloud (LccpSegmenter).
inline constexpr std::size_t kLccpStageCount = 9;

// Milliseconds per stage of one frame.
struct StageTimes {
  std::array<double, kStageCount> ms{};

  double& operator[](Stage stage) { return ms[static_cast<std::size_t>(stage)]; }
  double operator[](Stage stage) const { return ms[static_cast<std::size_t>(stage)]; }
  double total_ms() const { return std::accumulate(ms.begin(), ms.end(), 0.0); }
};

// The one stage timer: adds the wall time of its scope to times[stage],
// however the scope ends (a stage that throws keeps the time it took).
class StageTimer {
 public:
  StageTimer(StageTimes& times, Stage stage) : times_(times), stage_(stage) {}
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  ~StageTimer() {
    times_[stage_] += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  StageTimes& times_;
  Stage stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace lccp
