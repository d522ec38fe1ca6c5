#pragma once
// SceneConfig from YAML presets (config/*.yaml) and key=value overrides.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "lccp/config.hpp"

namespace lccp {

// Reads a YAML map of the keys listed by describe_config() for the first level
// and, for two levels, a map `parts:` of the same keys for the second (starting
// from the defaults, P1). Unknown keys and out-of-range values throw
// lccp::Error naming the key; so does anything that is not such a map (invalid
// YAML, a list or map as a value), with one line "PATH: problem". Files over
// 1 MiB are refused.
SceneConfig load_config(const std::filesystem::path& path);

// The same on YAML text in memory (for fuzzing and tests); `name` stands for
// the file in error messages.
SceneConfig parse_config(std::string_view yaml_text, std::string_view name);

// The presets built into the library from the project's config/*.yaml (p1,
// p2, objects, robot), sorted by name.
std::vector<std::string> preset_names();

// A preset by name (no folder, no suffix: "p2") or else a YAML file by path
// ("config/p2.yaml", "my.yaml": anything with a folder or a suffix), read with
// load_config. Throws lccp::Error for a name that is neither, listing the presets.
SceneConfig load_preset_or_file(const std::string& name_or_path);

// load_preset_or_file(name_or_path) (the defaults, P1, for an empty name),
// then every "key=value" of `settings` in turn with apply_setting: how the lccp
// tool (--config, --set) and the ROS node (~config, ~KEY) build their config.
SceneConfig resolve_config(const std::string& name_or_path, const std::vector<std::string>& settings);

// Applies one `key=value` override, e.g. "beta_thresh_deg=20", or
// "parts.beta_thresh_deg=20" for the second level (which must exist).
void apply_setting(SceneConfig& config, const std::string& key_equals_value);

// One line per key: name, unit and current value (for --help and docs); the
// second level's keys prefixed "parts.".
std::string describe_config(const SceneConfig& config);

// The keys of `config` in describe_config's order: the first level's, then the
// second level's (if any) prefixed "parts.".
std::vector<std::string> config_key_names(const SceneConfig& config);

}  // namespace lccp
