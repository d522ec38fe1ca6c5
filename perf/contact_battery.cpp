// Objects resting on a plane and on each other (tests/contact_scenes.hpp: one box,
// dome or upside-down bowl; tests/contact_clutter.hpp: two boxes face to face, a
// box leaning on a box, a can and a mug on their sides), each from 45 and 30 deg
// elevation, organized and unorganized, noise-free and with the Kinect v1 model,
// segmented by LccpSegmenter with the defaults (LccpConfig{}) and with the
// paper's method (config/paper.yaml), and by PCL 1.13's LCCP with the paper's
// parameters, its smoothness check off (as the paper) and on (PCL's strongest
// setting); scored as `lccp eval --ignore 0-9`.
// A view holds when no object is lost into the plane, WOv >= 0.8 for the scene
// and for every object on its own (its OV), and every object's best segment is
// mostly that object (contact_verdict). Prints one
// line per case and view, the failures of the defaults in words, and a summary
// per method; exits 0 (a report, not a test: tests/contact_test.cpp asserts ours).
//
//   build/perf/contact_battery
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "../tests/contact_clutter.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/io/config_file.hpp"
#include "pcl_reference.hpp"

namespace {

using lccp::test::ContactVerdict;

constexpr int kMethods = 4;
constexpr std::array<const char*, kMethods> kMethodNames = {"ours", "paper", "PCL", "PCL+smooth"};

// The flags of a failed view: L an object lost into the plane, M an object's
// best segment mostly another object's (merged), W WOv < 0.8, O an object's own
// OV < 0.8.
std::string flags(const ContactVerdict& v) {
  bool merged = false, low_overlap = false;
  for (const lccp::test::ObjectShare& o : v.objects) {
    merged = merged || (o.share <= 0.5 && o.dominant >= lccp::kLabelsPerObject);
    low_overlap = low_overlap || o.overlap < 0.8;
  }
  std::string f;
  if (!v.lost.empty()) f += 'L';
  if (merged) f += 'M';
  if (v.weighted_overlap < 0.8) f += 'W';
  if (low_overlap) f += 'O';
  return f;
}

struct Methods {
  lccp::LccpSegmenter ours{lccp::LccpConfig{}};
  lccp::LccpConfig paper_config = lccp::load_preset_or_file("paper").objects;
  lccp::LccpSegmenter paper{paper_config};
  lccp::LccpConfig smooth_config = [this] {
    lccp::LccpConfig c = paper_config;
    c.convexity.smoothness_check = true;
    return c;
  }();

  std::array<ContactVerdict, kMethods> run(const lccp::test::ContactScene& scene) const {
    return {lccp::test::contact_verdict(ours.segment(scene.cloud).labels, scene),
            lccp::test::contact_verdict(paper.segment(scene.cloud).labels, scene),
            lccp::test::contact_verdict(lccp::perf::run_pcl_lccp(scene.cloud, paper_config).labels, scene),
            lccp::test::contact_verdict(lccp::perf::run_pcl_lccp(scene.cloud, smooth_config).labels, scene)};
  }
};

struct Tally {
  std::array<int, kMethods> held{};
  int views = 0;
  void add(const std::array<ContactVerdict, kMethods>& v) {
    for (int m = 0; m < kMethods; ++m) held[m] += v[m].held();
    ++views;
  }
  void print(const char* what) const {
    std::printf("held %s:", what);
    for (int m = 0; m < kMethods; ++m) {
      std::printf(" %s %d/%d%s", kMethodNames[m], held[m], views, m + 1 < kMethods ? "," : "\n");
    }
  }
};

void print_header() {
  std::printf("%-48s %-4s %-5s %-6s", "case", "elev", "cloud", "noise");
  for (const char* name : kMethodNames) std::printf(" | %-10s", name);
  std::printf("\n");
}

void print_line(const std::string& name, const lccp::test::ContactView& view,
                const std::array<ContactVerdict, kMethods>& v) {
  std::printf("%-48s %3.0f  %-5s %-6s", name.c_str(), view.elevation_deg, view.organized ? "org" : "unorg",
              view.noisy ? "kinect" : "clean");
  for (const ContactVerdict& verdict : v) std::printf(" | %.3f %-4s", verdict.weighted_overlap, flags(verdict).c_str());
  if (!v[0].held()) std::printf("  ours: %s", v[0].failures().c_str());
  std::printf("\n");
}

}  // namespace

int main() {
  lccp::perf::quiet_pcl_console();
  const Methods methods;
  const std::size_t single_objects = lccp::test::contact_objects().size();
  const std::vector<lccp::test::ContactLayout> layouts = lccp::test::contact_battery_layouts();
  Tally all, clutter;
  print_header();
  for (std::size_t k = 0; k < layouts.size(); ++k) {
    for (const lccp::test::ContactView& view : lccp::test::contact_views()) {
      const std::array<ContactVerdict, kMethods> v = methods.run(lccp::test::contact_scene(layouts[k], view));
      all.add(v);
      if (k >= single_objects) clutter.add(v);
      print_line(layouts[k].name, view, v);
    }
  }
  std::printf("flags: L an object lost into the plane, M an object's best segment mostly another object's, "
              "W WOv < 0.8, O an object's own OV < 0.8\n");
  std::printf("methods: ours = LccpConfig{}, paper = config/paper.yaml, PCL = PCL 1.13 with paper.yaml's "
              "parameters, PCL+smooth = the same with its smoothness check\n");
  clutter.print("(objects touching each other)");
  all.print("(all)");
  return 0;
}
