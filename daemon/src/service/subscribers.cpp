#include "subscribers.hpp"

#include <malloc.h>

#include <algorithm>
#include <chrono>

#include <boost/asio/read_until.hpp>
#include <boost/asio/write.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "peer_address.hpp"

namespace kew::daemon {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {
// A silent connection closed for a newcomer gets this long for its ERROR: a client that
// floods connections and reads nothing must not pile up closing sockets.
constexpr auto kEvictionGrace = std::chrono::seconds(1);
constexpr std::size_t kMaxLinesPerWrite = 512;          // iovecs per gathered write (IOV_MAX is 1024)
// Requests are read only while less than this is waiting to be written: a client that
// repeats ?WATCH without reading gets no second snapshot queued behind the first.
constexpr std::size_t kPauseRequestsBytes = 64 * 1024;
// A session that held this much when it closed makes the server return freed memory.
constexpr std::size_t kTrimAfterBytes = 1 << 20;

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}
}  // namespace

SubscriberLimits subscriber_limits(const ServiceConfig& service) {
  SubscriberLimits l;
  l.max_subscribers = service.max_subscribers;
  l.queue_objects = service.subscriber_queue;
  l.queue_bytes = service.subscriber_queue_bytes;
  l.request_timeout = seconds(service.request_timeout_s);
  l.idle_timeout = seconds(service.idle_timeout_s);
  l.write_timeout = seconds(service.write_timeout_s);
  l.silent_per_address = service.silent_per_address;
  return l;
}

SubscriberSession::SubscriberSession(tcp::socket socket, SubscriberServer& server, bool admin)
    : socket_(std::move(socket)),
      server_(server),
      input_(protocol::kMaxWatchRequestBytes),
      grace_(socket_.get_executor()),
      request_deadline_(socket_.get_executor()),
      write_deadline_(socket_.get_executor()),
      admin_(admin),
      id_(server.next_id_++),
      address_(peer_address(socket_)),
      silent_since_(std::chrono::steady_clock::now()) {}

void SubscriberSession::start() {
  std::string version;
  protocol::append_version_json(version, server_.source().seq());
  enqueue(std::make_shared<const std::string>(std::move(version)));
  if (server_.source().start) {
    std::string start = server_.source().start();
    if (!start.empty()) enqueue(std::make_shared<const std::string>(std::move(start)));
  }
  arm_request_deadline();
  read_request();
}

void SubscriberSession::arm_request_deadline() {
  // A watching session is fed, and judged by how it reads (byte budget, write timeout);
  // the others must keep asking. The reserved slot is for a quick ?STATS only.
  if (watching_ && !admin_) {
    request_deadline_.cancel();
    return;
  }
  const SubscriberLimits& limits = server_.limits();
  const bool first = !answered_;
  request_deadline_.expires_after(first || admin_ ? limits.request_timeout : limits.idle_timeout);
  request_deadline_.async_wait([self = shared_from_this(), first](const boost::system::error_code& ec) {
    if (ec || self->closing_) return;
    ++self->server_.figures_.timed_out;
    self->server_.log_.reject("timed_out", fmt::format("subscriber {}: {}; disconnecting it", self->id_,
                                                       first ? "no complete request line in time" : "idle, not watching"));
    self->close_with_error(first ? "request timeout" : "idle timeout");
  });
}

bool SubscriberSession::enqueue(Line line) {
  if (closing_) return false;
  const SubscriberLimits& limits = server_.limits();
  if (queue_.size() - in_flight_ >= limits.queue_objects) {
    cut_off(fmt::format("fell {} objects behind", queue_.size()), "too slow: the subscriber queue overflowed");
    return false;
  }
  if (queued_bytes_ + line->size() > limits.queue_bytes) {
    cut_off(fmt::format("fell {} bytes behind", queued_bytes_ + line->size()),
            "too slow: the subscriber's byte budget overflowed");
    return false;
  }
  queued_bytes_ += line->size();
  auto& peak = server_.figures_.backlog_bytes_max;
  peak = std::max<std::uint64_t>(peak, queued_bytes_);
  queue_.push_back(std::move(line));
  if (!writing_) write_next();
  return true;
}

void SubscriberSession::cut_off(std::string_view why, std::string_view message) {
  ++server_.figures_.cut_off;
  server_.log_.reject("cut_off", fmt::format("subscriber {} {}; disconnecting it", id_, why));
  close_with_error(message);
}

void SubscriberSession::close_with_error(std::string_view message, std::chrono::steady_clock::duration grace) {
  if (closing_) return;
  // What the client has not yet read is dropped; the ERROR goes right after the line
  // being written, if any.
  queue_.erase(queue_.begin() + static_cast<std::ptrdiff_t>(in_flight_), queue_.end());
  queued_bytes_ = 0;
  for (const Line& l : queue_) queued_bytes_ += l->size();
  request_deadline_.cancel();
  std::string error;
  protocol::append_error_json(error, message, server_.source().seq());
  queue_.push_back(std::make_shared<const std::string>(std::move(error)));
  closing_ = true;
  grace_.expires_after(grace);
  grace_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (!ec) self->close();
  });
  if (!writing_) write_next();
}

void SubscriberSession::evict() {
  ++server_.figures_.evicted;
  server_.log_.reject("evicted", fmt::format("subscriber {} ({}): silent while every slot was taken or its address "
                                             "held {} silent connections; disconnecting it for a newcomer",
                                             id_, address_, server_.limits().silent_per_address));
  close_with_error("evicted: silent while another connection needed the slot", kEvictionGrace);
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
                           self->silent_since_ = std::chrono::steady_clock::now();
                           self->handle_request(line);
                           if (self->closing_) return;
                           self->answered_ = true;
                           self->arm_request_deadline();
                           if (self->queued_bytes_ >= kPauseRequestsBytes) {
                             self->reading_paused_ = true;  // resumed by write_next()
                             return;
                           }
                           self->read_request();
                         });
}

void SubscriberSession::handle_request(std::string_view line) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.remove_suffix(1);
  if (line.empty()) return;
  if (line == "?STATS" || line == "?STATS;") {
    enqueue(std::make_shared<const std::string>(server_.source().stats()));
    return;
  }
  if (admin_) {
    ++server_.figures_.refused;
    server_.log_.reject("refused", fmt::format("subscriber {}: ?WATCH refused (max_subscribers = {}; only ?STATS "
                                               "is served beyond it)", id_, server_.limits().max_subscribers));
    close_with_error("too many subscribers");
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
  send_snapshot(server_.source().snapshot(), server_.source().seq());
}

void SubscriberSession::send_snapshot(std::span<const AlertEvent> active, std::uint64_t seq) {
  // The snapshot restores a client's view: every active alert that passes its filter,
  // and exactly these ids count as sent.
  alerts_sent_.clear();
  std::vector<const AlertEvent*> shown;
  for (const AlertEvent& e : active) {
    if (e.severity < watch_.min_severity) continue;
    alerts_sent_.insert(e.id);
    shown.push_back(&e);
  }
  std::string snapshot;
  protocol::append_alerts_snapshot_json(snapshot, shown, seq);
  enqueue(std::make_shared<const std::string>(std::move(snapshot)));
}

void SubscriberSession::write_next() {
  if (closed_) return;
  if (reading_paused_ && queued_bytes_ < kPauseRequestsBytes && !closing_) {
    reading_paused_ = false;
    read_request();
  }
  if (queue_.empty()) {
    writing_ = false;
    write_deadline_.cancel();
    if (closing_) close();
    return;
  }
  writing_ = true;
  // Everything queued goes in one gathered write: the pipeline may queue hundreds of
  // lines per input read, and a write per line would let the queue grow without bound.
  in_flight_ = std::min(queue_.size(), kMaxLinesPerWrite);
  gather_.clear();
  for (std::size_t i = 0; i < in_flight_; ++i) gather_.push_back(asio::buffer(*queue_[i]));
  // A write that does not finish in time means the client stopped reading (its kernel
  // buffers are full): it would hold its slot for as long as its byte budget lasts.
  if (!closing_) {
    write_deadline_.expires_after(server_.limits().write_timeout);
    write_deadline_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
      if (ec || self->closing_) return;
      self->cut_off("stopped reading (a write stalled)", "too slow: a write stalled");
    });
  }
  asio::async_write(socket_, gather_,
                    [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                      if (self->closed_) return;
                      if (ec) {
                        self->close();
                        return;
                      }
                      for (std::size_t i = 0; i < self->in_flight_; ++i) self->queued_bytes_ -= self->queue_[i]->size();
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
  const std::size_t backlog = queued_bytes_;
  queue_.clear();
  queue_.shrink_to_fit();
  queued_bytes_ = 0;
  boost::system::error_code ignored;
  grace_.cancel();
  request_deadline_.cancel();
  write_deadline_.cancel();
  socket_.shutdown(tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  server_.forget(shared_from_this());
  server_.release_memory(backlog);
}

SubscriberServer::SubscriberServer(asio::io_context& io, const tcp::endpoint& endpoint,
                                   const SubscriberLimits& limits, bool tracks_allowed, Source source)
    : acceptor_(io, endpoint),
      accept_guard_(acceptor_.get_executor(), "subscribers"),
      limits_(limits),
      tracks_allowed_(tracks_allowed),
      source_(std::move(source)) {
  log_.set_reporter([](std::string_view, std::string_view message) { spdlog::warn("{}", message); });
}

void SubscriberServer::release_memory(std::size_t backlog_bytes) {
  // Large snapshots and long queues leave freed heap that glibc keeps by default; a
  // client that was cut off must not leave the daemon's resident size grown for good.
  if (backlog_bytes >= kTrimAfterBytes) malloc_trim(0);
}

void SubscriberServer::start() { accept(); }

void SubscriberServer::accept() {
  acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
    if (stopped_ || ec == asio::error::operation_aborted) return;
    if (!accept_guard_.accepted(ec, figures_.accept_failures, [this] {
          if (!stopped_) accept();
        }))
      return;
    // Alerts are small lines that must leave at once: no Nagle delay.
    boost::system::error_code ignored;
    socket.set_option(tcp::no_delay(true), ignored);
    make_room(socket);
    std::size_t admins = 0, subscribers = 0;
    for (const auto& s : sessions_)
      if (!s->closing()) ++(s->admin() ? admins : subscribers);
    const bool admin = subscribers >= limits_.max_subscribers;
    auto session = std::make_shared<SubscriberSession>(std::move(socket), *this, admin);
    sessions_.push_back(session);
    if (admin && admins >= kAdminSlots) {
      ++figures_.refused;
      log_.reject("refused", fmt::format("subscriber {}: refused (max_subscribers = {} and the reserved slots are "
                                         "taken)", session->id(), limits_.max_subscribers));
      session->close_with_error("too many subscribers");
    } else {
      ++(admin ? figures_.admin : figures_.accepted);
      session->start();
      spdlog::debug("subscriber {} connected ({} now{})", session->id(), sessions_.size(),
                    admin ? ", reserved slot: ?STATS only" : "");
    }
    accept();
  });
}

void SubscriberServer::make_room(const tcp::socket& newcomer) {
  const std::string address = peer_address(newcomer);
  std::vector<SlotHolder> holders;
  std::vector<SubscriberSession*> open;
  for (const auto& s : sessions_) {
    if (s->closing()) continue;
    holders.push_back(s->holder());
    open.push_back(s.get());
  }
  const bool every_slot_taken = open.size() >= limits_.max_subscribers + kAdminSlots;
  if (const auto i = connection_to_evict(holders, address, limits_.silent_per_address, every_slot_taken))
    open[*i]->evict();
}

void SubscriberServer::shutdown() {
  stopped_ = true;
  boost::system::error_code ignored;
  acceptor_.close(ignored);
  accept_guard_.cancel();
  const auto sessions = sessions_;  // sessions remove themselves as they close
  for (const auto& s : sessions) s->drain_and_close();
}

void SubscriberServer::forget(const std::shared_ptr<SubscriberSession>& session) {
  sessions_.erase(std::remove(sessions_.begin(), sessions_.end(), session), sessions_.end());
  if (stopped_ && sessions_.empty() && on_empty_) on_empty_();
}

void SubscriberServer::broadcast_alert(const AlertEvent& event, const Line& line) {
  // enqueue() never closes a session synchronously, so sessions_ is stable here.
  for (const auto& s : sessions_)
    if (s->wants(event)) s->enqueue(line);
}

void SubscriberServer::send_snapshot_to_watchers(std::span<const AlertEvent> active, std::uint64_t seq) {
  // enqueue() never closes a session synchronously, so sessions_ is stable here.
  for (const auto& s : sessions_)
    if (s->watching()) s->send_snapshot(active, seq);
}

void SubscriberServer::broadcast_to_watchers(const Line& line) {
  for (const auto& s : sessions_)
    if (s->watching()) s->enqueue(line);
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

std::size_t SubscriberServer::queued_bytes() const {
  std::size_t n = 0;
  for (const auto& session : sessions_) n += session->queued_bytes();
  return n;
}

}  // namespace kew::daemon
