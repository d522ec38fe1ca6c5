// mosd_accuracy: object segmentation scores on the mOSD test scenes (test0..test64),
// LccpSegmenter and PCL 1.13's LCCP with the same config, scored the same way.
//
// Scoring (paper Appendix B, as `lccp eval --ignore 0-9`): lccp::score_segmentation over finite points only, ground-truth
// labels 0-9 (the table) ignored, with two ground truths:
//   raw    - the file's labels; disjoint parts of one object (50, 51) are separate regions
//   merged - object parts merged: every label >= 20 becomes label / 10 * 10 (50, 51 -> 50)
// Prints markdown (per scene, per OSD category, overall, timing) and optionally JSON.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "lccp/process.hpp"

#include "lccp/config.hpp"
#include "lccp/objects/scene.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/metrics/scores.hpp"
#include "pcl_reference.hpp"
#include "statistics.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kSceneCount = 65;  // test0..test64
constexpr lccp::LabelRange kTable{0, 9};

struct Category {
  const char* name;
  int first;
  int last;
};
// OSD numbering (mOSD/README.md).
constexpr Category kCategories[] = {{"boxes", 0, 15},     {"stacked", 16, 23}, {"occluded", 24, 30},
                                    {"cylindric", 31, 42}, {"mixed", 43, 54},   {"complex", 55, 64}};

const char* category_of(int scene) {
  for (const Category& c : kCategories)
    if (scene >= c.first && scene <= c.last) return c.name;
  return "?";
}

enum class Method { ours, pcl };
constexpr Method kMethods[] = {Method::ours, Method::pcl};
const char* method_name(Method m) { return m == Method::ours ? "ours" : "PCL"; }

enum class GroundTruth { raw, merged };
constexpr GroundTruth kGroundTruths[] = {GroundTruth::raw, GroundTruth::merged};
const char* gt_name(GroundTruth g) { return g == GroundTruth::raw ? "raw" : "merged"; }

struct MethodRun {
  bool ran = false;
  std::string error;
  double ms = 0;  // ours: wall time of segment(); PCL: supervoxels + LCCP + per-point labels
  double pcl_supervoxels_ms = 0;
  double pcl_lccp_ms = 0;
  std::uint32_t supervoxels = 0;
  std::uint32_t segments = 0;
  std::uint64_t unlabelled_finite = 0;
  std::optional<lccp::SegmentationScores> scores[2];  // indexed by GroundTruth
  bool ok() const { return ran && error.empty(); }
};

struct SceneResult {
  int index = 0;
  std::string name;
  std::string error;  // loading failed
  bool organized = false;
  std::uint64_t finite_points = 0;
  MethodRun runs[2];  // indexed by Method
  const MethodRun& run(Method m) const { return runs[static_cast<int>(m)]; }
  MethodRun& run(Method m) { return runs[static_cast<int>(m)]; }
};

using lccp::perf::mean;
using lccp::perf::median;
using lccp::perf::ms_since;

std::string fmt(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

// "0-64", "2", "1,5,10-12" -> sorted unique scene indices in [0, 64].
std::vector<int> parse_scenes(const std::string& text) {
  std::vector<int> scenes;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item.empty()) continue;
    const std::size_t dash = item.find('-');
    try {
      const int first = std::stoi(item.substr(0, dash));
      const int last = dash == std::string::npos ? first : std::stoi(item.substr(dash + 1));
      if (first < 0 || last >= kSceneCount || first > last) throw lccp::Error("");
      for (int s = first; s <= last; ++s) scenes.push_back(s);
    } catch (const std::exception&) {
      throw lccp::Error("--scenes: bad item '" + item + "' (expected N or A-B within 0-64)");
    }
  }
  std::sort(scenes.begin(), scenes.end());
  scenes.erase(std::unique(scenes.begin(), scenes.end()), scenes.end());
  if (scenes.empty()) throw lccp::Error("--scenes: no scene selected");
  return scenes;
}

// A preset's name (p1, p2, paper, objects, robot: config/*.yaml, built in) or a YAML file.
lccp::SceneConfig resolve_config(const std::string& name, std::string& source) {
  source = name;
  return lccp::load_preset_or_file(name);
}

fs::path default_mosd_dir() {
  if (const char* env = std::getenv("LCCP_MOSD_DIR"); env != nullptr && *env != '\0') return env;
  return LCCP_MOSD_DEFAULT_DIR;
}

std::uint64_t count_unlabelled_finite(const lccp::PointCloud& cloud, const lccp::Labels& labels) {
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) n += (lccp::is_finite(cloud.points[i]) && labels[i] == 0) ? 1 : 0;
  return n;
}

// Parts against the raw ground truth; objects (a two-level config's, else the
// segments) against the merged one.
void score(MethodRun& run, const lccp::Labels& predicted, const lccp::Labels& objects,
           const lccp::Labels* ground_truths, const lccp::PointCloud& cloud) {
  for (GroundTruth g : kGroundTruths)
    run.scores[static_cast<int>(g)] = lccp::score_segmentation(
        g == GroundTruth::merged && !objects.empty() ? objects : predicted, ground_truths[static_cast<int>(g)],
        cloud.points, kTable);
}

// How each scene's cloud is changed before it is segmented: moved by `shift`
// (a different phase of the voxel grid, for how much a score owes to where the
// cells fall), and given as its finite points only (what numpy users pass).
struct CloudChange {
  Eigen::Vector3f shift = Eigen::Vector3f::Zero();
  bool finite_only = false;
};

void apply(const CloudChange& change, lccp::LabelledCloud& loaded) {
  lccp::PointCloud& cloud = loaded.cloud;
  for (Eigen::Vector3f& p : cloud.points) p += change.shift;
  if (!change.finite_only) return;
  lccp::PointCloud kept;
  lccp::Labels labels;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!lccp::is_finite(cloud.points[i])) continue;
    kept.points.push_back(cloud.points[i]);
    if (cloud.has_colors()) kept.colors.push_back(cloud.colors[i]);
    labels.push_back((*loaded.labels)[i]);
  }
  kept.width = static_cast<std::uint32_t>(kept.points.size());
  kept.height = 1;
  loaded.cloud = std::move(kept);
  loaded.labels = std::move(labels);
}

SceneResult run_scene(int index, const fs::path& dir, const lccp::SceneSegmenter& ours, const lccp::SceneConfig& config,
                      const std::vector<Method>& methods, const CloudChange& change) {
  SceneResult scene;
  scene.index = index;
  scene.name = "test" + std::to_string(index);
  lccp::LabelledCloud loaded;
  try {
    loaded = lccp::read_cloud(dir / (scene.name + ".pcd"));
    if (!loaded.labels) throw lccp::Error(scene.name + ".pcd has no label field");
    apply(change, loaded);
  } catch (const std::exception& e) {
    scene.error = e.what();
    return scene;
  }
  const lccp::PointCloud& cloud = loaded.cloud;
  scene.organized = cloud.organized();
  for (const auto& p : cloud.points) scene.finite_points += lccp::is_finite(p) ? 1 : 0;
  const lccp::Labels ground_truths[2] = {*loaded.labels, lccp::merge_object_parts(*loaded.labels)};

  for (Method m : methods) {
    MethodRun& run = scene.run(m);
    run.ran = true;
    try {
      lccp::Labels predicted, objects;
      if (m == Method::ours) {
        const auto start = Clock::now();
        lccp::SceneSegmentation r = ours.segment(cloud);
        run.ms = ms_since(start);
        run.supervoxels = r.supervoxel_count;
        run.segments = r.segment_count;
        predicted = std::move(r.labels);
        objects = std::move(r.objects);
      } else {
        lccp::perf::PclLccpResult r = lccp::perf::run_pcl_lccp(cloud, config.objects);
        run.ms = r.supervoxels_ms + r.lccp_ms + r.labels_ms;
        run.pcl_supervoxels_ms = r.supervoxels_ms;
        run.pcl_lccp_ms = r.lccp_ms;
        run.supervoxels = r.supervoxel_count;
        run.segments = r.segment_count;
        predicted = std::move(r.labels);
      }
      run.unlabelled_finite = count_unlabelled_finite(cloud, predicted);
      score(run, predicted, objects, ground_truths, cloud);
    } catch (const std::exception& e) {
      run.error = e.what();
    }
  }
  return scene;
}

// ---- reporting ---------------------------------------------------------------------

using Field = double lccp::SegmentationScores::*;
struct ScoreColumn {
  const char* name;
  Field field;
};
constexpr ScoreColumn kColumns[] = {{"WOv", &lccp::SegmentationScores::weighted_overlap},
                                    {"tp", &lccp::SegmentationScores::true_positive},
                                    {"fp", &lccp::SegmentationScores::false_positive},
                                    {"fn", &lccp::SegmentationScores::false_negative},
                                    {"Fos", &lccp::SegmentationScores::over_segmentation},
                                    {"Fus", &lccp::SegmentationScores::under_segmentation},
                                    {"ARI", &lccp::SegmentationScores::adjusted_rand_index}};

class Report {
 public:
  Report(const std::vector<SceneResult>& scenes, const std::vector<Method>& methods)
      : scenes_(scenes), methods_(methods) {}

  // "ours / PCL" in one cell, or one value when only one method ran.
  std::string cell(const std::vector<std::optional<double>>& values, const char* format = "%.3f") const {
    std::string out;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) out += " / ";
      out += values[i] ? fmt(format, *values[i]) : "err";
    }
    return out;
  }

  std::string method_header() const {
    std::string out;
    for (std::size_t i = 0; i < methods_.size(); ++i) out += (i > 0 ? " / " : "") + std::string(method_name(methods_[i]));
    return out;
  }

  void per_scene(GroundTruth g) const {
    std::printf("\n### Per scene (each cell: %s)\n\n", method_header().c_str());
    std::printf("| scene | category | N_G |");
    for (const ScoreColumn& c : kColumns) std::printf(" %s |", c.name);
    std::printf("\n|---|---|---|");
    for (std::size_t i = 0; i < std::size(kColumns); ++i) std::printf("---|");
    std::printf("\n");
    for (const SceneResult& s : scenes_) {
      if (!s.error.empty()) {
        std::printf("| %s | %s | load error: %s |\n", s.name.c_str(), category_of(s.index), s.error.c_str());
        continue;
      }
      std::uint32_t n_g = 0;
      for (Method m : methods_)
        if (const auto& sc = s.run(m).scores[static_cast<int>(g)]) n_g = sc->ground_truth_regions;
      std::printf("| %s%s | %s | %u |", s.name.c_str(), s.organized ? "" : " (unorg.)", category_of(s.index), n_g);
      for (const ScoreColumn& c : kColumns) {
        std::vector<std::optional<double>> values;
        for (Method m : methods_) {
          const auto& sc = s.run(m).scores[static_cast<int>(g)];
          values.push_back(sc ? std::optional<double>((*sc).*c.field) : std::nullopt);
        }
        std::printf(" %s |", cell(values).c_str());
      }
      std::printf("\n");
    }
  }

  // Mean over the scenes in [first, last] (optionally organized only) that every method scored.
  struct Means {
    std::size_t scenes = 0;
    std::vector<std::vector<double>> per_method;  // [method][column]
  };
  Means means(GroundTruth g, int first, int last, bool organized_only) const {
    Means out;
    out.per_method.assign(methods_.size(), std::vector<double>(std::size(kColumns), 0.0));
    for (const SceneResult& s : scenes_) {
      if (s.index < first || s.index > last || !s.error.empty() || (organized_only && !s.organized)) continue;
      bool all = true;
      for (Method m : methods_) all = all && s.run(m).scores[static_cast<int>(g)].has_value();
      if (!all) continue;
      ++out.scenes;
      for (std::size_t mi = 0; mi < methods_.size(); ++mi)
        for (std::size_t ci = 0; ci < std::size(kColumns); ++ci)
          out.per_method[mi][ci] += (*s.run(methods_[mi]).scores[static_cast<int>(g)]).*kColumns[ci].field;
    }
    for (auto& row : out.per_method)
      for (double& v : row) v = out.scenes > 0 ? v / static_cast<double>(out.scenes) : 0.0;
    return out;
  }

  void means_row(const char* label, const Means& m) const {
    std::printf("| %s | %zu |", label, m.scenes);
    for (std::size_t ci = 0; ci < std::size(kColumns); ++ci) {
      std::vector<std::optional<double>> values;
      for (std::size_t mi = 0; mi < methods_.size(); ++mi) values.push_back(m.per_method[mi][ci]);
      std::printf(" %s |", m.scenes > 0 ? cell(values).c_str() : "-");
    }
    std::printf("\n");
  }

  // Objects lost into the table: regions whose best segment holds more table points than their own.
  void objects_lost(GroundTruth g) const {
    std::printf("\nObjects lost into the table (%s):", method_header().c_str());
    for (Method m : methods_) {
      std::uint32_t total = 0;
      std::string where;
      for (const SceneResult& s : scenes_) {
        const auto& sc = s.run(m).scores[static_cast<int>(g)];
        if (!sc || sc->objects_lost == 0) continue;
        total += sc->objects_lost;
        where += " " + s.name + " (" + std::to_string(sc->objects_lost) + ")";
      }
      std::printf(" %s %u%s%s;", method_name(m), total, where.empty() ? "" : ":", where.c_str());
    }
    std::printf("\n");
  }

  void per_category(GroundTruth g) const {
    std::printf("\n### Means per OSD category and overall (mean over scenes; each cell: %s)\n\n",
                method_header().c_str());
    std::printf("| category | scenes |");
    for (const ScoreColumn& c : kColumns) std::printf(" %s |", c.name);
    std::printf("\n|---|---|");
    for (std::size_t i = 0; i < std::size(kColumns); ++i) std::printf("---|");
    std::printf("\n");
    for (const Category& c : kCategories) {
      const std::string label = std::string(c.name) + " " + std::to_string(c.first) + "-" + std::to_string(c.last);
      means_row(label.c_str(), means(g, c.first, c.last, false));
    }
    means_row("**all**", means(g, 0, kSceneCount - 1, false));
    means_row("organized only", means(g, 0, kSceneCount - 1, true));
  }

  void runs_table() const {
    std::printf("\n## Per scene: time, segments, unlabelled finite points (each cell: %s)\n\n",
                method_header().c_str());
    std::printf("| scene | category | finite points | ms | supervoxels | segments | unlabelled finite |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const SceneResult& s : scenes_) {
      if (!s.error.empty()) continue;
      std::vector<std::optional<double>> ms, sv, seg, unl;
      for (Method m : methods_) {
        const MethodRun& r = s.run(m);
        ms.push_back(r.ok() ? std::optional<double>(r.ms) : std::nullopt);
        sv.push_back(r.ok() ? std::optional<double>(r.supervoxels) : std::nullopt);
        seg.push_back(r.ok() ? std::optional<double>(r.segments) : std::nullopt);
        unl.push_back(r.ok() ? std::optional<double>(static_cast<double>(r.unlabelled_finite)) : std::nullopt);
      }
      std::printf("| %s%s | %s | %llu | %s | %s | %s | %s |\n", s.name.c_str(), s.organized ? "" : " (unorg.)",
                  category_of(s.index), static_cast<unsigned long long>(s.finite_points), cell(ms, "%.1f").c_str(),
                  cell(sv, "%.0f").c_str(), cell(seg, "%.0f").c_str(), cell(unl, "%.0f").c_str());
    }
  }

  std::vector<double> times(Method m, bool organized_only, double MethodRun::*field = &MethodRun::ms) const {
    std::vector<double> out;
    for (const SceneResult& s : scenes_)
      if (s.error.empty() && s.run(m).ok() && (!organized_only || s.organized)) out.push_back(s.run(m).*field);
    return out;
  }

  void timing() const {
    std::printf("\n## Timing\n\nms per frame. Ours: wall time of LccpSegmenter::segment. PCL: supervoxels + LCCP + "
                "per-point labels (conversion to pcl::PointXYZRGBA excluded). One run per scene, no warm-up: "
                "use bench_segment for speed figures.\n\n");
    std::printf("| frames | method | scenes | median ms | mean ms | PCL supervoxels median | PCL LCCP median |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const bool organized_only : {false, true}) {
      for (Method m : methods_) {
        const std::vector<double> t = times(m, organized_only);
        const bool pcl = m == Method::pcl;
        std::printf("| %s | %s | %zu | %.1f | %.1f | %s | %s |\n", organized_only ? "organized" : "all",
                    method_name(m), t.size(), median(t), mean(t),
                    pcl ? fmt("%.1f", median(times(m, organized_only, &MethodRun::pcl_supervoxels_ms))).c_str() : "-",
                    pcl ? fmt("%.1f", median(times(m, organized_only, &MethodRun::pcl_lccp_ms))).c_str() : "-");
      }
    }
    if (methods_.size() == 2) {
      for (const bool organized_only : {false, true}) {
        const double pcl = median(times(Method::pcl, organized_only));
        const double ours = median(times(Method::ours, organized_only));
        std::printf("\nMedian ratio PCL / ours (%s scenes): %.2fx\n", organized_only ? "organized" : "all",
                    ours > 0 ? pcl / ours : 0.0);
      }
    }
    std::printf("\n| scenes | method | unlabelled finite points | per scene | scenes with any |\n");
    std::printf("|---|---|---|---|---|\n");
    for (const bool organized_only : {false, true}) {
      for (Method m : methods_) {
        std::uint64_t total = 0;
        std::size_t with = 0, n = 0;
        for (const SceneResult& s : scenes_) {
          if (!s.error.empty() || !s.run(m).ok() || (organized_only && !s.organized)) continue;
          ++n;
          total += s.run(m).unlabelled_finite;
          with += s.run(m).unlabelled_finite > 0 ? 1 : 0;
        }
        std::printf("| %s | %s | %llu | %.1f | %zu |\n", organized_only ? "organized" : "all", method_name(m),
                    static_cast<unsigned long long>(total),
                    n > 0 ? static_cast<double>(total) / static_cast<double>(n) : 0.0, with);
      }
    }
  }

  void errors() const {
    bool any = false;
    for (const SceneResult& s : scenes_) {
      const auto line = [&](const std::string& what) {
        if (!any) std::printf("\n## Errors\n\n");
        any = true;
        std::printf("- %s: %s\n", s.name.c_str(), what.c_str());
      };
      if (!s.error.empty()) line(s.error);
      for (Method m : methods_)
        if (!s.run(m).error.empty()) line(std::string(method_name(m)) + ": " + s.run(m).error);
    }
  }

 private:
  const std::vector<SceneResult>& scenes_;
  const std::vector<Method>& methods_;
};

nlohmann::ordered_json method_json(const MethodRun& r, Method m) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  if (!r.error.empty()) json["error"] = r.error;
  json.update({{"ms", r.ms}, {"supervoxels", r.supervoxels}, {"segments", r.segments},
               {"unlabelled_finite", r.unlabelled_finite}});
  if (m == Method::pcl) json.update({{"supervoxels_ms", r.pcl_supervoxels_ms}, {"lccp_ms", r.pcl_lccp_ms}});
  for (GroundTruth g : kGroundTruths) {
    const auto& sc = r.scores[static_cast<int>(g)];
    if (!sc) continue;
    nlohmann::ordered_json scores = {{"N_G", sc->ground_truth_regions}};
    for (const ScoreColumn& c : kColumns) scores[c.name] = (*sc).*c.field;
    json[gt_name(g)] = std::move(scores);
  }
  return json;
}

nlohmann::ordered_json scene_json(const SceneResult& s, const std::vector<Method>& methods) {
  nlohmann::ordered_json json = {{"scene", s.name}, {"category", category_of(s.index)},
                                 {"organized", s.organized}, {"finite_points", s.finite_points}};
  if (!s.error.empty()) json["error"] = s.error;
  for (Method m : methods) json[m == Method::ours ? "ours" : "pcl"] = method_json(s.run(m), m);
  return json;
}

// The results as JSON (nlohmann/json, https://json.nlohmann.me/), indented by two spaces.
void write_json(const fs::path& path, const std::vector<SceneResult>& scenes, const std::vector<Method>& methods,
                const std::string& date, const std::string& config_source, const std::string& config_text,
                const fs::path& dir, std::size_t threads) {
  std::ofstream out(path);
  if (!out) throw lccp::Error("cannot write " + path.string());
  nlohmann::ordered_json json = {{"date", date},
                                 {"mosd_dir", dir.string()},
                                 {"threads", threads},
                                 {"config_source", config_source},
                                 {"config", config_text},
                                 {"ignored_gt_labels", {0, 9}},
                                 {"scenes", nlohmann::ordered_json::array()}};
  for (const SceneResult& s : scenes) json["scenes"].push_back(scene_json(s, methods));
  out << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
}

std::string now_string() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S %Z", std::localtime(&t));
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Object segmentation scores on the mOSD test scenes: LccpSegmenter vs PCL 1.13's LCCP"};
  std::string mosd_dir = default_mosd_dir().string();
  std::string config_name = "p1";
  std::vector<std::string> settings;
  std::string scenes_text = "0-64";
  std::string json_path;
  std::string methods_text = "both";
  std::size_t threads = 0;
  std::vector<float> shift_mm;
  CloudChange change;
  app.add_option("--mosd", mosd_dir, "directory holding test0.pcd .. test64.pcd ($LCCP_MOSD_DIR)")
      ->capture_default_str();
  app.add_option("--config", config_name, "a preset (p1, p2, paper, objects, robot) or a YAML file")->capture_default_str();
  app.add_option("--set", settings, "key=value override applied after --config (repeatable)");
  app.add_option("--scenes", scenes_text, "scene indices: N, A-B or a comma list, within 0-64")
      ->capture_default_str();
  app.add_option("--json", json_path, "also write per-scene results as JSON to this file");
  app.add_option("--methods", methods_text, "both, ours or pcl")
      ->check(CLI::IsMember({"both", "ours", "pcl"}))
      ->capture_default_str();
  app.add_option("--threads", threads, "TBB threads for LccpSegmenter (0: all cores)")->capture_default_str();
  app.add_option("--shift-mm", shift_mm, "move every cloud by X,Y,Z millimetres first (another phase of the voxel grid)")
      ->delimiter(',')
      ->expected(3);
  app.add_flag("--finite-only", change.finite_only, "pass each cloud as its finite points only (unorganized)");
  CLI11_PARSE(app, argc, argv);
  if (shift_mm.size() == 3) change.shift = Eigen::Vector3f(shift_mm[0], shift_mm[1], shift_mm[2]) / 1000.0f;

  try {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    const tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism, threads);
    lccp::perf::quiet_pcl_console();
    lccp::keep_freed_memory_for_next_frames();  // as lccp's main does; applies to PCL too

    std::string config_source;
    lccp::SceneConfig config = resolve_config(config_name, config_source);
    for (const std::string& s : settings) {
      lccp::apply_setting(config, s);
      config_source += ", " + s;
    }
    const lccp::SceneSegmenter ours(config);
    const std::vector<int> scene_indices = parse_scenes(scenes_text);
    std::vector<Method> methods;
    if (methods_text != "pcl") methods.push_back(Method::ours);
    if (methods_text != "ours") methods.push_back(Method::pcl);
    const fs::path dir = mosd_dir;
    if (!fs::is_directory(dir)) throw lccp::Error("mOSD directory not found: " + dir.string());

    const std::string date = now_string();
    const std::string config_text = lccp::describe_config(config);
    std::string command;
    for (int i = 0; i < argc; ++i) command += (i > 0 ? " " : "") + std::string(argv[i]);

    std::vector<SceneResult> scenes;
    for (int index : scene_indices) {
      scenes.push_back(run_scene(index, dir, ours, config, methods, change));
      const SceneResult& s = scenes.back();
      std::fprintf(stderr, "mosd_accuracy: %s", s.name.c_str());
      for (Method m : methods) {
        const MethodRun& r = s.run(m);
        if (r.ok())
          std::fprintf(stderr, "  %s %.0f ms WOv %.3f", method_name(m), r.ms,
                       r.scores[0] ? r.scores[0]->weighted_overlap : 0.0);
      }
      std::fprintf(stderr, "%s\n", s.error.empty() ? "" : (" error: " + s.error).c_str());
    }

    const Report report(scenes, methods);
    std::printf("# mOSD object segmentation: LccpSegmenter vs PCL 1.13 LCCP\n\n");
    std::printf("- date: %s\n- command: `%s`\n- mOSD: %s, %zu scenes\n- TBB threads (ours): %zu; PCL is single-threaded\n",
                date.c_str(), command.c_str(), dir.c_str(), scenes.size(), threads);
    std::printf("- config: %s\n- PCL: SupervoxelClustering (default camera transform: organized clouds only, no "
                "refinement) + LCCPSegmentation (sanity and smoothness checks as configured, k = 0, "
                "min segment size = n_filter)\n",
                config_source.c_str());
    std::printf("- scoring: score_segmentation over finite points, GT labels 0-9 (table) ignored; S_i = the segment "
                "with the largest intersection with G_i; per-scene scores, category rows are plain means over scenes\n");
    std::printf("\n```\n%s%s```\n", config_text.c_str(),
                config_text.empty() || config_text.back() == '\n' ? "" : "\n");

    for (GroundTruth g : kGroundTruths) {
      std::printf("\n## Ground truth %s: %s\n", gt_name(g),
                  g == GroundTruth::raw ? "file labels as they are (disjoint parts of one object, e.g. 50 and 51, "
                                          "are separate regions)"
                                        : "object parts merged (lccp::merge_object_parts: every label >= 10 -> "
                                          "label / 10 * 10, so 50 and 51 -> 50; the table 1-9 one region); a "
                                          "two-level config is scored by its objects");
      report.per_category(g);
      report.objects_lost(g);
      report.per_scene(g);
    }
    report.runs_table();
    report.timing();
    report.errors();

    if (!json_path.empty())
      write_json(json_path, scenes, methods, date, config_source, config_text, dir, threads);

    bool failed = false;
    for (const SceneResult& s : scenes) {
      failed = failed || !s.error.empty();
      for (Method m : methods) failed = failed || !s.run(m).error.empty();
    }
    return failed ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mosd_accuracy: %s\n", e.what());
    return 1;
  }
}
