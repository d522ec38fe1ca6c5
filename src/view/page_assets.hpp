#pragma once
// The page's files (src/view/page/), compiled in by CMake (cmake/view_assets.cpp.in):
// the server reads nothing from the file system.
#include <span>
#include <string_view>

namespace lccp::view {

struct PageAsset {
  std::string_view path;          // the request target that gets it: "/", "/view.js"
  std::string_view content_type;  // "text/html; charset=utf-8"
  std::string_view body;
};

std::span<const PageAsset> page_assets();

}  // namespace lccp::view
