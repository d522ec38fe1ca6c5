// lccp: the command-line front end. The thread count is set here and nowhere else.
#include <cstdio>
#include <memory>
#include <vector>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "commands.hpp"
#include "lccp/process.hpp"
#include "stop_signal.hpp"

namespace {

using namespace lccp::app;

// "N", "X" or "TEXT" for an option's value in --help, instead of CLI11's type
// strings ("UINT:INT in [1 - 1000000]"); the default after "=", if any.
void plain_help(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_size() == 0) continue;
    const std::string type = option->get_type_name();
    const std::string base = type.substr(0, type.find(':'));
    std::string text = base == "UINT" || base == "INT" ? "N" : base == "FLOAT" ? "X" : base.empty() ? "" : "TEXT";
    if (!option->get_default_str().empty()) text += "=" + option->get_default_str();
    if (option->get_expected_max() > 1) text += " ...";
    if (option->get_required()) text += " (required)";
    option->option_text(text);
  }
  for (CLI::App* command : app.get_subcommands({})) plain_help(*command);
}

int run_command(const std::vector<Subcommand>& commands, std::stop_token stop) {
  try {
    for (const Subcommand& command : commands) {
      if (command.cli->parsed()) return command.run(stop);
    }
    return kExitUsage;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "lccp: error: %s\n", e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lccp: error: %s\n", e.what());
    return kExitError;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const SignalStop signals;  // before any work: Ctrl-C from the first millisecond is a clean stop
  CLI::App cli{"LCCP Stream: object and part segmentation of depth data (Locally Convex Connected Patches)"};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", std::string("lccp ") + LCCP_VERSION);
  cli.footer("Exit status: 0 done, 1 error, 2 usage error, 130 stopped by Ctrl-C or SIGTERM.");
  unsigned threads = 0;
  cli.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
  std::string log_level = "info";
  cli.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  cli.fallthrough();  // --threads and --log-level may follow the subcommand (set before adding them)
  const std::vector<Subcommand> commands{add_segment_command(cli),    add_eval_command(cli),
                                         add_replay_command(cli),     add_live_command(cli),
                                         add_record_command(cli),     add_record_bag_command(cli),
                                         add_truth_command(cli),      add_profile_command(cli),
                                         add_devices_command(cli)};
  plain_help(cli);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "lccp: error: %s (see lccp --help)\n", e.what());
    return kExitUsage;
  }
  spdlog::set_default_logger(spdlog::stderr_color_mt("lccp"));  // stdout carries results only
  spdlog::set_level(spdlog::level::from_str(log_level));
  lccp::keep_freed_memory_for_next_frames();
  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0) {
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  }
  return run_command(commands, signals.token());
}
