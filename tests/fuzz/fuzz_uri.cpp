// Fuzzes the virtual sensor's URI parser (drivers/virtual_sensor/virtual_uri.cpp):
// any string either parses or throws an lccp::Error.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "virtual_uri.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lccp::fuzz::expect_success_or_lccp_error(
      [&] { lccp::virtual_sensor::parse_virtual_uri(lccp::fuzz::text_of(data, size)); });
}
