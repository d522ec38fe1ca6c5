#include "virtual_uri.hpp"

#include <algorithm>
#include <charconv>
#include <set>
#include <string>

#include "lccp/error.hpp"

namespace lccp::virtual_sensor {
namespace {

constexpr std::size_t kMaxUriBytes = 4096;   // OpenNI2 itself passes at most ONI_MAX_STR (256)
constexpr std::size_t kMaxQuotedBytes = 120;

// `text` for a one-line message: bytes outside printable ASCII as \xHH, cut after
// kMaxQuotedBytes bytes (a URI may hold anything, even newlines or NUL).
std::string quoted(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMaxQuotedBytes; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += {'\\', 'x', kHex[c >> 4], kHex[c & 15]};
    }
  }
  if (text.size() > kMaxQuotedBytes) out += "...";
  return out;
}

std::uint64_t parse_count(std::string_view uri, std::string_view key, std::string_view value) {
  std::uint64_t number = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), number);
  if (value.empty() || error != std::errc() || end != value.data() + value.size()) {
    throw Error("virtual sensor URI '" + quoted(uri) + "': " + quoted(key) + "=" + quoted(value) +
                (error == std::errc::result_out_of_range ? " is out of range" : " is not a non-negative integer"));
  }
  return number;
}

}  // namespace

bool is_virtual_uri(std::string_view uri) { return uri.starts_with(kUriScheme); }

VirtualUri parse_virtual_uri(std::string_view uri) {
  const auto fail = [&](const std::string& problem) {
    throw Error("virtual sensor URI '" + quoted(uri) + "': " + problem);
  };
  if (!is_virtual_uri(uri)) fail("does not start with " + std::string(kUriScheme));
  if (uri.size() > kMaxUriBytes) fail("longer than " + std::to_string(kMaxUriBytes) + " bytes");
  const auto control = std::find_if(uri.begin(), uri.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
  if (control != uri.end()) fail("control character at byte " + std::to_string(control - uri.begin()));

  const std::string_view rest = uri.substr(kUriScheme.size());
  const auto question = rest.find('?');
  const std::string_view source = rest.substr(0, question);
  const std::string_view query = question == std::string_view::npos ? std::string_view() : rest.substr(question + 1);

  VirtualUri parsed;
  if (source == "synthetic") {
    parsed.kind = SourceKind::synthetic;
  } else if (source == "clouds") {
    parsed.kind = SourceKind::clouds;
  } else {
    fail("unknown source '" + quoted(source) +
         "' (expected virtual://synthetic[?seed=N][&frames=N] or virtual://clouds?path=P[&frames=N])");
  }

  std::set<std::string_view> seen;
  for (std::size_t begin = 0; question != std::string_view::npos && begin <= query.size();) {
    const auto end = std::min(query.find('&', begin), query.size());
    const std::string_view option = query.substr(begin, end - begin);
    begin = end + 1;

    const auto equals = option.find('=');
    if (equals == std::string_view::npos) fail("option '" + quoted(option) + "' is not key=value");
    const std::string_view key = option.substr(0, equals);
    const std::string_view value = option.substr(equals + 1);
    if (!seen.insert(key).second) fail("option '" + quoted(key) + "' given twice");

    if (key == "frames") {
      parsed.frame_limit = parse_count(uri, key, value);
      if (*parsed.frame_limit == 0) fail("frames must be at least 1");
    } else if (key == "seed" && parsed.kind == SourceKind::synthetic) {
      parsed.seed = parse_count(uri, key, value);
    } else if (key == "path" && parsed.kind == SourceKind::clouds) {
      if (value.empty()) fail("path is empty");
      parsed.path = std::filesystem::path(std::string(value));
    } else {
      fail("unknown option '" + quoted(key) + "' for virtual://" + quoted(source));
    }
  }
  if (parsed.kind == SourceKind::clouds && parsed.path.empty()) fail("virtual://clouds needs ?path=P");
  return parsed;
}

}  // namespace lccp::virtual_sensor
