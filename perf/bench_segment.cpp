// bench_segment: milliseconds per frame, PCL 1.13's LCCP vs LccpSegmenter, parameter
// sets P1 and P2 (paper Table II), on the same frames (by default the 62 organized
// mOSD test scenes).
//
// Every benchmark runs one frame per repetition, cycling over the frames, so the
// aggregates Google Benchmark prints (median, mean, stddev, cv) are statistics over
// frames. A summary table (median ms/frame, PCL vs ours) follows the benchmark output.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "lccp/process.hpp"

#include "lccp/config.hpp"
#include "lccp/core/lccp.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/io/config_file.hpp"
#include "pcl_reference.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kUsage = R"(usage: bench_segment [options] [--benchmark_* flags]
  --frames-dir DIR   directory of .pcd frames (default: $LCCP_MOSD_DIR, else
                     )" LCCP_MOSD_DEFAULT_DIR R"(, else )" LCCP_TEST_DATA_DIR R"()
  --all-clouds       also use unorganized clouds (default: organized clouds only)
  --max-frames N     use only the first N frames (natural file order)
  --rounds K         pass over every frame K times (default 1)
  --threads N        TBB threads for LccpSegmenter (default: all cores; PCL is single-threaded)
  --help             this text, then Google Benchmark's flags
Benchmarks: BM_Pcl/P1 BM_Lccp/P1 BM_Pcl/P2 BM_Lccp/P2 (select with --benchmark_filter=REGEX).
P1/P2 come from )" LCCP_CONFIG_DIR R"(/p1.yaml and p2.yaml (Table II values if missing).
)";

struct Options {
  std::optional<fs::path> frames_dir;
  bool all_clouds = false;
  std::size_t max_frames = 0;  // 0: all
  std::size_t rounds = 1;
  std::size_t threads = 0;     // 0: all cores
};

struct Frame {
  std::string name;
  lccp::PointCloud cloud;
};

struct NamedConfig {
  std::string name;    // P1, P2
  std::string source;  // file it came from, or "built-in Table II"
  lccp::LccpConfig config;
};

// One frame's times (ms). For PCL: supervoxels, LCCP, per-point labels. For ours: StageTimes.
struct FrameTime {
  double total_ms = 0;
  double pcl_supervoxels_ms = 0;
  double pcl_lccp_ms = 0;
};

// One benchmark: one method on one parameter set, cycling over the frames.
struct Case {
  std::string name;  // e.g. BM_Pcl/P1
  bool pcl = false;
  const NamedConfig* config = nullptr;
  std::optional<lccp::LccpSegmenter> ours;
  std::size_t next_frame = 0;
  bool warmed_up = false;
  std::vector<FrameTime> frames;
};

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  double m = values[mid];
  if (values.size() % 2 == 0) m = (m + *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid))) / 2;
  return m;
}

double median_of(const std::vector<FrameTime>& frames, double FrameTime::*field) {
  std::vector<double> values;
  values.reserve(frames.size());
  for (const FrameTime& f : frames) values.push_back(f.*field);
  return median(std::move(values));
}

std::size_t parse_count(const std::string& flag, const std::string& value) {
  try {
    std::size_t used = 0;
    const unsigned long n = std::stoul(value, &used);
    if (used == value.size()) return n;
  } catch (const std::exception&) {
  }
  throw lccp::Error(flag + ": expected a non-negative integer, got '" + value + "'");
}

// Splits argv into our options and the rest (left for benchmark::Initialize).
Options parse_options(int argc, char** argv, std::vector<char*>& rest, bool& help) {
  Options options;
  rest.push_back(argv[0]);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const std::string& flag) -> std::optional<std::string> {
      if (arg == flag) {
        if (i + 1 >= argc) throw lccp::Error(flag + ": missing value");
        return std::string(argv[++i]);
      }
      if (arg.rfind(flag + "=", 0) == 0) return arg.substr(flag.size() + 1);
      return std::nullopt;
    };
    if (auto v = value("--frames-dir")) {
      options.frames_dir = *v;
    } else if (auto v = value("--max-frames")) {
      options.max_frames = parse_count("--max-frames", *v);
    } else if (auto v = value("--rounds")) {
      options.rounds = std::max<std::size_t>(1, parse_count("--rounds", *v));
    } else if (auto v = value("--threads")) {
      options.threads = parse_count("--threads", *v);
    } else if (arg == "--all-clouds") {
      options.all_clouds = true;
    } else if (arg == "--help" || arg == "-h") {
      help = true;
      rest.push_back(argv[i]);
    } else {
      rest.push_back(argv[i]);
    }
  }
  return options;
}

// The trailing number of a file stem (test12 -> 12), for natural order.
long trailing_number(const std::string& stem) {
  std::size_t start = stem.size();
  while (start > 0 && stem[start - 1] >= '0' && stem[start - 1] <= '9') --start;
  return start < stem.size() ? std::stol(stem.substr(start)) : -1;
}

fs::path frames_directory(const Options& options) {
  if (options.frames_dir) return *options.frames_dir;
  if (const char* env = std::getenv("LCCP_MOSD_DIR"); env != nullptr && *env != '\0') return env;
  if (fs::is_directory(LCCP_MOSD_DEFAULT_DIR)) return LCCP_MOSD_DEFAULT_DIR;
  std::fprintf(stderr, "bench_segment: %s missing, falling back to %s\n", LCCP_MOSD_DEFAULT_DIR,
               LCCP_TEST_DATA_DIR);
  return LCCP_TEST_DATA_DIR;
}

std::vector<Frame> load_frames(const fs::path& dir, const Options& options) {
  if (!fs::is_directory(dir)) throw lccp::Error("frames directory not found: " + dir.string());
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".pcd") files.push_back(entry.path());
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const long na = trailing_number(a.stem().string()), nb = trailing_number(b.stem().string());
    return na != nb ? na < nb : a < b;
  });
  std::vector<Frame> frames;
  std::vector<std::string> skipped;
  for (const fs::path& file : files) {
    if (options.max_frames != 0 && frames.size() == options.max_frames) break;
    lccp::LabelledCloud loaded = lccp::read_cloud(file);
    if (!loaded.cloud.organized() && !options.all_clouds) {
      skipped.push_back(file.filename().string());
      continue;
    }
    frames.push_back({file.stem().string(), std::move(loaded.cloud)});
  }
  if (frames.empty()) throw lccp::Error("no usable .pcd frame in " + dir.string());
  std::string skipped_list;
  for (const std::string& s : skipped) skipped_list += " " + s;
  std::fprintf(stderr, "bench_segment: %zu frames from %s%s%s\n", frames.size(), dir.c_str(),
               skipped.empty() ? "" : "; skipped unorganized (use --all-clouds):", skipped_list.c_str());
  return frames;
}

NamedConfig named_config(const std::string& name, float voxel_m, float seed_m, std::uint32_t n_filter) {
  const fs::path file = fs::path(LCCP_CONFIG_DIR) / (std::string(name == "P1" ? "p1" : "p2") + ".yaml");
  if (fs::exists(file)) return {name, file.string(), lccp::load_config(file).objects};
  std::fprintf(stderr, "bench_segment: %s not found, using the paper's Table II values for %s\n",
               file.c_str(), name.c_str());
  lccp::LccpConfig config;  // defaults: weights 1/4/0, beta_thresh 10 deg, SC on
  config.voxels.voxel_size_m = voxel_m;
  config.supervoxels.seed_size_m = seed_m;
  config.filter.n_filter_supervoxels = n_filter;
  return {name, "built-in Table II", config};
}

void run_case(benchmark::State& state, Case& c, const std::vector<Frame>& frames) {
  // One untimed run so that the first timed frame does not pay for cold caches or TBB start-up.
  if (!c.warmed_up) {
    c.warmed_up = true;
    try {
      const lccp::Labels labels = c.pcl ? lccp::perf::run_pcl_lccp(frames.front().cloud, c.config->config).labels
                                        : c.ours->segment(frames.front().cloud).labels;
      benchmark::DoNotOptimize(labels.data());
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      return;
    }
  }

  std::vector<double> sums(c.pcl ? 4 : lccp::kLccpStageCount, 0.0);
  double supervoxels = 0, segments = 0;
  for (auto _ : state) {
    const Frame& frame = frames[c.next_frame++ % frames.size()];
    FrameTime time;
    try {
      if (c.pcl) {
        const lccp::perf::PclLccpResult r = lccp::perf::run_pcl_lccp(frame.cloud, c.config->config);
        // The conversion to PCL's point type is left out: a PCL user already has a pcl::PointCloud.
        time.total_ms = r.supervoxels_ms + r.lccp_ms + r.labels_ms;
        time.pcl_supervoxels_ms = r.supervoxels_ms;
        time.pcl_lccp_ms = r.lccp_ms;
        const double stages[] = {r.supervoxels_ms, r.lccp_ms, r.labels_ms, r.convert_ms};
        for (std::size_t i = 0; i < 4; ++i) sums[i] += stages[i];
        supervoxels += r.supervoxel_count;
        segments += r.segment_count;
      } else {
        const auto start = Clock::now();
        const lccp::SegmentationResult r = c.ours->segment(frame.cloud);
        time.total_ms = ms_since(start);
        benchmark::DoNotOptimize(r.labels.data());
        const lccp::StageTimes& t = r.times;
        for (std::size_t i = 0; i < lccp::kLccpStageCount; ++i) sums[i] += t.ms[i];
        supervoxels += r.supervoxel_count;
        segments += r.segment_count;
      }
    } catch (const std::exception& e) {
      state.SkipWithError((frame.name + ": " + e.what()).c_str());
      break;
    }
    state.SetIterationTime(time.total_ms / 1000.0);
    c.frames.push_back(time);
  }

  using benchmark::Counter;
  const auto avg = [](double v) { return Counter(v, Counter::kAvgIterations); };
  static constexpr const char* kPclNames[] = {"pcl_supervoxels_ms", "pcl_lccp_ms", "pcl_labels_ms",
                                              "pcl_convert_ms"};
  for (std::size_t i = 0; i < sums.size(); ++i) {
    state.counters[c.pcl ? std::string(kPclNames[i]) : std::string(lccp::kStages[i].name) + "_ms"] = avg(sums[i]);
  }
  state.counters["supervoxels"] = avg(supervoxels);
  state.counters["segments"] = avg(segments);
}

bool machine_readable_output(const std::vector<char*>& args) {
  for (const char* a : args) {
    const std::string_view arg(a);
    if (arg.rfind("--benchmark_format=", 0) == 0 && arg != "--benchmark_format=console") return true;
  }
  return false;
}

void print_summary(std::FILE* out, const std::vector<std::unique_ptr<Case>>& cases, std::size_t frame_count,
                   std::size_t threads) {
  std::fprintf(out, "\nSummary: median ms per frame over %zu frames, %zu TBB threads for ours "
                    "(PCL: single-threaded; its time excludes the conversion to pcl::PointXYZRGBA)\n",
               frame_count, threads);
  std::fprintf(out, "| config | frames run | PCL 1.13 ms | ours ms | PCL / ours | PCL supervoxels ms | PCL LCCP ms |\n");
  std::fprintf(out, "|---|---|---|---|---|---|---|\n");
  for (const char* config : {"P1", "P2"}) {
    const Case* pcl = nullptr;
    const Case* ours = nullptr;
    for (const auto& c : cases) {
      if (c->config->name != config || c->frames.empty()) continue;
      (c->pcl ? pcl : ours) = c.get();
    }
    if (pcl == nullptr && ours == nullptr) continue;
    const auto cell = [](const Case* c, double FrameTime::*field) {
      char buf[32];
      if (c == nullptr) return std::string("-");
      std::snprintf(buf, sizeof buf, "%.1f", median_of(c->frames, field));
      return std::string(buf);
    };
    std::string ratio = "-";
    if (pcl != nullptr && ours != nullptr) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2fx",
                    median_of(pcl->frames, &FrameTime::total_ms) / median_of(ours->frames, &FrameTime::total_ms));
      ratio = buf;
    }
    const std::size_t run = std::max(pcl ? pcl->frames.size() : 0, ours ? ours->frames.size() : 0);
    std::fprintf(out, "| %s | %zu | %s | %s | %s | %s | %s |\n", config, run, cell(pcl, &FrameTime::total_ms).c_str(),
                 cell(ours, &FrameTime::total_ms).c_str(), ratio.c_str(),
                 cell(pcl, &FrameTime::pcl_supervoxels_ms).c_str(), cell(pcl, &FrameTime::pcl_lccp_ms).c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<char*> rest;
    bool help = false;
    const Options options = parse_options(argc, argv, rest, help);
    if (help) std::fputs(kUsage, stdout);
    int rest_argc = static_cast<int>(rest.size());
    benchmark::Initialize(&rest_argc, rest.data());
    if (benchmark::ReportUnrecognizedArguments(rest_argc, rest.data())) return 1;

    const std::size_t threads =
        options.threads != 0 ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    const tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism, threads);
    lccp::perf::quiet_pcl_console();
    lccp::keep_freed_memory_for_next_frames();  // as lccp's main does; applies to PCL too

    const fs::path dir = frames_directory(options);
    const std::vector<Frame> frames = load_frames(dir, options);
    const NamedConfig configs[] = {named_config("P1", 0.005f, 0.02f, 3), named_config("P2", 0.0075f, 0.06f, 1)};

    std::vector<std::unique_ptr<Case>> cases;
    for (const NamedConfig& config : configs) {
      for (const bool pcl : {true, false}) {
        auto c = std::make_unique<Case>();
        c->name = std::string(pcl ? "BM_Pcl/" : "BM_Lccp/") + config.name;
        c->pcl = pcl;
        c->config = &config;
        if (!pcl) c->ours.emplace(config.config);
        cases.push_back(std::move(c));
      }
    }
    const auto repetitions = static_cast<int>(frames.size() * options.rounds);
    for (const auto& c : cases) {
      Case& the_case = *c;
      benchmark::RegisterBenchmark(the_case.name.c_str(),
                                   [&the_case, &frames](benchmark::State& s) { run_case(s, the_case, frames); })
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1)
          ->Repetitions(repetitions)
          ->ReportAggregatesOnly(true);
    }
    benchmark::AddCustomContext("frames_dir", dir.string());
    benchmark::AddCustomContext("frames", std::to_string(frames.size()) + " x " + std::to_string(options.rounds) +
                                              " round(s), one frame per repetition");
    benchmark::AddCustomContext("tbb_threads", std::to_string(threads));
    for (const NamedConfig& config : configs) benchmark::AddCustomContext("config_" + config.name, config.source);

    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    print_summary(machine_readable_output(rest) ? stderr : stdout, cases, frames.size(), threads);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_segment: %s\n", e.what());
    return 1;
  }
}
