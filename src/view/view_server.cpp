// The live view's server (view_server.hpp): Boost.Beast over one io_context on
// one thread of its own; every session and the encoder run there, so none of
// their state needs a lock. Only the hand-over from publish() does.
#include "lccp/view/view_server.hpp"

#include <algorithm>
#include <charconv>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <spdlog/spdlog.h>

#include "http_request.hpp"
#include "lccp/error.hpp"
#include "view_message.hpp"

namespace lccp::view {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using Message = std::shared_ptr<const std::string>;

constexpr auto kMessagePeriod = std::chrono::milliseconds(33);  // 30 messages a second at most
constexpr std::size_t kMaxClientMessage = 1024;                 // the page sends nothing

std::string text(beast::string_view view) { return {view.data(), view.size()}; }

std::string peer_of(const tcp::socket& socket) {
  beast::error_code error;
  const tcp::endpoint peer = socket.remote_endpoint(error);
  return error ? std::string("a client") : peer.address().to_string() + ":" + std::to_string(peer.port());
}

}  // namespace

ViewAddress parse_view_address(std::string_view text) {
  const auto bad = [&](const char* why) { return Error("--view " + std::string(text) + ": " + why + " (use [HOST:]PORT)"); };
  ViewAddress address;
  const std::size_t colon = text.rfind(':');
  std::string_view port = text;
  if (colon != std::string_view::npos) {
    std::string_view host = text.substr(0, colon);
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    if (host.empty()) throw bad("no host before ':'");
    address.host = host == "localhost" ? "127.0.0.1" : std::string(host);
    port = text.substr(colon + 1);
  }
  const auto [end, error] = std::from_chars(port.data(), port.data() + port.size(), address.port);
  if (port.empty() || error != std::errc() || end != port.data() + port.size()) throw bad("the port must be 0 to 65535");
  return address;
}

class ViewServer::Impl {
 public:
  Impl(const ViewAddress& address, ViewLimits limits);
  ~Impl();

  void publish(const FrameResult& result, const PipelineStats& stats);
  void finish(const PipelineStats& stats);
  std::string url() const { return url_; }

  class HttpSession;
  class StreamSession;

  // The sink's thread (publish, finish): a change to the published state under
  // mutex_, then a take_published posted to the server's thread.
  template <typename Change>
  void hand_over(Change&& change);

  // The server's thread only:
  void accept();
  void open_stream(beast::tcp_stream stream, http::request<http::empty_body> request);
  void stream_opened(const std::shared_ptr<StreamSession>& session);
  void take_published();
  void send_newest();
  void close_when_sent(Clock::time_point deadline);

  const ViewLimits limits_;
  const Clock::time_point start_ = Clock::now();

  // publish() and finish() to the server's thread.
  std::mutex mutex_;
  std::optional<FrameSample> published_;
  std::vector<FrameTimes> published_times_;
  PipelineStats published_stats_;
  bool ended_ = false;
  bool take_posted_ = false;
  std::condition_variable_any viewer_opened_;
  std::uint64_t viewers_ = 0;  // streams opened; under mutex_

  // The server's thread only.
  std::optional<FrameSample> frame_;  // the newest sample, not yet encoded if dirty_
  RunFigures figures_;
  bool dirty_ = false;
  Clock::time_point last_encoded_{};
  Message newest_;
  std::vector<std::weak_ptr<StreamSession>> streams_;
  unsigned connections_ = 0;

  asio::io_context io_;  // after what its handlers touch: destroyed first
  tcp::acceptor acceptor_{io_};
  asio::steady_timer send_timer_{io_};
  asio::steady_timer close_timer_{io_};
  std::string url_;
  std::thread thread_;
};

// One HTTP request: a page file, an error status, or the upgrade to /stream.
class ViewServer::Impl::HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket socket, Impl& server) : peer_(peer_of(socket)), stream_(std::move(socket)), server_(server) {
    ++server_.connections_;
  }
  ~HttpSession() { --server_.connections_; }

  void start() {
    limit_parser(parser_);
    stream_.expires_after(server_.limits_.request_timeout);
    http::async_read_header(stream_, buffer_, parser_,
                            [self = shared_from_this()](beast::error_code error, std::size_t) { self->on_header(error); });
  }

 private:
  void on_header(beast::error_code error) {
    const bool closed = error == http::error::end_of_stream || error == http::error::partial_message ||
                        error.category() != http::make_error_code(http::error::bad_method).category();
    if (error && closed) return spdlog::info("view: {}: no request ({})", peer_, error.message());  // or timed out
    if (error == http::error::header_limit) return respond({http::status::request_header_fields_too_large}, "header too large");
    if (error) return respond({http::status::bad_request}, error.message());
    const Answer reply = answer(parser_.get());
    if (reply.stream) return server_.open_stream(std::move(stream_), parser_.release());
    const auto& request = parser_.get();
    respond(reply, reply.status == http::status::ok ? "" : text(request.method_string()) + " " + text(request.target()));
  }

  void respond(const Answer& reply, const std::string& problem) {
    if (!problem.empty()) spdlog::warn("view: {}: {} ({})", peer_, static_cast<unsigned>(reply.status), problem.substr(0, 200));
    auto response = std::make_shared<http::response<http::string_body>>(reply.status, 11);
    response->set(http::field::server, "lccp-view");
    response->set(http::field::cache_control, "no-store");
    const std::string_view type = reply.asset ? reply.asset->content_type : "text/plain; charset=utf-8";
    response->set(http::field::content_type, beast::string_view(type.data(), type.size()));
    response->body() = reply.asset ? std::string(reply.asset->body) : text(http::obsolete_reason(reply.status)) + "\n";
    response->keep_alive(false);
    response->prepare_payload();
    http::async_write(stream_, *response, [self = shared_from_this(), response](beast::error_code, std::size_t) {
      beast::error_code ignored;
      self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
      self->stream_.expires_after(std::chrono::seconds(2));
      self->drain();
    });
  }

  // Reads what the client still sends until it closes (or 2 s pass), so that
  // closing with unread bytes does not reset the connection before the client
  // has read the answer (a lingering close).
  void drain() {
    stream_.async_read_some(asio::buffer(discard_), [self = shared_from_this()](beast::error_code error, std::size_t) {
      if (!error) self->drain();
    });
  }

  std::string peer_;
  beast::tcp_stream stream_;
  beast::flat_buffer buffer_{2 * kMaxHeaderBytes};  // the parser's header_limit answers first
  RequestParser parser_;
  Impl& server_;
  char discard_[4096];
};

// One page's stream: the newest message whenever the last one has gone out.
class ViewServer::Impl::StreamSession : public std::enable_shared_from_this<StreamSession> {
 public:
  StreamSession(beast::tcp_stream stream, Impl& server)
      : peer_(peer_of(stream.socket())), socket_(std::move(stream)), server_(server) {
    ++server_.connections_;
  }
  ~StreamSession() { --server_.connections_; }

  void start(http::request<http::empty_body> request) {
    beast::get_lowest_layer(socket_).expires_never();
    socket_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    socket_.read_message_max(kMaxClientMessage);
    socket_.binary(true);
    socket_.async_accept(request, [self = shared_from_this()](beast::error_code error) {
      if (error) return spdlog::warn("view: {}: WebSocket handshake: {}", self->peer_, error.message());
      self->server_.stream_opened(self);
      self->read();
    });
  }

  void offer(const Message& message) {
    newest_ = message;
    if (!writing_ && open_) write_newest();
  }
  bool idle() const { return !open_ || (!writing_ && sent_ == newest_); }
  void close() {
    open_ = false;
    beast::error_code ignored;
    beast::get_lowest_layer(socket_).socket().close(ignored);
  }

 private:
  void read() {
    socket_.async_read(incoming_, [self = shared_from_this()](beast::error_code error, std::size_t) {
      if (error == websocket::error::closed || error == asio::error::operation_aborted) return self->close();
      spdlog::warn("view: {}: {}; stream closed", self->peer_,
                   error ? error.message() : std::string("a message from the page, which sends none"));
      self->close();
    });
  }

  void write_newest() {
    if (!newest_ || newest_ == sent_) return;
    writing_ = true;
    sent_ = newest_;
    socket_.async_write(asio::buffer(*sent_), [self = shared_from_this()](beast::error_code error, std::size_t) {
      self->writing_ = false;
      if (error) return self->close();
      self->write_newest();
    });
  }

  std::string peer_;
  websocket::stream<beast::tcp_stream> socket_;
  Impl& server_;
  beast::flat_buffer incoming_;
  Message newest_, sent_;
  bool writing_ = false;
  bool open_ = true;
};

ViewServer::Impl::Impl(const ViewAddress& address, ViewLimits limits) : limits_(limits) {
  beast::error_code error;
  const asio::ip::address ip = asio::ip::make_address(address.host, error);
  const std::string where = address.host + ":" + std::to_string(address.port);
  if (error) throw Error("view: cannot listen on " + where + ": not an IP address");
  const tcp::endpoint endpoint(ip, address.port);
  acceptor_.open(endpoint.protocol(), error);
  if (!error) acceptor_.set_option(asio::socket_base::reuse_address(true), error);
  if (!error) acceptor_.bind(endpoint, error);
  if (!error) acceptor_.listen(asio::socket_base::max_listen_connections, error);
  if (error) throw Error("view: cannot listen on " + where + ": " + error.message());
  const std::string host = ip.is_v6() ? "[" + address.host + "]" : address.host;
  url_ = "http://" + host + ":" + std::to_string(acceptor_.local_endpoint().port()) + "/";
  accept();
  thread_ = std::thread([this] { io_.run(); });
}

ViewServer::Impl::~Impl() {
  asio::post(io_, [this] {
    beast::error_code ignored;
    acceptor_.close(ignored);
    close_when_sent(Clock::now() + limits_.final_flush);
  });
  thread_.join();
}

void ViewServer::Impl::accept() {
  acceptor_.async_accept([this](beast::error_code error, tcp::socket socket) {
    if (error == asio::error::operation_aborted) return;
    if (!error && connections_ >= limits_.max_connections) {
      spdlog::warn("view: {}: {} connections already; closed", peer_of(socket), connections_);
    } else if (!error) {
      std::make_shared<HttpSession>(std::move(socket), *this)->start();
    }
    accept();
  });
}

void ViewServer::Impl::open_stream(beast::tcp_stream stream, http::request<http::empty_body> request) {
  std::make_shared<StreamSession>(std::move(stream), *this)->start(std::move(request));
}

void ViewServer::Impl::stream_opened(const std::shared_ptr<StreamSession>& session) {
  std::erase_if(streams_, [](const std::weak_ptr<StreamSession>& stream) { return stream.expired(); });
  streams_.push_back(session);
  {
    const std::lock_guard lock(mutex_);
    ++viewers_;
  }
  viewer_opened_.notify_all();
  if (newest_ && !dirty_) session->offer(newest_);
  send_newest();
}

// The sink's thread: a sample of the frame (taken outside the lock: the
// server's thread never waits for it), its times and the counts.
void ViewServer::Impl::publish(const FrameResult& result, const PipelineStats& stats) {
  FrameSample sample = sample_frame(result);
  const FrameTimes times = frame_times(result, std::chrono::duration<double>(Clock::now() - start_).count());
  hand_over([&] {
    published_ = std::move(sample);
    published_times_.push_back(times);
    published_stats_ = stats;
  });
}

void ViewServer::Impl::finish(const PipelineStats& stats) {
  hand_over([&] {
    published_stats_ = stats;
    ended_ = true;
  });
}

template <typename Change>
void ViewServer::Impl::hand_over(Change&& change) {
  const std::lock_guard lock(mutex_);
  change();
  if (std::exchange(take_posted_, true)) return;
  asio::post(io_, [this] { take_published(); });
}

void ViewServer::Impl::take_published() {
  std::vector<FrameTimes> times;
  {
    const std::lock_guard lock(mutex_);
    if (published_) frame_ = std::exchange(published_, std::nullopt);
    times.swap(published_times_);
    figures_.stats = published_stats_;
    figures_.ended = ended_;
    take_posted_ = false;
  }
  add_frame_times(figures_, times);
  dirty_ = true;
  send_newest();
}

// Encodes the newest frame with the figures (at most 30 times a second; the
// run's end at once) and offers it to every stream.
void ViewServer::Impl::send_newest() {
  std::erase_if(streams_, [](const std::weak_ptr<StreamSession>& stream) { return stream.expired(); });
  if (!dirty_ || streams_.empty()) return;
  const Clock::duration since = Clock::now() - last_encoded_;
  if (since < kMessagePeriod && !figures_.ended) {
    send_timer_.expires_after(kMessagePeriod - since);
    send_timer_.async_wait([this](beast::error_code error) {
      if (!error) send_newest();
    });
    return;
  }
  last_encoded_ = Clock::now();
  dirty_ = false;
  newest_ = std::make_shared<const std::string>(encode_frame(frame_ ? &*frame_ : nullptr, figures_));
  for (const auto& stream : streams_) {
    if (const auto session = stream.lock()) session->offer(newest_);
  }
}

void ViewServer::Impl::close_when_sent(Clock::time_point deadline) {
  std::erase_if(streams_, [](const std::weak_ptr<StreamSession>& stream) { return stream.expired(); });
  const bool sent = std::all_of(streams_.begin(), streams_.end(), [](const std::weak_ptr<StreamSession>& stream) {
    const auto session = stream.lock();
    return !session || session->idle();
  });
  if (!sent && Clock::now() < deadline) {
    close_timer_.expires_after(std::chrono::milliseconds(20));
    close_timer_.async_wait([this, deadline](beast::error_code) { close_when_sent(deadline); });
    return;
  }
  for (const auto& stream : streams_) {
    if (const auto session = stream.lock()) session->close();
  }
  send_timer_.cancel();
  io_.stop();
}

ViewServer::ViewServer(const ViewAddress& address, ViewLimits limits)
    : impl_(std::make_unique<Impl>(address, limits)) {}
ViewServer::~ViewServer() = default;

std::string ViewServer::url() const { return impl_->url(); }

void ViewServer::publish(const FrameResult& result, const PipelineStats& stats) { impl_->publish(result, stats); }

void ViewServer::finish(const PipelineStats& stats) { impl_->finish(stats); }

void ViewServer::wait_for_viewer(std::stop_token stop) const {
  std::unique_lock lock(impl_->mutex_);
  impl_->viewer_opened_.wait(lock, stop, [&] { return impl_->viewers_ > 0; });
}

}  // namespace lccp::view
