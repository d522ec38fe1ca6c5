#pragma once
// The live view: a small HTTP + WebSocket server (Boost.Beast) that shows a
// running stream in a browser; a RunObserver of the pipeline (PipelineConfig). It serves its own page (compiled in: no file
// system paths) at /, and the stream at /stream: one binary WebSocket message
// per frame it sends (format: src/view/view_message.hpp), the newest frame only.
//
// It never slows the pipeline: publish() copies a decimated sample of the frame
// and returns; sampling into a message, the JSON and every socket run on the
// server's own thread. Each client is sent the newest message when its last
// one has gone out, so a slow or stalled client skips frames and holds one
// message at most.
#include <chrono>
#include <cstdint>
#include <memory>
#include <stop_token>
#include <string>
#include <string_view>

#include "lccp/pipeline/pipeline.hpp"

namespace lccp::view {

// Where the server listens: --view [HOST:]PORT. Port 0 picks a free one.
struct ViewAddress {
  std::string host = "127.0.0.1";  // loopback unless another address is given
  std::uint16_t port = 0;
};

// Parses "[HOST:]PORT" ("8080", "0.0.0.0:8080", "[::1]:8080"; HOST an IP
// address or localhost). Throws
// lccp::Error with one line for anything else.
ViewAddress parse_view_address(std::string_view text);

struct ViewLimits {
  unsigned max_connections = 64;                        // at once; more are closed at accept
  std::chrono::seconds request_timeout{10};             // to send a request's header
  std::chrono::milliseconds final_flush{2000};          // the last message's time to go out at close
};

class ViewServer final : public RunObserver {
 public:
  // Binds and starts serving. Throws lccp::Error ("view: cannot listen on
  // HOST:PORT: reason") if the address cannot be bound.
  explicit ViewServer(const ViewAddress& address, ViewLimits limits = {});
  ~ViewServer() override;  // the final counts go out (ViewLimits::final_flush at most), then every socket closes
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  std::string url() const;  // http://HOST:PORT/

  // A frame handed over (the pipeline's sink thread, in frame order) and the
  // run's counts as they stand. Copies a sample and returns.
  void publish(const FrameResult& result, const PipelineStats& stats) override;

  // The run's final counts (they add up): the page shows the run as ended.
  void finish(const PipelineStats& stats) override;

  // Blocks until a page has opened the stream, or `stop` is requested.
  void wait_for_viewer(std::stop_token stop) const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lccp::view
