// Reads a point cloud, segments it with a preset, prints its segments:
//   segment_cloud CLOUD.pcd [PRESET_OR_YAML]
#include <cstdio>
#include <exception>

#include "lccp/lccp_stream.hpp"

int main(int argc, char** argv) try {
  if (argc < 2) {
    std::fprintf(stderr, "usage: segment_cloud CLOUD.pcd|.ply [PRESET_OR_YAML]\n");
    return 2;
  }
  const lccp::PointCloud cloud = lccp::read_cloud(argv[1]).cloud;
  const lccp::SceneSegmenter segmenter(lccp::load_preset_or_file(argc > 2 ? argv[2] : "p1"));
  const lccp::SceneSegmentation scene = segmenter.segment(cloud);

  std::printf("%zu points, %u objects, %u segments\n", cloud.size(), scene.object_count, scene.segment_count);
  for (const lccp::ObjectSegments& object : scene.segments) {
    const lccp::SegmentGeometry& g = object.object;
    std::printf("object %u: %llu points, centroid %.3f %.3f %.3f m, box %.3f x %.3f x %.3f m, %zu parts\n", g.id,
                static_cast<unsigned long long>(g.points), g.centroid.x(), g.centroid.y(), g.centroid.z(),
                g.obb.extents.x(), g.obb.extents.y(), g.obb.extents.z(), object.parts.size());
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "segment_cloud: %s\n", e.what());
  return 1;
}
