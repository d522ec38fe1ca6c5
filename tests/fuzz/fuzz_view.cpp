// libFuzzer target: the live view's request handling (src/view/http_request.hpp),
// bytes as a client sends them, parsed with the server's limits and answered.
// Every input gets a status; nothing else may happen.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "http_request.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lccp::view::Answer reply = lccp::view::answer(std::string_view(reinterpret_cast<const char*>(data), size));
  if (reply.status == lccp::view::http::status::ok && reply.asset == nullptr) __builtin_trap();
  if (reply.asset != nullptr && reply.asset->body.empty()) __builtin_trap();
  return 0;
}
