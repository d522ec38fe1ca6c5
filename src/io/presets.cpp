#include <filesystem>

#include "lccp/error.hpp"
#include "lccp/io/config_file.hpp"
#include "presets.hpp"

namespace lccp {

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const detail::Preset& preset : detail::presets()) names.emplace_back(preset.name);
  return names;
}

SceneConfig load_preset_or_file(const std::string& name_or_path) {
  for (const detail::Preset& preset : detail::presets()) {
    if (preset.name == name_or_path) return parse_config(preset.yaml, "preset " + name_or_path);
  }
  const std::filesystem::path path(name_or_path);
  if (path.has_parent_path() || path.has_extension()) return load_config(path);
  std::string names;
  for (const std::string& name : preset_names()) names += (names.empty() ? "" : ", ") + name;
  throw Error("config " + name_or_path + ": no such preset (" + names + ") and not a path to a .yaml file");
}

SceneConfig resolve_config(const std::string& name_or_path, const std::vector<std::string>& settings) {
  SceneConfig config = name_or_path.empty() ? SceneConfig{} : load_preset_or_file(name_or_path);
  for (const std::string& setting : settings) apply_setting(config, setting);
  return config;
}

}  // namespace lccp
