#include "subscribers.hpp"

#include <algorithm>
#include <chrono>

#include <boost/asio/read_until.hpp>
#include <boost/asio/write.hpp>
#include <spdlog/spdlog.h>

namespace kew::daemon {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {
constexpr auto kCloseGrace = std::chrono::seconds(5);  // a stuck client gets this long for its ERROR
constexpr std::size_t kMaxLinesPerWrite = 512;          // iovecs per gathered write (IOV_MAX is 1024)
}

SubscriberSession::SubscriberSession(tcp::socket socket, SubscriberServer& server)
    : socket_(std::move(socket)),
      server_(server),
      input_(protocol::kMaxWatchRequestBytes),
      grace_(socket_.get_executor()),
      id_(server.next_id_++) {}

void SubscriberSession::start() {
  std::string version;
  protocol::append_version_json(version, server_.source().seq());
  enqueue(std::make_shared<const std::string>(std::move(version)));
  if (server_.source().start) {
    std::string start = server_.source().start();
    if (!start.empty()) enqueue(std::make_shared<const std::string>(std::move(start)));
  }
  read_request();
}

bool SubscriberSession::enqueue(Line line) {
  if (closing_) return false;
  if (queue_.size() - in_flight_ >= server_.queue_limit()) {
    ++server_.figures_.cut_off;
    spdlog::warn("subscriber {} fell {} objects behind; disconnecting it", id_, queue_.size());
    close_with_error("too slow: the subscriber queue overflowed");
    return false;
  }
  queue_.push_back(std::move(line));
  if (!writing_) write_next();
  return true;
}

void SubscriberSession::close_with_error(std::string_view message) {
  if (closing_) return;
  // What the client has not yet read is dropped; the ERROR goes right after the line
  // being written, if any.
  queue_.erase(queue_.begin() + static_cast<std::ptrdiff_t>(in_flight_), queue_.end());
  std::string error;
  protocol::append_error_json(error, message, server_.source().seq());
  queue_.push_back(std::make_shared<const std::string>(std::move(error)));
  closing_ = true;
  grace_.expires_after(kCloseGrace);
  grace_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (!ec) self->close();
  });
  if (!writing_) write_next();
}

void SubscriberSession::drain_and_close() {
  if (closing_) return;
  closing_ = true;
  grace_.expires_after(kCloseGrace);
  grace_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (!ec) self->close();
  });
  if (!writing_) write_next();
}

bool SubscriberSession::wants(const AlertEvent& event) {
  if (!watching()) return false;
  const bool seen = alerts_sent_.count(event.id) > 0;
  if (event.state == AlertState::End) {
    if (seen) alerts_sent_.erase(event.id);
    return seen;
  }
  if (seen) return true;
  if (event.severity < watch_.min_severity) return false;
  alerts_sent_.insert(event.id);
  return true;
}

void SubscriberSession::read_request() {
  asio::async_read_until(socket_, input_, '\n',
                         [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
                           if (self->closed_) return;
                           if (ec == asio::error::not_found) {
                             ++self->server_.figures_.bad_requests;
                             self->close_with_error("request line too long");
                             return;
                           }
                           if (ec) {
                             if (!self->closing_) self->close();
                             return;
                           }
                           std::string line(asio::buffers_begin(self->input_.data()),
                                            asio::buffers_begin(self->input_.data()) + static_cast<std::ptrdiff_t>(n));
                           self->input_.consume(n);
                           self->handle_request(line);
                           if (!self->closing_) self->read_request();
                         });
}

void SubscriberSession::handle_request(std::string_view line) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.remove_suffix(1);
  if (line.empty()) return;
  if (line == "?STATS" || line == "?STATS;") {
    enqueue(std::make_shared<const std::string>(server_.source().stats()));
    return;
  }
  const protocol::WatchParseResult parsed = protocol::parse_watch_request(line);
  if (!parsed.ok) {
    ++server_.figures_.bad_requests;
    std::string error;
    protocol::append_error_json(error, parsed.error, server_.source().seq());
    enqueue(std::make_shared<const std::string>(std::move(error)));
    return;
  }
  watch_ = parsed.request;
  if (watch_.tracks && !server_.tracks_allowed()) watch_.tracks = false;
  watching_ = watch_.enable;
  alerts_sent_.clear();
  if (!watching_) return;
  spdlog::info("subscriber {} watching alerts from {}{}", id_, to_string(watch_.min_severity),
               watch_.tracks ? ", with tracks" : "");
  // The snapshot restores a reconnecting client's view: every active alert that passes
  // its filter, and these ids count as sent.
  std::vector<AlertEvent> active = server_.source().snapshot();
  std::vector<const AlertEvent*> shown;
  for (const AlertEvent& e : active) {
    if (e.severity < watch_.min_severity) continue;
    alerts_sent_.insert(e.id);
    shown.push_back(&e);
  }
  std::string snapshot;
  protocol::append_alerts_snapshot_json(snapshot, shown, server_.source().seq());
  enqueue(std::make_shared<const std::string>(std::move(snapshot)));
}

void SubscriberSession::write_next() {
  if (closed_) return;
  if (queue_.empty()) {
    writing_ = false;
    if (closing_) close();
    return;
  }
  writing_ = true;
  // Everything queued goes in one gathered write: the pipeline may queue hundreds of
  // lines per input read, and a write per line would let the queue grow without bound.
  in_flight_ = std::min(queue_.size(), kMaxLinesPerWrite);
  gather_.clear();
  for (std::size_t i = 0; i < in_flight_; ++i) gather_.push_back(asio::buffer(*queue_[i]));
  asio::async_write(socket_, gather_,
                    [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                      if (self->closed_) return;
                      if (ec) {
                        self->close();
                        return;
                      }
                      self->queue_.erase(self->queue_.begin(),
                                         self->queue_.begin() + static_cast<std::ptrdiff_t>(self->in_flight_));
                      self->in_flight_ = 0;
                      self->write_next();
                    });
}

void SubscriberSession::close() {
  if (closed_) return;
  closed_ = true;
  closing_ = true;
  queue_.clear();
  boost::system::error_code ignored;
  grace_.cancel();
  socket_.shutdown(tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  server_.forget(shared_from_this());
}

SubscriberServer::SubscriberServer(asio::io_context& io, const tcp::endpoint& endpoint, std::size_t max_subscribers,
                                   std::size_t queue_limit, bool tracks_allowed, Source source)
    : acceptor_(io, endpoint),
      max_subscribers_(max_subscribers),
      queue_limit_(queue_limit),
      tracks_allowed_(tracks_allowed),
      source_(std::move(source)) {}

void SubscriberServer::start() { accept(); }

void SubscriberServer::accept() {
  acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
    if (stopped_) return;
    if (!ec) {
      // Alerts are small lines that must leave at once: no Nagle delay.
      boost::system::error_code ignored;
      socket.set_option(tcp::no_delay(true), ignored);
      auto session = std::make_shared<SubscriberSession>(std::move(socket), *this);
      if (sessions_.size() >= max_subscribers_) {
        ++figures_.refused;
        sessions_.push_back(session);
        session->close_with_error("too many subscribers");
      } else {
        ++figures_.accepted;
        sessions_.push_back(session);
        session->start();
        spdlog::debug("subscriber {} connected ({} now)", session->id(), sessions_.size());
      }
    }
    accept();
  });
}

void SubscriberServer::shutdown() {
  stopped_ = true;
  boost::system::error_code ignored;
  acceptor_.close(ignored);
  const auto sessions = sessions_;  // sessions remove themselves as they close
  for (const auto& s : sessions) s->drain_and_close();
}

void SubscriberServer::forget(const std::shared_ptr<SubscriberSession>& session) {
  sessions_.erase(std::remove(sessions_.begin(), sessions_.end(), session), sessions_.end());
  if (stopped_ && sessions_.empty() && on_empty_) on_empty_();
}

void SubscriberServer::broadcast_alert(const AlertEvent& event) {
  Line line;
  // enqueue() never closes a session synchronously, so sessions_ is stable here.
  for (const auto& s : sessions_) {
    if (!s->wants(event)) continue;
    if (!line) {
      std::string text;
      protocol::append_alert_json(text, event, event.seq);
      line = std::make_shared<const std::string>(std::move(text));
    }
    s->enqueue(line);
  }
}

void SubscriberServer::broadcast_alive(const protocol::AliveStatus& status) {
  Line line;
  // enqueue() never closes a session synchronously, so sessions_ is stable here.
  for (const auto& s : sessions_) {
    if (!s->watching()) continue;
    if (!line) {
      std::string text;
      protocol::append_alive_json(text, status, source_.seq());
      line = std::make_shared<const std::string>(std::move(text));
    }
    s->enqueue(line);
  }
}

void SubscriberServer::broadcast_ack(const protocol::Acknowledgement& ack) {
  Line line;
  for (const auto& s : sessions_) {
    if (!s->watching()) continue;
    if (!line) {
      std::string text;
      protocol::append_ack_json(text, ack, source_.seq());
      line = std::make_shared<const std::string>(std::move(text));
    }
    s->enqueue(line);
  }
}

bool SubscriberServer::anyone_wants_tracks() const {
  return std::any_of(sessions_.begin(), sessions_.end(),
                     [](const auto& s) { return s->watching() && s->watch().tracks; });
}

void SubscriberServer::broadcast_track(const TrackReport& report) {
  Line line;
  // enqueue() never closes a session synchronously, so sessions_ is stable here.
  for (const auto& s : sessions_) {
    if (!s->watching() || !s->watch().tracks) continue;
    if (!line) {
      std::string text;
      protocol::append_track_json(text, report, source_.seq());
      line = std::make_shared<const std::string>(std::move(text));
    }
    s->enqueue(line);
  }
}

void SubscriberServer::set_limits(std::size_t max_subscribers, std::size_t queue_limit) {
  max_subscribers_ = max_subscribers;
  queue_limit_ = queue_limit;
}

}  // namespace kew::daemon
