#pragma once
// LccpConfig from YAML presets (config/*.yaml) and key=value overrides.
#include <filesystem>
#include <string>
#include <string_view>

#include "lccp/config.hpp"

namespace lccp {

// Reads a flat YAML map of the keys listed by describe_config(). Unknown keys and
// out-of-range values throw lccp::Error naming the key; so does anything that
// is not such a map (invalid YAML, a list or map as a key or value), with one
// line "PATH: problem". Files over 1 MiB are refused.
LccpConfig load_config(const std::filesystem::path& path);

// The same on YAML text in memory (for fuzzing and tests); `name` stands for
// the file in error messages.
LccpConfig parse_config(std::string_view yaml_text, std::string_view name);

// Applies one `key=value` override, e.g. "beta_thresh_deg=20".
void apply_setting(LccpConfig& config, const std::string& key_equals_value);

// One line per key: name, unit and current value (for --help and docs).
std::string describe_config(const LccpConfig& config);

}  // namespace lccp
