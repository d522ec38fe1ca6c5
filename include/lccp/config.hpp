#pragma once
// Parameters of the LCCP method. Defaults are the paper's parameter set P1
// (Table II, beta_thresh 10 deg); every field carries its unit in its name.
#include <cstdint>

namespace lccp {

// How points are binned into voxels.
enum class Binning {
  automatic,  // camera for organized clouds, euclidean otherwise
  euclidean,  // cubes of voxel_size_m in metres (the paper)
  camera,     // cells of voxel_size_m in (x/z, y/z, ln z): size grows with depth (PCL)
};

struct VoxelConfig {
  float voxel_size_m = 0.005f;  // v
  Binning binning = Binning::automatic;
};

struct SupervoxelConfig {
  float seed_size_m = 0.02f;   // s: seed grid spacing
  float spatial_weight = 1.0f; // w_s, per seed_size_m of distance
  float normal_weight = 4.0f;  // w_n, on 1 - |n1 . n2|
  float color_weight = 0.0f;   // w_c, on |rgb1 - rgb2| / 255
};

struct ConvexityConfig {
  float beta_thresh_deg = 10.0f;        // CC bias, eq. (1)
  bool sanity_criterion = true;         // SC, eq. (4)
  float theta_max_deg = 60.0f;          // eq. (3)
  float beta_off_deg = 25.0f;           // eq. (3)
  float sigmoid_slope_per_deg = 0.25f;  // a in eq. (3)
};

struct FilterConfig {
  std::uint32_t n_filter_supervoxels = 3;  // segments of <= this many supervoxels merge (A.4)
};

struct LccpConfig {
  VoxelConfig voxels;
  SupervoxelConfig supervoxels;
  ConvexityConfig convexity;
  FilterConfig filter;
};

// Throws lccp::Error naming the first out-of-range field.
void validate(const LccpConfig& config);

}  // namespace lccp
