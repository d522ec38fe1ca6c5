#pragma once
// The view's answer to an HTTP request: the one piece of request handling the
// project does itself (Boost.Beast parses the bytes; tests/fuzz/fuzz_view feeds
// it arbitrary ones). A target names a compiled-in page file or the stream, or
// nothing: no path is ever joined, decoded or looked up on disk.
#include <cstddef>
#include <string_view>

#include <boost/beast/http.hpp>

#include "page_assets.hpp"

namespace lccp::view {

namespace http = boost::beast::http;

inline constexpr std::size_t kMaxHeaderBytes = 8192;  // a request's line and headers

using RequestParser = http::request_parser<http::empty_body>;

// A parser with the view's limits: kMaxHeaderBytes of header, no body.
void limit_parser(RequestParser& parser);

struct Answer {
  http::status status = http::status::not_found;
  const PageAsset* asset = nullptr;  // status 200: the file
  bool stream = false;               // a WebSocket upgrade to /stream
};

// GET of a page file (the query string ignored), an upgrade to
// /stream; 405 for other methods, 400 for an upgrade elsewhere or a plain
// request to /stream, else 404.
Answer answer(const http::request<http::empty_body>& request);

// Parses `bytes` as one request with the view's limits and answers it: 431 for
// a header over the limit, 400 for bytes that are no request.
Answer answer(std::string_view bytes);

}  // namespace lccp::view
