#pragma once
// The subscriber stream of design §5.3 (gpsd-style JSON lines over TCP). Every session
// has a bounded queue of shared, already encoded lines; a session whose queue overflows
// is sent a final ERROR object and closed, so a slow client never slows ingestion.
// Everything runs on the service's single I/O thread.

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <vector>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/streambuf.hpp>

#include "kew/alert/alert_event.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"

namespace kew::daemon {

using Line = std::shared_ptr<const std::string>;

class SubscriberServer;

class SubscriberSession : public std::enable_shared_from_this<SubscriberSession> {
 public:
  SubscriberSession(boost::asio::ip::tcp::socket socket, SubscriberServer& server);
  void start();
  /// Queues a line; false when the queue was full (the session is then being closed).
  bool enqueue(Line line);
  /// Sends an ERROR object and closes after it is written (or after a grace period).
  void close_with_error(std::string_view message);
  /// Writes what is queued, then closes (service shutdown).
  void drain_and_close();

  bool watching() const { return watching_ && !closing_; }
  const protocol::WatchRequest& watch() const { return watch_; }
  /// Whether an ALERT for `event` passes this session's filter; remembers sent ids so
  /// that the End of an alert the client saw is always sent.
  bool wants(const AlertEvent& event);
  std::uint64_t id() const { return id_; }

 private:
  void read_request();
  void handle_request(std::string_view line);
  void write_next();
  void close();

  boost::asio::ip::tcp::socket socket_;
  SubscriberServer& server_;
  boost::asio::streambuf input_;
  boost::asio::steady_timer grace_;
  std::deque<Line> queue_;               // front in_flight_ lines are being written
  std::size_t in_flight_ = 0;
  std::vector<boost::asio::const_buffer> gather_;
  bool writing_ = false;
  bool closing_ = false;
  bool closed_ = false;
  bool watching_ = false;
  protocol::WatchRequest watch_;
  std::set<std::string> alerts_sent_;
  std::uint64_t id_;
};

class SubscriberServer {
 public:
  /// What the server asks of the service: the snapshot of active alerts and the stream's
  /// current sequence number (the last alert's).
  struct Source {
    std::function<std::vector<AlertEvent>()> snapshot;
    std::function<std::uint64_t()> seq;
    /// One STATS line (answer to "?STATS"), newline included.
    std::function<std::string()> stats;
    /// The START line of this run, sent right after VERSION (design §5.3); "" none.
    std::function<std::string()> start;
  };

  SubscriberServer(boost::asio::io_context& io, const boost::asio::ip::tcp::endpoint& endpoint,
                   std::size_t max_subscribers, std::size_t queue_limit, bool tracks_allowed, Source source);
  void start();
  /// Stops accepting; every session writes what it has queued and closes.
  void shutdown();

  void broadcast_alert(const AlertEvent& event);
  void broadcast_alive(const protocol::AliveStatus& status);
  /// Sends an ACK object (operator acknowledgement) to every watching session.
  void broadcast_ack(const protocol::Acknowledgement& ack);
  /// Sends a TRACK object to the sessions that asked for tracks.
  void broadcast_track(const TrackReport& report);
  bool anyone_wants_tracks() const;

  void set_limits(std::size_t max_subscribers, std::size_t queue_limit);
  std::size_t queue_limit() const { return queue_limit_; }
  bool tracks_allowed() const { return tracks_allowed_; }
  std::size_t sessions() const { return sessions_.size(); }
  const protocol::SubscriberStatistics& figures() const { return figures_; }
  protocol::SubscriberStatistics& figures() { return figures_; }
  std::uint16_t port() const { return acceptor_.local_endpoint().port(); }
  const Source& source() const { return source_; }

  void forget(const std::shared_ptr<SubscriberSession>& session);
  /// Called once the last session has closed after shutdown().
  void on_empty(std::function<void()> callback) { on_empty_ = std::move(callback); }

 private:
  void accept();

  boost::asio::ip::tcp::acceptor acceptor_;
  std::size_t max_subscribers_;
  std::size_t queue_limit_;
  bool tracks_allowed_;
  Source source_;
  std::vector<std::shared_ptr<SubscriberSession>> sessions_;
  protocol::SubscriberStatistics figures_;
  std::uint64_t next_id_ = 1;
  bool stopped_ = false;
  std::function<void()> on_empty_;
  friend class SubscriberSession;
};

}  // namespace kew::daemon
