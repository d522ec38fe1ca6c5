#pragma once
// LccpConfig from YAML presets (config/*.yaml) and key=value overrides.
#include <filesystem>
#include <string>

#include "lccp/config.hpp"

namespace lccp {

// Reads a flat YAML map of the keys listed by config_keys(). Unknown keys and
// out-of-range values throw lccp::Error naming the key.
LccpConfig load_config(const std::filesystem::path& path);

// Applies one `key=value` override, e.g. "beta_thresh_deg=20".
void apply_setting(LccpConfig& config, const std::string& key_equals_value);

// One line per key: name, unit and current value (for --help and docs).
std::string describe_config(const LccpConfig& config);

}  // namespace lccp
