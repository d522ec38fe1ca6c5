#include "commands.hpp"
#include "lccp/io/config_file.hpp"

namespace lccp::app {

void ConfigOptions::add_to(CLI::App& command) {
  command.add_option("--config", file, "YAML preset, e.g. config/p1.yaml (default: P1)");
  command.add_option("--set", settings, "override one parameter: key=value (repeatable)");
}

LccpConfig ConfigOptions::resolve() const {
  LccpConfig config = file.empty() ? LccpConfig{} : load_config(file);
  for (const std::string& setting : settings) apply_setting(config, setting);
  return config;  // LccpSegmenter validates it
}

}  // namespace lccp::app
