#pragma once
// The one list of a frame's stages: the method in the paper's order (Section
// II.B and Appendix A, stages 1-8), framed by the robot application's (Section
// III.C): the support plane before, parts, geometry and stable ids after. The
// segmenters run them in this order, the streaming pipeline groups them into its
// flow-graph nodes by `node`, and every timing report names and orders its
// columns from this table.
#include <array>
#include <cstddef>
#include <numeric>
#include <string_view>

namespace lccp {

enum class Stage : unsigned char {
  support,     // 0. points outside the region of interest, then the support plane (Sec. III.C), left out if the config asks
  voxelize,    // 1. voxel grid with 26-adjacency (A.1, VCCS)
  normals,     // 2. one normal per voxel
  seeds,       // 3. supervoxel seeds on a grid of R_seed
  growth,      // 4. VCCS growth in the weighted feature space
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
  unsigned node;          // the pipeline's flow-graph node that runs it (kPipelineNodes)
};

inline constexpr std::array<StageInfo, 12> kStages{{
    {Stage::support, "support", 0},
    {Stage::voxelize, "voxelize", 0},
    {Stage::normals, "normals", 0},
    {Stage::seeds, "seeds", 1},
    {Stage::growth, "growth", 1},
    {Stage::adjacency, "adjacency", 2},
    {Stage::classify, "classify", 2},
    {Stage::components, "components", 2},
    {Stage::filter, "filter", 2},
    {Stage::parts, "parts", 3},
    {Stage::geometry, "geometry", 3},
    {Stage::ids, "ids", 4},
}};
inline constexpr std::size_t kStageCount = kStages.size();

// Stages 0-8: one level of LCCP on one cloud (LccpSegmenter).
inline constexpr std::size_t kLccpStageCount = 9;

// The pipeline's nodes, each a run of consecutive stages of kStages. Every node
// but the last runs frames in parallel; the last runs them one at a time in frame order.
inline constexpr std::array<std::string_view, 5> kPipelineNodes{"voxelize_normals", "supervoxels", "graph_labels",
                                                               "parts_geometry", "ids"};

// Milliseconds per stage of one frame.
struct StageTimes {
  std::array<double, kStageCount> ms{};

  double& operator[](Stage stage) { return ms[static_cast<std::size_t>(stage)]; }
  double operator[](Stage stage) const { return ms[static_cast<std::size_t>(stage)]; }
  double total_ms() const { return std::accumulate(ms.begin(), ms.end(), 0.0); }
  double node_ms(unsigned node) const {
    double sum = 0;
    for (const StageInfo& info : kStages) sum += info.node == node ? (*this)[info.stage] : 0.0;
    return sum;
  }
};

}  // namespace lccp
