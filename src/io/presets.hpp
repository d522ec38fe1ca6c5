#pragma once
// The presets of config/*.yaml, compiled in (cmake/presets.cpp.in).
#include <string_view>
#include <vector>

namespace lccp::detail {

struct Preset {
  std::string_view name;  // the file's stem: p1, p2, paper, objects, robot
  std::string_view yaml;  // the file's text
};

const std::vector<Preset>& presets();

}  // namespace lccp::detail
