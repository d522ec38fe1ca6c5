// The view's answer to a request (http_request.hpp).
#include "http_request.hpp"

#include <boost/asio/buffer.hpp>
#include <boost/beast/websocket/rfc6455.hpp>

namespace lccp::view {

void limit_parser(RequestParser& parser) {
  parser.header_limit(kMaxHeaderBytes);
  parser.body_limit(0);
}

Answer answer(const http::request<http::empty_body>& request) {
  const std::string_view target(request.target().data(), request.target().size());
  const std::string_view path = target.substr(0, target.find('?'));
  const bool upgrade = boost::beast::websocket::is_upgrade(request);
  if (path == "/stream") return upgrade ? Answer{http::status::switching_protocols, nullptr, true} : Answer{http::status::bad_request};
  if (upgrade) return {http::status::bad_request};
  if (request.method() != http::verb::get) return {http::status::method_not_allowed};
  for (const PageAsset& asset : page_assets()) {
    if (asset.path == path) return {http::status::ok, &asset};
  }
  return {http::status::not_found};
}

Answer answer(std::string_view bytes) {
  RequestParser parser;
  limit_parser(parser);
  parser.eager(true);
  boost::beast::error_code error;
  parser.put(boost::asio::buffer(bytes.data(), bytes.size()), error);
  if (error == http::error::header_limit) return {http::status::request_header_fields_too_large};
  if (error || !parser.is_header_done()) return {http::status::bad_request};
  return answer(parser.get());
}

}  // namespace lccp::view
