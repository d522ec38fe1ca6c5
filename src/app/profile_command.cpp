// lccp profile SOURCE: latency profile of the streaming pipeline on a recording,
// a device or cloud files; report.json, frames.csv and report.html in a folder.
#include <cstdio>
#include <filesystem>

#include <tbb/global_control.h>

#include "commands.hpp"
#include "lccp/io/atomic_file.hpp"
#include "profile_report.hpp"
#include "stream_run.hpp"

namespace lccp::app {
namespace {

struct ProfileCommandOptions {
  std::vector<std::string> sources;
  ConfigOptions config;
  unsigned frames_in_flight = 2;
  LimitOptions limits;
  bool realtime = false;
  std::string directory = "profile-out";
  bool quiet = false;
  ViewOptions view;
};

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words) text += (text.empty() ? "" : " ") + word;
  return text;
}

ProfileSetup profile_setup(const ProfileCommandOptions& options, const FrameSource& source) {
  ProfileSetup setup;
  setup.source = joined(options.sources);
  setup.kind = source_kind(options.sources);
  setup.config_file = options.config.file;
  setup.settings = options.config.settings;
  setup.config = options.config.resolve();
  setup.threads = static_cast<unsigned>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  setup.frames_in_flight = options.frames_in_flight;
  setup.drop_policy = drop_policy_for(source);
  setup.realtime = options.realtime;
  return setup;
}

int run_profile(const ProfileCommandOptions& options, std::stop_token stop) {
  const SceneSegmenter segmenter(options.config.resolve());
  const auto source = open_source(options.sources, {options.limits.limits(), options.realtime});
  const ProfileSetup setup = profile_setup(options, *source);
  const std::filesystem::path directory(options.directory);
  create_output_folder(directory);
  const auto view = options.view.start(stop);
  const PipelineRun run = run_pipeline(*source, segmenter, {options.frames_in_flight, !options.quiet, view.get()}, stop);
  write_profile_reports(directory, setup, run.report);
  std::fputs(profile_table(setup, run.report).c_str(), stdout);
  std::printf("reports %s, %s, %s\n", (directory / "report.json").c_str(), (directory / "frames.csv").c_str(),
              (directory / "report.html").c_str());
  std::fflush(stdout);
  options.view.hold_until_stopped(view.get(), stop);
  return exit_code(run, *source);
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
  options->limits.add_to(*command);
  command->add_flag("--realtime", options->realtime,
                    "recordings: pace frames by their timestamps, as a live sensor would (late frames are dropped)");
  command->add_option("-o,--output-dir", options->directory, "folder for the reports (created if missing)")
      ->capture_default_str();
  command->add_flag("-q,--quiet", options->quiet, "no progress line");
  options->view.add_to(*command);
  return {command, [options](std::stop_token stop) { return run_profile(*options, stop); }};
}

}  // namespace lccp::app
