#include "http_server.hpp"

#include <filesystem>

#include <algorithm>

#include <spdlog/spdlog.h>

#include "http_session.hpp"
#include "peer_address.hpp"
#include "static_files.hpp"
#include "websocket_session.hpp"

namespace kew::daemon::http {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

template <class Session>
void erase_session(std::vector<std::shared_ptr<Session>>& sessions, const Session* session) {
  const auto it = std::find_if(sessions.begin(), sessions.end(), [&](const auto& s) { return s.get() == session; });
  if (it != sessions.end()) sessions.erase(it);
}

}  // namespace

HttpServer::HttpServer(asio::io_context& io, const tcp::endpoint& endpoint, const HttpConfig& config,
                       HttpSource source)
    : acceptor_(io, endpoint),
      accept_guard_(io.get_executor(), "http"),
      config_(config),
      request_timeout_(seconds(config.request_timeout_s)),
      write_timeout_(seconds(config.write_timeout_s)),
      source_(std::move(source)),
      router_(config.web_root.empty() ? default_web_root() : config.web_root, config.leaflet_root, config.host_names,
              source_, stats_.bad_requests, config) {
  // Refusals go to the log rate-limited per reason (their counts are in /metrics).
  stats_.bad_requests.set_reporter([](std::string_view reason, std::string_view message) {
    spdlog::info("http: refused a request ({}): {}", reason, message);
  });
  stats_.websocket_closed.set_reporter([](std::string_view reason, std::string_view message) {
    spdlog::info("http: closed a WebSocket ({}): {}", reason, message);
  });
}

HttpServer::~HttpServer() = default;

void HttpServer::start() {
  accept();
  const std::string& root = router().web().root();
  spdlog::info("HTTP (map, API, metrics) on port {}, files from {}", port(), root);
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec))
    spdlog::warn("[http] web_root {} is not a directory: the map is not served (the API is)", root);
}

void HttpServer::accept() {
  acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
    if (stopped_ || ec == asio::error::operation_aborted) return;
    if (!accept_guard_.accepted(ec, stats_.accept_failures, [this] { accept(); })) return;
    make_room(socket);
    if (connections() >= config_.max_connections) {
      ++stats_.connections_refused;
      boost::system::error_code ignored;
      socket.close(ignored);
    } else {
      ++stats_.connections_accepted;
      auto session = std::make_shared<HttpSession>(std::move(socket), *this);
      sessions_.push_back(session);
      session->start();
    }
    accept();
  });
}

void HttpServer::make_room(const tcp::socket& newcomer) {
  const std::string address = peer_address(newcomer);
  std::vector<SlotHolder> holders;
  holders.reserve(sessions_.size());
  for (const auto& session : sessions_) holders.push_back(session->holder());
  const auto i = connection_to_evict(holders, address, config_.silent_per_address,
                                     connections() >= config_.max_connections);
  if (!i) return;
  ++stats_.connections_evicted;
  const std::shared_ptr<HttpSession> keep = sessions_[*i];
  keep->close();
  forget(keep.get());
}

std::size_t HttpServer::websocket_slots() const {
  return config_.max_connections > kStatusSlots ? config_.max_connections - kStatusSlots : 1;
}

void HttpServer::shutdown() {
  stopped_ = true;
  accept_guard_.cancel();
  boost::system::error_code ignored;
  acceptor_.close(ignored);
  for (const auto& session : std::vector(sessions_)) session->close();
  for (const auto& ws : std::vector(websockets_)) ws->close();
  sessions_.clear();
  websockets_.clear();
}

void HttpServer::set_limits(const HttpConfig& fresh) {
  config_.max_connections = fresh.max_connections;
  config_.silent_per_address = fresh.silent_per_address;
  config_.max_header_bytes = fresh.max_header_bytes;
  config_.max_body_bytes = fresh.max_body_bytes;
  config_.request_timeout_s = fresh.request_timeout_s;
  config_.write_timeout_s = fresh.write_timeout_s;
  config_.client_queue_bytes = fresh.client_queue_bytes;
  request_timeout_ = seconds(fresh.request_timeout_s);
  write_timeout_ = seconds(fresh.write_timeout_s);
}

void HttpServer::push(std::string_view object) {
  if (websockets_.empty()) return;
  if (!object.empty() && object.back() == '\n') object.remove_suffix(1);
  batch_.push_back(batch_.empty() ? '[' : ',');
  batch_.append(object);
}

void HttpServer::flush() {
  if (batch_.empty()) return;
  batch_.push_back(']');
  const Message message = std::make_shared<const std::string>(std::move(batch_));
  batch_.clear();
  for (const auto& ws : std::vector(websockets_)) ws->send(message);
}

std::size_t HttpServer::queued_bytes() const {
  std::size_t n = 0;
  for (const auto& ws : websockets_) n += ws->queued_bytes();
  return n;
}

void HttpServer::forget(const HttpSession* session) { erase_session(sessions_, session); }
void HttpServer::forget(const WebSocketSession* session) { erase_session(websockets_, session); }
void HttpServer::adopt(std::shared_ptr<WebSocketSession> session) { websockets_.push_back(std::move(session)); }

}  // namespace kew::daemon::http
