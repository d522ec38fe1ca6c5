#include <filesystem>

#include "commands.hpp"
#include "lccp/error.hpp"
#include "lccp/io/config_file.hpp"
#include "presets.hpp"

namespace lccp::app {
namespace {

std::string preset_names() {
  std::string names;
  for (const Preset& preset : presets()) names += (names.empty() ? "" : ", ") + std::string(preset.name);
  return names;
}

// A preset's name (no folder, no suffix) or a YAML file.
SceneConfig load_preset_or_file(const std::string& name_or_path) {
  for (const Preset& preset : presets()) {
    if (preset.name == name_or_path) return parse_config(preset.yaml, "preset " + name_or_path);
  }
  const std::filesystem::path path(name_or_path);
  if (path.has_parent_path() || path.has_extension()) return load_config(path);
  throw Error("--config " + name_or_path + ": no such preset (" + preset_names() + ") and not a path to a .yaml file");
}

}  // namespace

void ConfigOptions::add_to(CLI::App& command) {
  command.add_option("--config", file, "a preset (" + preset_names() + ") or a YAML file (default: p1)");
  command.add_option("--set", settings, "override one parameter: key=value (repeatable)");
}

SceneConfig ConfigOptions::resolve() const {
  SceneConfig config = file.empty() ? SceneConfig{} : load_preset_or_file(file);
  for (const std::string& setting : settings) apply_setting(config, setting);
  return config;  // SceneSegmenter validates it
}

}  // namespace lccp::app
