#pragma once
// One /ws client (design §5.8): a snapshot first, then one text message per service tick
// (a JSON array of stream objects). Its queue of shared messages is bounded in bytes: a
// client that falls that far behind is cut off, so it never slows ingestion. The client
// has nothing to say: any message from it, or a broken frame, closes the connection.

#include <deque>
#include <memory>
#include <string>

#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/websocket/stream.hpp>

namespace kew::daemon::http {

class HttpServer;

using Message = std::shared_ptr<const std::string>;

class WebSocketSession : public std::enable_shared_from_this<WebSocketSession> {
 public:
  WebSocketSession(boost::asio::ip::tcp::socket socket, HttpServer& server);
  /// Completes the handshake of `upgrade`, then sends the snapshot.
  void start(boost::beast::http::request<boost::beast::http::string_body> upgrade);
  /// Queues a message; cuts the client off when its queue would exceed the byte budget.
  void send(Message message);
  /// Closes the connection at once (shutdown).
  void close();
  std::size_t queued_bytes() const { return queued_bytes_; }

 private:
  void read();
  void write_next();
  /// Counts `reason` and ends the connection: a close frame when nothing is being
  /// written, else the socket closed at once (the client is not reading anyway).
  void end(std::string_view reason, std::string_view message);
  void finish();

  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  HttpServer& server_;
  boost::beast::flat_buffer input_;
  std::deque<Message> queue_;
  std::size_t queued_bytes_ = 0;
  bool open_ = false;  // the handshake completed
  bool writing_ = false;
  bool ending_ = false;
  bool finished_ = false;
};

}  // namespace kew::daemon::http
