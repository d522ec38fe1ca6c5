// Fuzzes .oni recordings: the bytes go through lccp::detail::check_oni_recording,
// and input it accepts is replayed with open_recording (our reader) to the last
// frame. Either every frame comes out or an lccp::Error is thrown.
#include <cstddef>
#include <stop_token>
#include <cstdint>
#include <optional>

#include "fuzz_input.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "oni_check.hpp"

namespace {

void replay_every_frame(const std::uint8_t* data, std::size_t size) {
  static lccp::fuzz::InputFile file(".oni");
  const auto& path = file.write(data, size);
  const auto source = lccp::open_recording(path);
  while (source->next(std::stop_token{})) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lccp::fuzz::expect_success_or_lccp_error([&] {
    lccp::detail::check_oni_recording(lccp::fuzz::bytes_of(data, size), "fuzz.oni");
    replay_every_frame(data, size);  // open_recording checks the file again, then reads it
  });
}
