// lccp: the command-line front end. The thread count is set here and nowhere else.
#include <cstdio>
#include <vector>
#include <memory>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "commands.hpp"
#include "lccp/error.hpp"
#include "lccp/process.hpp"
#include "stop_signal.hpp"

int main(int argc, char** argv) {
  lccp::app::install_stop_handlers();  // before any work: Ctrl-C from the first millisecond is a clean stop
  CLI::App cli{"LCCP Stream: object and part segmentation of depth data (Locally Convex Connected Patches)"};
  cli.require_subcommand(1);
  unsigned threads = 0;
  cli.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
  std::string log_level = "info";
  cli.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));

  cli.fallthrough();  // --threads and --log-level may follow the subcommand (set before adding them)
  const std::vector<lccp::app::Subcommand> commands{lccp::app::add_segment_command(cli),
                                                    lccp::app::add_eval_command(cli),
                                                    lccp::app::add_replay_command(cli),
                                                    lccp::app::add_live_command(cli),
                                                    lccp::app::add_record_command(cli),
                                                    lccp::app::add_truth_command(cli),
                                                    lccp::app::add_profile_command(cli)};

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e);
  }
  spdlog::set_default_logger(spdlog::stderr_color_mt("lccp"));  // stdout carries results only
  spdlog::set_level(spdlog::level::from_str(log_level));
  lccp::keep_freed_memory_for_next_frames();
  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0) {
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  }
  try {
    for (const auto& command : commands) {
      if (command.cli->parsed()) return command.run();
    }
    return 2;
  } catch (const lccp::Error& e) {
    std::fprintf(stderr, "lccp: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lccp: internal error: %s\n", e.what());
    return 3;
  }
}
