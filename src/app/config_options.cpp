#include "commands.hpp"
#include "lccp/io/config_file.hpp"

namespace lccp::app {
namespace {

std::string listed_presets() {
  std::string names;
  for (const std::string& name : preset_names()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

}  // namespace

void ConfigOptions::add_to(CLI::App& command) {
  command.add_option("--config", file, "a preset (" + listed_presets() + ") or a YAML file (default: p1)");
  command.add_option("--set", settings, "override one parameter: key=value (repeatable)");
}

SceneConfig ConfigOptions::resolve() const {
  return resolve_config(file, settings);  // SceneSegmenter validates it
}

}  // namespace lccp::app
