#include "http_session.hpp"

#include <boost/beast/core/bind_handler.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/write.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <fmt/format.h>

#include "http_server.hpp"
#include "kew/config/address.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "websocket_session.hpp"

namespace kew::daemon::http {

namespace beast = boost::beast;
namespace bhttp = boost::beast::http;

HttpSession::HttpSession(boost::asio::ip::tcp::socket socket, HttpServer& server)
    : stream_(std::move(socket)), server_(server), since_(std::chrono::steady_clock::now()) {
  boost::system::error_code ec;
  const auto peer = stream_.socket().remote_endpoint(ec);
  if (ec) return;
  address_ = peer.address().to_string();
  client_ = config::to_string({address_, peer.port()});
}

void HttpSession::start() { read(); }

void HttpSession::close() {
  if (closed_) return;
  closed_ = true;
  beast::error_code ignored;
  stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
  stream_.close();
}

SlotHolder HttpSession::holder() const {
  const bool stalled = writing_ && std::chrono::steady_clock::now() - since_ >= kStalledWrite;
  return {address_, !closed_ && (reading_ || stalled), since_};
}

void HttpSession::read() {
  parser_.emplace();
  parser_->header_limit(static_cast<std::uint32_t>(server_.limits().max_header_bytes));
  parser_->body_limit(server_.limits().max_body_bytes);
  since_ = std::chrono::steady_clock::now();
  reading_ = true;
  // The whole request within request_timeout: a slow client cannot hold the connection.
  stream_.expires_after(server_.request_timeout());
  bhttp::async_read(stream_, buffer_, *parser_,
                    [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
}

void HttpSession::on_read(beast::error_code ec) {
  reading_ = false;
  if (closed_) {
    server_.forget(this);
    return;
  }
  if (ec == bhttp::error::header_limit) return refuse(431, "header_too_large", "request header fields too large");
  if (ec == bhttp::error::body_limit) return refuse(413, "body_too_large", "request body too large");
  if (ec == beast::error::timeout) {
    if (parser_->got_some()) server_.statistics().bad_requests.reject("timeout", "request not complete in time");
    close();
    server_.forget(this);
    return;
  }
  if (ec == bhttp::error::end_of_stream || ec == boost::asio::error::eof ||
      ec == boost::asio::error::connection_reset || ec == boost::asio::error::operation_aborted) {
    close();
    server_.forget(this);
    return;
  }
  if (ec) return refuse(400, "malformed", ec.message());

  bhttp::request<bhttp::string_body> request = parser_->release();
  const std::uint16_t port = server_.port();
  if (beast::websocket::is_upgrade(request)) {
    const std::string_view target(request.target().data(), request.target().size());
    if (target.substr(0, target.find('?')) != "/ws") return refuse(404, "not_found", "only /ws is a WebSocket");
    if (!server_.router().websocket_allowed(request, port)) return refuse(403, "", "foreign Origin");
    if (server_.websockets() >= server_.websocket_slots())
      return refuse(503, "websockets_full", "every WebSocket slot is taken");
    stream_.expires_never();
    auto ws = std::make_shared<WebSocketSession>(stream_.release_socket(), server_);
    closed_ = true;  // the socket is the WebSocket's now
    server_.adopt(ws);
    server_.forget(this);
    ws->start(std::move(request));
    return;
  }
  const Reply reply = server_.router().handle(request, client_, port);
  send(reply, request.keep_alive(), request.method() == bhttp::verb::head);
}

void HttpSession::refuse(unsigned status, std::string_view reason, std::string_view message) {
  if (!reason.empty()) server_.statistics().bad_requests.reject(reason, message);
  Reply reply{status, "application/json", "{\"error\":"};
  protocol::append_json_string(reply.body, message);
  reply.body += "}\n";
  send(reply, false, false);
}

void HttpSession::send(const Reply& reply, bool keep_alive, bool head) {
  server_.count_response(reply.status);
  response_ = std::make_shared<bhttp::response<bhttp::string_body>>(static_cast<bhttp::status>(reply.status), 11);
  response_->set(bhttp::field::server, "kewd");
  response_->set(bhttp::field::content_type, reply.content_type);
  response_->set(bhttp::field::cache_control, "no-store");
  response_->set("X-Content-Type-Options", "nosniff");
  response_->keep_alive(keep_alive);
  response_->body() = head ? std::string() : reply.body;
  response_->prepare_payload();
  if (head) response_->content_length(reply.body.size());
  stream_.expires_after(server_.write_timeout());
  writing_ = true;
  since_ = std::chrono::steady_clock::now();
  bhttp::async_write(stream_, *response_, [self = shared_from_this(), keep_alive](beast::error_code ec, std::size_t) {
    self->writing_ = false;
    self->response_.reset();
    if (!ec && keep_alive && !self->closed_) return self->read();
    self->close();
    self->server_.forget(self.get());
  });
}

}  // namespace kew::daemon::http
