#pragma once
// The `lccp` subcommands. Each registers itself and its options on the CLI and
// returns the function that runs it; a run returns the process exit code.
#include <functional>
#include <stop_token>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "lccp/config.hpp"
#include "lccp/error.hpp"

namespace lccp::app {

// Exit codes (README "Exit status").
inline constexpr int kExitDone = 0;
inline constexpr int kExitError = 1;        // a runtime error: bad input, device lost, cannot write
inline constexpr int kExitUsage = 2;        // the command line itself is wrong
inline constexpr int kExitInterrupted = 130;  // stopped by Ctrl-C or SIGTERM before the end (128 + SIGINT)

// A command line the parser accepts but a command refuses (e.g. --save without -o).
class UsageError : public Error {
 public:
  using Error::Error;
};

// A run gets the process's stop token (Ctrl-C, SIGTERM) and returns the exit
// code: 0 done, 130 stopped before the end (errors are thrown: lccp::Error).
struct Subcommand {
  CLI::App* cli = nullptr;
  std::function<int(std::stop_token)> run;
};

Subcommand add_segment_command(CLI::App& cli);
Subcommand add_eval_command(CLI::App& cli);
Subcommand add_replay_command(CLI::App& cli);
Subcommand add_live_command(CLI::App& cli);
Subcommand add_record_command(CLI::App& cli);
Subcommand add_record_bag_command(CLI::App& cli);
Subcommand add_truth_command(CLI::App& cli);
Subcommand add_profile_command(CLI::App& cli);
Subcommand add_devices_command(CLI::App& cli);

// Checks of a number option with a one-line message ("--frames: must be at least
// 1"), where CLI11's own ranges print their bounds in full (1.8e308 as 309 digits).
CLI::Validator at_least_one();  // N >= 1
CLI::Validator more_than_zero();  // S > 0

// --config PRESET|FILE and --set key=value, shared by every command that segments.
struct ConfigOptions {
  std::string file;
  std::vector<std::string> settings;

  void add_to(CLI::App& command);
  SceneConfig resolve() const;  // defaults (P1) <- preset or file <- settings
};

}  // namespace lccp::app
