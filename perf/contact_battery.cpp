// Objects resting on a plane (tests/contact_scenes.hpp: boxes, domes, upside-down
// bowls; organized and unorganized; noise-free and with the Kinect v1 model), each
// segmented at P1 by LccpSegmenter (as configured, and with crease-preserving
// normals) and by PCL 1.13's LCCP (smoothness check off, as the paper; and on, PCL's
// strongest setting), scored as `lccp eval --ignore 0-9`.
// A case holds when the object is not lost into the plane and WOv >= 0.8 (the
// object's best segment is mostly the object). Prints one line per case and a
// summary; exits 0 (a report, not a test: tests/contact_test.cpp asserts ours).
//
//   build/perf/contact_battery
#include <cstdio>
#include <string>
#include <vector>

#include "../tests/contact_scenes.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/metrics/scores.hpp"
#include "pcl_reference.hpp"

namespace {

struct Outcome {
  double wov = 0;
  bool apart = false;
};

Outcome score(const lccp::Labels& labels, const lccp::test::ContactScene& scene) {
  const lccp::SegmentationScores s =
      lccp::score_objects(labels, scene.truth, scene.cloud.points, lccp::LabelRange{0, 9});
  return {s.weighted_overlap, s.objects_lost == 0 && s.weighted_overlap >= 0.8};
}

const char* mark(const Outcome& o) { return o.apart ? "   " : " x "; }

}  // namespace

int main() {
  lccp::perf::quiet_pcl_console();
  const lccp::LccpConfig ours_config;  // P1
  lccp::LccpConfig smooth_config, crease_config;
  smooth_config.convexity.smoothness_check = true;
  crease_config.normals.crease_preserving = true;
  const lccp::LccpSegmenter ours(ours_config), ours_crease(crease_config);
  int held[4] = {0, 0, 0, 0}, cases = 0;
  std::printf("%-26s %-5s %-5s %-6s | %-10s | %-10s | %-10s | %-10s\n", "object", "elev", "cloud", "noise", "ours WOv",
              "ours+crease", "PCL WOv", "PCL+smooth");
  for (const lccp::test::ContactObject& object : lccp::test::contact_objects()) {
    for (const double elevation : {45.0, 30.0}) {
      for (const bool organized : {true, false}) {
        for (const bool noisy : {false, true}) {
          lccp::test::ContactView view;
          view.elevation_deg = elevation, view.organized = organized, view.noisy = noisy;
          const lccp::test::ContactScene scene = lccp::test::contact_scene(object, view);
          const Outcome o[4] = {score(ours.segment(scene.cloud).labels, scene),
                                score(ours_crease.segment(scene.cloud).labels, scene),
                                score(lccp::perf::run_pcl_lccp(scene.cloud, ours_config).labels, scene),
                                score(lccp::perf::run_pcl_lccp(scene.cloud, smooth_config).labels, scene)};
          for (int m = 0; m < 4; ++m) held[m] += o[m].apart;
          ++cases;
          std::printf("%-26s %3.0f   %-5s %-6s | %.3f%s | %.3f%s | %.3f%s | %.3f%s\n", object.name.c_str(), elevation,
                      organized ? "org" : "unorg", noisy ? "kinect" : "clean", o[0].wov, mark(o[0]), o[1].wov,
                      mark(o[1]), o[2].wov, mark(o[2]), o[3].wov, mark(o[3]));
        }
      }
    }
  }
  std::printf("apart from the plane (x: lost or WOv < 0.8): ours %d/%d, ours+crease %d/%d, PCL %d/%d, PCL+smooth %d/%d\n",
              held[0], cases, held[1], cases, held[2], cases, held[3], cases);
  return 0;
}
