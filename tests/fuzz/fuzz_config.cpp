// Fuzzes the YAML parameter presets, on text in memory: any bytes either give a valid
// LccpConfig or an lccp::Error naming the problem.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "lccp/io/config_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lccp::fuzz::expect_success_or_lccp_error(
      [&] { lccp::parse_config(lccp::fuzz::text_of(data, size), "fuzz.yaml"); });
}
