#pragma once
// The device URIs of the virtual sensor:
//   virtual://synthetic[?seed=N][&frames=N]   the animated table-top scene
//   virtual://clouds?path=P[&frames=N]         depth rebuilt from organized clouds (P: a .pcd
//                                              file, or a folder of them read in name order)
// frames=N makes the device disappear after N delivered frames, like an unplugged sensor.
// Options may come in any order; no percent-decoding, so P cannot contain '&'.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>

namespace lccp::virtual_sensor {

inline constexpr std::string_view kUriScheme = "virtual://";
inline constexpr std::string_view kSyntheticUri = "virtual://synthetic";

enum class SourceKind { synthetic, clouds };

struct VirtualUri {
  SourceKind kind = SourceKind::synthetic;
  std::uint64_t seed = 1;                    // synthetic: noise seed (TabletopScene's default)
  std::filesystem::path path;                // clouds: one cloud file or a folder of .pcd files
  std::optional<std::uint64_t> frame_limit;  // frames=N: delivered frames before the device disappears
};

// True if `uri` is in the virtual sensor's scheme (whether or not it parses).
bool is_virtual_uri(std::string_view uri);

// Parses a virtual sensor URI; any string is safe to pass (the fuzzing entry point,
// tests/fuzz/fuzz_uri.cpp). Throws lccp::Error with one line naming the URI (bytes
// outside printable ASCII escaped, cut after 120 bytes) and what is wrong with it:
// unknown source, unknown or repeated option, a number that is not a non-negative
// integer or exceeds 64 bits, a control character or NUL anywhere, over 4096 bytes.
VirtualUri parse_virtual_uri(std::string_view uri);

}  // namespace lccp::virtual_sensor
