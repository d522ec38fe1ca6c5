// lccp profile SOURCE: latency profile of the streaming pipeline on a recording,
// a device or cloud files; report.json, frames.csv and report.html in a folder.
#include <cstdio>
#include <filesystem>

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "commands.hpp"
#include "frame_source_spec.hpp"
#include "lccp/error.hpp"
#include "profile_report.hpp"
#include "stream_run.hpp"

namespace lccp::app {
namespace {

struct ProfileCommandOptions {
  std::vector<std::string> sources;
  ConfigOptions config;
  unsigned frames_in_flight = 2;
  std::uint64_t frames = 0;  // 0: all
  double seconds = 0;        // 0: no limit
  bool realtime = false;
  std::string directory = "profile-out";
  bool quiet = false;
};

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words) text += (text.empty() ? "" : " ") + word;
  return text;
}

std::filesystem::path create_directory(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (!std::filesystem::is_directory(directory, error)) throw Error("cannot create output folder " + directory.string());
  return directory;
}

int run_profile(const ProfileCommandOptions& options) {
  const StopOnSignal stop;
  ProfileSetup setup;
  setup.source = joined(options.sources);
  setup.kind = source_kind(options.sources);
  setup.config_file = options.config.file;
  setup.settings = options.config.settings;
  setup.config = options.config.resolve();
  const LccpSegmenter segmenter(setup.config);

  SourceOptions source_options;
  if (options.frames > 0) source_options.max_frames = options.frames;
  if (options.seconds > 0) source_options.max_seconds = options.seconds;
  source_options.realtime = options.realtime;
  const auto source = open_frame_source(options.sources, source_options);
  setup.threads = static_cast<unsigned>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  setup.frames_in_flight = options.frames_in_flight;
  setup.drop_policy = drop_policy_for(*source);
  setup.realtime = setup.kind == SourceKind::recording && options.realtime;

  const std::filesystem::path directory = create_directory(options.directory);
  const PipelineRun run = run_pipeline(*source, segmenter, {options.frames_in_flight, !options.quiet}, stop);
  write_profile_reports(directory, setup, run.report);
  std::fputs(profile_table(setup, run.report).c_str(), stdout);
  std::printf("reports %s, %s, %s\n", (directory / "report.json").c_str(), (directory / "frames.csv").c_str(),
              (directory / "report.html").c_str());
  if (!run.source_error.empty()) throw Error(run.source_error);
  if (run.interrupted && !source->is_live()) {
    const auto total = source->frame_count();
    spdlog::warn("interrupted after {} of {} frames", run.report.frames().size(), total ? std::to_string(*total) : "?");
    return 130;
  }
  return 0;
}

}  // namespace

Subcommand add_profile_command(CLI::App& cli) {
  auto options = std::make_shared<ProfileCommandOptions>();
  CLI::App* command = cli.add_subcommand(
      "profile", "latency profile of the pipeline on a recording, a device or cloud files: report.json, frames.csv, "
                 "report.html");
  command
      ->add_option("source", options->sources,
                   "an .oni recording, a device URI (e.g. virtual://synthetic), or .pcd/.ply files or folders of them")
      ->required();
  options->config.add_to(*command);
  add_inflight_option(*command, options->frames_in_flight);
  command->add_option("--frames", options->frames, "stop after N frames (default: all)")->check(CLI::PositiveNumber);
  command->add_option("--seconds", options->seconds, "stop after S seconds")->check(CLI::PositiveNumber);
  command->add_flag("--realtime", options->realtime,
                    "recordings: pace frames by their timestamps, as a live sensor would (late frames are dropped)");
  command->add_option("-o,--output-dir", options->directory, "folder for the reports (created if missing)")
      ->capture_default_str();
  command->add_flag("-q,--quiet", options->quiet, "no progress line");
  return {command, [options] { return run_profile(*options); }};
}

}  // namespace lccp::app
