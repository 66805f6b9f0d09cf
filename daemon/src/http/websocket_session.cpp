#include "websocket_session.hpp"

#include <boost/asio/buffer.hpp>
#include <boost/beast/websocket/error.hpp>
#include <boost/beast/websocket/stream_base.hpp>

#include "http_server.hpp"

namespace kew::daemon::http {

namespace beast = boost::beast;
namespace websocket = boost::beast::websocket;

namespace {
/// Nothing a client may send is longer (it should send nothing but control frames).
constexpr std::size_t kMaxClientMessageBytes = 1024;
}  // namespace

WebSocketSession::WebSocketSession(boost::asio::ip::tcp::socket socket, HttpServer& server)
    : ws_(std::move(socket)), server_(server) {}

void WebSocketSession::start(beast::http::request<beast::http::string_body> upgrade) {
  websocket::stream_base::timeout timeout;
  timeout.handshake_timeout = server_.request_timeout();
  // A client that answers no ping (it stopped reading, or vanished) is closed.
  timeout.idle_timeout = server_.write_timeout();
  timeout.keep_alive_pings = true;
  ws_.set_option(timeout);
  ws_.read_message_max(kMaxClientMessageBytes);
  ws_.auto_fragment(false);  // one frame per batch
  ws_.set_option(websocket::stream_base::decorator(
      [](websocket::response_type& response) { response.set(beast::http::field::server, "kewd"); }));
  ws_.async_accept(upgrade, [self = shared_from_this()](beast::error_code ec) {
    if (ec) {
      self->server_.statistics().websocket_closed.reject("handshake", ec.message());
      return self->finish();
    }
    self->open_ = true;
    ++self->server_.statistics().websockets_accepted;
    self->send(std::make_shared<const std::string>(self->server_.source().snapshot()));
    self->read();
  });
}

void WebSocketSession::read() {
  ws_.async_read(input_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
    if (self->finished_) return;
    if (!ec) return self->end("client_message", "a client sends nothing on /ws");
    if (ec == websocket::error::closed) return self->finish();  // the client closed
    if (ec == beast::error::timeout) return self->end("timeout", "no answer to pings");
    if (ec == boost::asio::error::eof || ec == boost::asio::error::connection_reset ||
        ec == boost::asio::error::operation_aborted || self->ending_)
      return self->finish();
    self->end("protocol_error", ec.message());
  });
}

void WebSocketSession::send(Message message) {
  if (!open_ || ending_ || finished_) return;
  if (queued_bytes_ + message->size() > server_.limits().client_queue_bytes)
    return end("cut_off", "more than client_queue_bytes waiting");
  queued_bytes_ += message->size();
  queue_.push_back(std::move(message));
  if (!writing_) write_next();
}

void WebSocketSession::write_next() {
  if (queue_.empty() || finished_) return;
  writing_ = true;
  // The message in flight stays with the handler: end() may clear the queue meanwhile.
  Message message = std::move(queue_.front());
  queue_.pop_front();
  ws_.text(true);
  ws_.async_write(boost::asio::buffer(*message),
                  [self = shared_from_this(), message](beast::error_code ec, std::size_t) {
                    self->writing_ = false;
                    if (self->finished_) return;
                    if (!self->ending_) self->queued_bytes_ -= message->size();
                    if (ec) return self->finish();
                    if (self->ending_) return;
                    self->write_next();
                  });
}

void WebSocketSession::end(std::string_view reason, std::string_view message) {
  if (ending_ || finished_) return;
  ending_ = true;
  server_.statistics().websocket_closed.reject(reason, message);
  queue_.clear();
  queued_bytes_ = 0;
  // A client that fell behind or answers no ping is not reading: a close frame would
  // wait behind its full socket for the closing handshake's timeout (request_timeout_s),
  // holding the connection that long after it was cut off.
  if (writing_ || !open_ || reason == "cut_off" || reason == "timeout") return finish();
  // What is left is the client's own fault: a message, or a broken frame.
  const websocket::close_reason why(websocket::close_code::policy_error, std::string(reason));
  ws_.async_close(why, [self = shared_from_this()](beast::error_code) { self->finish(); });
}

void WebSocketSession::close() {
  ending_ = true;
  finish();
}

void WebSocketSession::finish() {
  if (finished_) return;
  finished_ = true;
  queue_.clear();
  queued_bytes_ = 0;
  beast::error_code ignored;
  beast::get_lowest_layer(ws_).socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
  beast::get_lowest_layer(ws_).close();
  server_.forget(this);
}

}  // namespace kew::daemon::http
