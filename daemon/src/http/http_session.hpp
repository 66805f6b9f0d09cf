#pragma once
// One HTTP connection (design §5.8): reads requests within the header, body and time
// limits, answers each through the Router, and hands an upgrade of /ws over to a
// WebSocketSession. Owned by the HttpServer while it lives; runs on the I/O thread.

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/string_body.hpp>

#include "slot_policy.hpp"

namespace kew::daemon::http {

class HttpServer;
struct Reply;

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket socket, HttpServer& server);
  void start();
  /// Closes the connection at once (eviction, shutdown).
  void close();
  /// What the slot policy needs to know of it: silent while it waits for a request
  /// (none of it or part of it has arrived), since the wait began, and while a reply has
  /// been waiting kStalledWrite or more for the client to read it, since the write began.
  SlotHolder holder() const;
  static constexpr std::chrono::seconds kStalledWrite{1};

 private:
  void read();
  void on_read(boost::beast::error_code ec);
  /// Answers a request the parser refused (431, 413, 400), then closes.
  void refuse(unsigned status, std::string_view reason, std::string_view message);
  void send(const Reply& reply, bool keep_alive, bool head);

  boost::beast::tcp_stream stream_;
  HttpServer& server_;
  boost::beast::flat_buffer buffer_;
  std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
  std::shared_ptr<boost::beast::http::response<boost::beast::http::string_body>> response_;
  std::string client_;   ///< "HOST:PORT" of the peer
  std::string address_;  ///< the peer's IP address
  std::chrono::steady_clock::time_point since_;
  bool reading_ = false;
  bool writing_ = false;
  bool closed_ = false;
};

}  // namespace kew::daemon::http
