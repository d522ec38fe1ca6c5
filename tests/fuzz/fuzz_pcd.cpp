// Fuzzes the PCD parser behind read_cloud, on bytes in memory: any bytes either give a
// cloud or an lccp::Error.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "lccp/io/cloud_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lccp::fuzz::expect_success_or_lccp_error(
      [&] { lccp::parse_pcd(lccp::fuzz::bytes_of(data, size), "fuzz.pcd"); });
}
