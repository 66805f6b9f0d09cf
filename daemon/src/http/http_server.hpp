#pragma once
// kewd's HTTP server (design §5.8): one acceptor on the service's I/O thread, the HTTP
// sessions it accepted and the WebSocket sessions they became. It owns the limits, the
// counters and the per-tick WebSocket batch; what is served comes from the Router, which
// asks the service through HttpSource.

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <boost/asio/ip/tcp.hpp>

#include "accept_guard.hpp"
#include "http_source.hpp"
#include "kew/daemon/config.hpp"
#include "kew/util/rejections.hpp"
#include "router.hpp"

namespace kew::daemon::http {

class HttpSession;
class WebSocketSession;

/// What /metrics reports of the HTTP server.
struct HttpStatistics {
  std::uint64_t connections_accepted = 0;
  std::uint64_t connections_refused = 0;  ///< closed at once: every slot taken by busy connections
  std::uint64_t connections_evicted = 0;  ///< closed to make room: waiting longest for a request
  std::uint64_t accept_failures = 0;
  std::map<unsigned, std::uint64_t> responses;  ///< by status code
  /// Requests refused before or instead of a route (malformed, header_too_large, ...).
  Rejections bad_requests;
  /// WebSocket connections closed by kewd, by reason (client_message, protocol_error,
  /// cut_off, ...).
  Rejections websocket_closed;
  std::uint64_t websockets_accepted = 0;
};

class HttpServer {
 public:
  HttpServer(boost::asio::io_context& io, const boost::asio::ip::tcp::endpoint& endpoint, const HttpConfig& config,
             HttpSource source);
  ~HttpServer();
  void start();
  /// Stops accepting and closes every connection.
  void shutdown();
  /// Takes the limits of `fresh` (SIGHUP): connections, bytes and time-outs apply to what
  /// comes next; the listen address, the files served and the host names need a restart.
  void set_limits(const HttpConfig& fresh);

  /// Adds one stream object (a line of the alert stream, '\n' optional) to the batch the
  /// WebSocket clients get at the next flush(). Nothing happens without WebSocket clients.
  void push(std::string_view object);
  /// Sends the batch (a JSON array) to every WebSocket client: once per service tick.
  void flush();
  bool has_websockets() const { return !websockets_.empty(); }

  std::uint16_t port() const { return acceptor_.local_endpoint().port(); }
  /// The limits ([http] in deploy/kew.toml says why each).
  const HttpConfig& limits() const { return config_; }
  std::chrono::steady_clock::duration request_timeout() const { return request_timeout_; }
  std::chrono::steady_clock::duration write_timeout() const { return write_timeout_; }
  const HttpStatistics& statistics() const { return stats_; }
  HttpStatistics& statistics() { return stats_; }
  std::size_t connections() const { return sessions_.size() + websockets_.size(); }
  std::size_t websockets() const { return websockets_.size(); }
  /// WebSockets at once: max_connections less kStatusSlots (at least 1), so that a
  /// request such as GET /api/status always finds a connection to replace.
  std::size_t websocket_slots() const;
  static constexpr std::size_t kStatusSlots = 2;
  /// Bytes queued for every WebSocket client together.
  std::size_t queued_bytes() const;
  Router& router() { return router_; }
  const HttpSource& source() const { return source_; }

  // For the sessions.
  void forget(const HttpSession* session);
  void forget(const WebSocketSession* session);
  void adopt(std::shared_ptr<WebSocketSession> session);
  void count_response(unsigned status) { ++stats_.responses[status]; }

 private:
  void accept();
  /// Before `newcomer` takes a slot: closes the session the slot policy names, if any.
  void make_room(const boost::asio::ip::tcp::socket& newcomer);

  boost::asio::ip::tcp::acceptor acceptor_;
  AcceptGuard accept_guard_;
  HttpConfig config_;
  std::chrono::steady_clock::duration request_timeout_, write_timeout_;
  HttpSource source_;
  Router router_;
  std::vector<std::shared_ptr<HttpSession>> sessions_;  // oldest first
  std::vector<std::shared_ptr<WebSocketSession>> websockets_;
  std::string batch_;  // "[obj,obj" while objects wait for flush()
  HttpStatistics stats_;
  bool stopped_ = false;
};

}  // namespace kew::daemon::http
