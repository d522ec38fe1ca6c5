// The live view's server: its page, its answers to bad requests, and the
// stream's newest-frame-only policy, through real sockets on the loopback.
#include <chrono>
#include <cstring>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "expect_error.hpp"
#include "http_request.hpp"  // src/view
#include "lccp/view/view_server.hpp"

namespace lccp::view {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

struct Reply {
  unsigned status = 0;  // 0: the connection closed without an answer
  std::string content_type;
  std::string body;
};

std::uint16_t port_of(const ViewServer& server) {
  const std::string url = server.url();  // http://127.0.0.1:PORT/
  return static_cast<std::uint16_t>(std::stoi(url.substr(url.rfind(':') + 1)));
}

// Sends `bytes` on a new connection and reads until the server closes it.
std::string send_request(const ViewServer& server, const std::string& bytes) {
  asio::io_context io;
  tcp::socket socket(io);
  socket.connect({asio::ip::make_address("127.0.0.1"), port_of(server)});
  asio::write(socket, asio::buffer(bytes));
  std::string answer;
  beast::error_code error;
  char chunk[4096];
  while (!error) answer.append(chunk, socket.read_some(asio::buffer(chunk), error));
  return answer;
}

Reply parse_reply(const std::string& bytes) {
  Reply reply;
  if (bytes.empty()) return reply;
  http::response_parser<http::string_body> parser;
  parser.eager(true);
  beast::error_code error;
  parser.put(asio::buffer(bytes), error);
  parser.put_eof(error);
  reply.status = static_cast<unsigned>(parser.get().result_int());
  const beast::string_view type = parser.get()[http::field::content_type];
  reply.content_type.assign(type.data(), type.size());
  reply.body = parser.get().body();
  return reply;
}

Reply get(const ViewServer& server, const std::string& target) {
  return parse_reply(send_request(server, "GET " + target + " HTTP/1.1\r\nHost: localhost\r\n\r\n"));
}

// A page's stream, read from the test.
class StreamClient {
 public:
  explicit StreamClient(const ViewServer& server) : socket_(io_) {
    beast::get_lowest_layer(socket_).connect({asio::ip::make_address("127.0.0.1"), port_of(server)});
    socket_.handshake("127.0.0.1", "/stream");
  }
  // The next message's JSON header.
  nlohmann::json next() {
    beast::flat_buffer buffer;
    socket_.read(buffer);
    const std::string bytes = beast::buffers_to_string(buffer.data());
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data(), 4);
    last_size_ = bytes.size();
    return nlohmann::json::parse(bytes.substr(4, length));
  }
  // Headers until one satisfies `done`.
  template <typename Done>
  nlohmann::json until(Done done) {
    for (;;) {
      nlohmann::json header = next();
      if (done(header)) return header;
    }
  }
  std::size_t last_size() const { return last_size_; }
  websocket::stream<tcp::socket>& socket() { return socket_; }

 private:
  asio::io_context io_;
  websocket::stream<tcp::socket> socket_;
  std::size_t last_size_ = 0;
};

// A width x height organized frame: the left half segment 2, the right half segment 3.
FrameResult frame(std::uint64_t index, std::uint32_t width = 64, std::uint32_t height = 48) {
  FrameResult result;
  result.frame.index = index;
  result.frame.cloud.width = width;
  result.frame.cloud.height = height;
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      result.frame.cloud.points.emplace_back(0.01f * (x - 32.0f), 0.01f * (y - 24.0f), 1.0f);
      result.segmentation.labels.push_back(x < width / 2 ? 2 : 3);
    }
  }
  for (std::uint32_t id : {2u, 3u}) {
    ObjectSegments object;
    object.object.id = id;
    object.object.points = std::uint64_t{width / 2} * height;
    result.segmentation.segments.push_back(object);
  }
  result.frame.captured = Clock::now();
  result.labels_ready = result.frame.captured + std::chrono::milliseconds(20);
  return result;
}

PipelineStats counts(std::uint64_t frames) {
  PipelineStats stats;
  stats.frames_received = frames;
  stats.frames_completed = frames;
  return stats;
}

TEST(ViewAddress, ParsesPortAndHostPort) {
  EXPECT_EQ(parse_view_address("8080").host, "127.0.0.1");
  EXPECT_EQ(parse_view_address("8080").port, 8080);
  EXPECT_EQ(parse_view_address("0.0.0.0:9000").host, "0.0.0.0");
  EXPECT_EQ(parse_view_address("0.0.0.0:9000").port, 9000);
  EXPECT_EQ(parse_view_address("[::1]:80").host, "::1");
  for (const char* bad : {"", "http", "70000", ":80", "host:", "80x", "-1"}) {
    test::expect_lccp_error([&] { parse_view_address(bad); }, {"--view", "(use [HOST:]PORT)"});
  }
}

TEST(ViewServer, ServesItsPageAndNothingElse) {
  const ViewServer server({"127.0.0.1", 0});
  EXPECT_EQ(server.url().rfind("http://127.0.0.1:", 0), 0u) << server.url();
  const Reply page = get(server, "/");
  EXPECT_EQ(page.status, 200u);
  EXPECT_EQ(page.content_type, "text/html; charset=utf-8");
  EXPECT_NE(page.body.find("<title>LCCP Stream</title>"), std::string::npos);
  EXPECT_EQ(get(server, "/view.js?v=1").status, 200u);
  EXPECT_EQ(get(server, "/view.css").content_type, "text/css; charset=utf-8");
  for (const char* target : {"/index.html/../view.js", "/../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "//etc/passwd",
                             "/etc/passwd", "/view.js/", "/VIEW.JS", "*"}) {
    EXPECT_EQ(get(server, target).status, 404u) << target;
  }
  EXPECT_EQ(parse_reply(send_request(server, "POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\n\r\n")).status, 405u);
  EXPECT_EQ(get(server, "/stream").status, 400u);  // the stream is a WebSocket
}

TEST(ViewServer, AnswersBadRequestsAndKeepsServing) {
  const ViewServer server({"127.0.0.1", 0});
  const std::string huge = "GET / HTTP/1.1\r\nHost: x\r\nX-Big: " + std::string(20000, 'a') + "\r\n\r\n";
  EXPECT_EQ(parse_reply(send_request(server, huge)).status, 431u);
  EXPECT_EQ(parse_reply(send_request(server, std::string("\x16\x03\x01\x02\x00garbage\r\n\r\n", 16))).status, 400u);
  EXPECT_EQ(get(server, "/").status, 200u);
}

TEST(ViewServer, TwoHundredClientsThatVanishCostNothing) {
  ViewServer server({"127.0.0.1", 0});
  asio::io_context io;
  for (int i = 0; i < 200; ++i) {
    tcp::socket socket(io);
    socket.connect({asio::ip::make_address("127.0.0.1"), port_of(server)});
    if (i % 2) asio::write(socket, asio::buffer(std::string("GET / HT")));  // half a request line
  }
  EXPECT_EQ(get(server, "/").status, 200u);
  StreamClient client(server);
  server.publish(frame(7), counts(1));
  EXPECT_EQ(client.until([](const auto& h) { return h.contains("index"); })["index"], 7);
}

TEST(ViewServer, ConnectionsBeyondTheLimitAreClosed) {
  const ViewServer server({"127.0.0.1", 0}, ViewLimits{4, std::chrono::seconds(30), std::chrono::milliseconds(500)});
  asio::io_context io;
  std::vector<tcp::socket> idle;
  for (int i = 0; i < 4; ++i) {
    idle.emplace_back(io).connect({asio::ip::make_address("127.0.0.1"), port_of(server)});
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // accepted, each waiting for a request
  EXPECT_EQ(get(server, "/").status, 0u);                        // closed at accept, no answer
  idle.clear();
  Reply page;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);  // a loaded machine
  while (page.status != 200 && std::chrono::steady_clock::now() < deadline) {  // until the server has seen them go
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    page = get(server, "/");
  }
  EXPECT_EQ(page.status, 200u);
}

TEST(ViewServer, StreamSendsTheNewestFrameAndTheFinalCounts) {
  ViewServer server({"127.0.0.1", 0});
  StreamClient client(server);
  for (std::uint64_t i = 0; i < 5; ++i) server.publish(frame(i), counts(i));
  const nlohmann::json header = client.until([](const auto& h) { return h.value("index", -1) == 4; });
  EXPECT_EQ(header["width"], 64);
  EXPECT_EQ(header["height"], 48);
  ASSERT_EQ(header["segments"].size(), 2u);
  EXPECT_EQ(header["segments"][0]["id"], 2);
  EXPECT_EQ(header["segments"][1]["points"], 32 * 48);
  EXPECT_GT(client.last_size(), 64u * 48u * 3u);  // the labels and the shading follow the header
  server.finish(counts(5));
  const nlohmann::json end = client.until([](const auto& h) { return h["ended"] == true; });
  EXPECT_EQ(end["counts"]["frames_received"], 5);
  EXPECT_EQ(end["counts"]["frames_completed"], 5);
  EXPECT_EQ(end["counts"]["frames_dropped"], 0);
  EXPECT_GE(end["latency"]["frames"], 1);
  EXPECT_NEAR(end["latency"]["end_to_end"]["p50"].get<double>(), 20.0, 0.5);
}

TEST(ViewServer, AStalledClientSkipsFramesAndHoldsNobodyBack) {
  ViewServer server({"127.0.0.1", 0});
  StreamClient stalled(server);  // never reads
  StreamClient reader(server);
  FrameResult big = frame(0, 640, 480);  // about 230 kB a message
  for (std::uint64_t i = 0; i < 300; ++i) {  // 3 s: more messages than the stalled socket's buffers hold
    big.frame.index = i;
    server.publish(big, counts(i + 1));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(reader.until([](const auto& h) { return h.value("index", -1) == 299; })["index"], 299);
  server.finish(counts(300));
  EXPECT_EQ(reader.until([](const auto& h) { return h["ended"] == true; })["counts"]["frames_received"], 300);
  // Read at last, the stalled page gets what its socket held, then the newest: the end.
  const nlohmann::json end = stalled.until([](const auto& h) { return h["ended"] == true; });
  EXPECT_EQ(end["counts"]["frames_received"], 300);
  EXPECT_EQ(end["index"], 299);
}

TEST(ViewServer, APageThatSendsGarbageIsClosedAndOthersGoOn) {
  ViewServer server({"127.0.0.1", 0});
  StreamClient rude(server);
  StreamClient polite(server);
  rude.socket().text(true);
  rude.socket().write(asio::buffer(std::string("\x01\x02 not a request")));
  beast::flat_buffer buffer;
  beast::error_code error;
  while (!error) rude.socket().read(buffer, error);  // the server closes it
  server.publish(frame(3), counts(1));
  EXPECT_EQ(polite.until([](const auto& h) { return h.contains("index"); })["index"], 3);
}

TEST(ViewServer, WaitsForAViewerUntilStopped) {
  const ViewServer server({"127.0.0.1", 0});
  std::stop_source stop;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    stop.request_stop();
  });
  server.wait_for_viewer(stop.get_token());  // returns on the stop
  stopper.join();
  StreamClient client(server);
  server.wait_for_viewer({});  // returns at once: a page is open
}

TEST(ViewRequest, AnswersRawBytes) {
  EXPECT_EQ(answer("GET / HTTP/1.1\r\nHost: x\r\n\r\n").status, http::status::ok);
  EXPECT_EQ(answer("GET /nope HTTP/1.1\r\nHost: x\r\n\r\n").status, http::status::not_found);
  EXPECT_EQ(answer("GET / HTTP/1.1\r\nHost: x\r\n").status, http::status::bad_request);  // unfinished
  EXPECT_EQ(answer("\r\n\r\n").status, http::status::bad_request);
  EXPECT_EQ(answer("GET / HTTP/1.1\r\nA: " + std::string(9000, 'b') + "\r\n\r\n").status,
            http::status::request_header_fields_too_large);
  EXPECT_TRUE(answer("GET /stream HTTP/1.1\r\nHost: x\r\nConnection: Upgrade\r\nUpgrade: websocket\r\n"
                     "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n")
                  .stream);
}

}  // namespace
}  // namespace lccp::view
