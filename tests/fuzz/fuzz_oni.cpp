// Fuzzes .oni recordings: the bytes go through lccp::detail::check_oni_recording,
// and input it accepts is replayed with open_recording (OpenNI2's file driver,
// manual playback) to the last frame. Either every frame comes out or an
// lccp::Error is thrown.
#include <cstddef>
#include <stop_token>
#include <cstdint>
#include <optional>

#include "fuzz_input.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "oni_check.hpp"

namespace {

// A damaged recording must fail fast, not after the default 5 s stall timeout.
constexpr int kStallTimeoutMs = 200;

void replay_every_frame(const std::uint8_t* data, std::size_t size) {
  static lccp::fuzz::InputFile file(".oni");
  const auto& path = file.write(data, size);
  lccp::ReplayOptions options;
  options.stall_timeout_ms = kStallTimeoutMs;
  const auto source = lccp::open_recording(path, options);
  while (source->next(std::stop_token{})) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lccp::fuzz::expect_success_or_lccp_error([&] {
    lccp::detail::check_oni_recording(lccp::fuzz::bytes_of(data, size), "fuzz.oni");
    replay_every_frame(data, size);  // open_recording checks the file again, then OpenNI2 plays it
  });
}
