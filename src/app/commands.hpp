#pragma once
// The `lccp` subcommands. Each registers itself and its options on the CLI and
// returns the function that runs it; a run returns the process exit code.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "lccp/config.hpp"

namespace lccp::app {

struct Subcommand {
  CLI::App* cli = nullptr;
  std::function<int()> run;
};

Subcommand add_segment_command(CLI::App& cli);
Subcommand add_eval_command(CLI::App& cli);
Subcommand add_replay_command(CLI::App& cli);
Subcommand add_live_command(CLI::App& cli);
Subcommand add_record_command(CLI::App& cli);
Subcommand add_truth_command(CLI::App& cli);
Subcommand add_profile_command(CLI::App& cli);

// --config FILE and --set key=value, shared by every command that segments.
struct ConfigOptions {
  std::string file;
  std::vector<std::string> settings;

  void add_to(CLI::App& command);
  LccpConfig resolve() const;  // defaults (P1) <- file <- settings
};

}  // namespace lccp::app
