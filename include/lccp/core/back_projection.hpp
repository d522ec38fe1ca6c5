#pragma once
// Depth image to organized point cloud (the pipeline's first stage).
#include "lccp/cloud.hpp"
#include "lccp/frame.hpp"

namespace lccp {

// Pinhole model from the fields of view, as OpenNI2's CoordinateConverter:
// fx = W / (2 tan(hfov/2)), fy = H / (2 tan(vfov/2)), cx = W/2, cy = H/2.
// Output in metres in the optical frame PCL and ROS use (x right, y down,
// z forward): OpenNI2's world y (up) negated. Pixels with depth 0 become NaN
// points, so the cloud stays organized (width x height).
PointCloud back_project(const DepthImage& depth);

}  // namespace lccp
