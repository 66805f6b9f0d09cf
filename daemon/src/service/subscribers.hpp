#pragma once
// The subscriber stream of design §5.3 (gpsd-style JSON lines over TCP). Every session
// has a queue of shared, already encoded lines bounded in objects and in bytes; a session
// that falls that far behind, or whose write stalls, is sent a final ERROR object and
// closed, so a slow client never slows ingestion. A connection must complete its request
// lines in time, so silent sockets cannot hold the slots; a reserved slot beyond
// max_subscribers answers ?STATS; when every slot is taken, the connection silent longest
// gives way to a newcomer (slot_policy.hpp, design §6.6).
// Everything runs on the service's single I/O thread.

#include <chrono>
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

#include "accept_guard.hpp"
#include "slot_policy.hpp"
#include "kew/alert/alert_event.hpp"
#include "kew/daemon/config.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"

namespace kew::daemon {

using Line = std::shared_ptr<const std::string>;

class SubscriberServer;

/// The limits of the subscriber port, from [service] (deploy/kew.toml says why each).
struct SubscriberLimits {
  std::size_t max_subscribers = 32;
  std::size_t queue_objects = 262144;
  std::size_t queue_bytes = 64u << 20;
  std::chrono::steady_clock::duration request_timeout = std::chrono::seconds(10);
  std::chrono::steady_clock::duration idle_timeout = std::chrono::seconds(60);
  std::chrono::steady_clock::duration write_timeout = std::chrono::seconds(30);
  std::size_t silent_per_address = 4;
};
SubscriberLimits subscriber_limits(const ServiceConfig& service);

class SubscriberSession : public std::enable_shared_from_this<SubscriberSession> {
 public:
  /// `admin`: in the reserved slot, where only ?STATS is served.
  SubscriberSession(boost::asio::ip::tcp::socket socket, SubscriberServer& server, bool admin);
  void start();
  /// Queues a line; false when the queue was full (the session is then being closed).
  bool enqueue(Line line);
  /// Sends an ERROR object and closes after it is written (or after `grace`).
  void close_with_error(std::string_view message, std::chrono::steady_clock::duration grace = kCloseGrace);
  /// How long a closing client has to take its ERROR.
  static constexpr std::chrono::seconds kCloseGrace{5};
  /// Writes what is queued, then closes (service shutdown).
  void drain_and_close();
  /// Closes a silent connection to make room for a newcomer (with an ERROR saying so).
  void evict();

  /// Being closed: it holds no slot any more.
  bool closing() const { return closing_; }
  /// What the slot policy needs to know of it.
  SlotHolder holder() const { return {address_, !watching(), silent_since_}; }

  bool watching() const { return watching_ && !closing_; }
  const protocol::WatchRequest& watch() const { return watch_; }
  /// Whether an ALERT for `event` passes this session's filter; remembers sent ids so
  /// that the End of an alert the client saw is always sent.
  bool wants(const AlertEvent& event);
  /// Queues an ALERTS object of the alerts of `active` that pass this session's filter,
  /// `seq` the stream's sequence number it carries; its ids are then the alerts sent.
  void send_snapshot(std::span<const AlertEvent> active, std::uint64_t seq);
  std::uint64_t id() const { return id_; }
  bool admin() const { return admin_; }
  std::size_t queued_bytes() const { return queued_bytes_; }

 private:
  void read_request();
  void handle_request(std::string_view line);
  /// Arms the request deadline: a connection not watching must complete a request line
  /// within request_timeout of connecting (idle_timeout after a request it was answered).
  void arm_request_deadline();
  void write_next();
  void cut_off(std::string_view why, std::string_view message);
  void close();

  boost::asio::ip::tcp::socket socket_;
  SubscriberServer& server_;
  boost::asio::streambuf input_;
  boost::asio::steady_timer grace_;
  boost::asio::steady_timer request_deadline_;
  boost::asio::steady_timer write_deadline_;
  std::deque<Line> queue_;               // front in_flight_ lines are being written
  std::size_t in_flight_ = 0;
  std::size_t queued_bytes_ = 0;         // of every line in queue_, in flight included
  std::vector<boost::asio::const_buffer> gather_;
  bool writing_ = false;
  bool reading_paused_ = false;          // requests wait while the answers are unread
  bool answered_ = false;                // a complete request line was handled
  bool admin_;
  bool closing_ = false;
  bool closed_ = false;
  bool watching_ = false;
  protocol::WatchRequest watch_;
  std::set<std::string> alerts_sent_;
  std::uint64_t id_;
  std::string address_;  ///< the peer's IP address
  std::chrono::steady_clock::time_point silent_since_;  ///< connected, or last complete request line
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

  /// Connections beyond max_subscribers that may still ask ?STATS (and nothing else).
  static constexpr std::size_t kAdminSlots = 2;

  SubscriberServer(boost::asio::io_context& io, const boost::asio::ip::tcp::endpoint& endpoint,
                   const SubscriberLimits& limits, bool tracks_allowed, Source source);
  void start();
  /// Stops accepting; every session writes what it has queued and closes.
  void shutdown();

  /// An alert event's ALERT line (encoded once by the caller) to the sessions that want
  /// that alert.
  void broadcast_alert(const AlertEvent& event, const Line& line);
  /// An ALERTS snapshot of `active` (as of `seq`) to every watching session, each through
  /// its filter: a takeover by a hot standby, whose sessions were sent no alert event.
  void send_snapshot_to_watchers(std::span<const AlertEvent> active, std::uint64_t seq);
  /// An ALIVE or ACK line to every watching session.
  void broadcast_to_watchers(const Line& line);
  /// Sends a TRACK object to the sessions that asked for tracks.
  void broadcast_track(const TrackReport& report);
  bool anyone_wants_tracks() const;

  void set_limits(const SubscriberLimits& limits) { limits_ = limits; }
  const SubscriberLimits& limits() const { return limits_; }
  bool tracks_allowed() const { return tracks_allowed_; }
  std::size_t sessions() const { return sessions_.size(); }
  /// Bytes queued for every session together.
  std::size_t queued_bytes() const;
  const protocol::SubscriberStatistics& figures() const { return figures_; }
  protocol::SubscriberStatistics& figures() { return figures_; }
  std::uint16_t port() const { return acceptor_.local_endpoint().port(); }
  const Source& source() const { return source_; }

  void forget(const std::shared_ptr<SubscriberSession>& session);
  /// Called once the last subscriber has gone after shutdown().
  void on_empty(std::function<void()> callback) { on_empty_ = std::move(callback); }

 private:
  void accept();
  /// Before `newcomer` takes a slot: closes the connection the slot policy names, if any.
  void make_room(const boost::asio::ip::tcp::socket& newcomer);
  /// After a session with a large backlog closed: hands freed memory back to the system.
  void release_memory(std::size_t backlog_bytes);

  boost::asio::ip::tcp::acceptor acceptor_;
  AcceptGuard accept_guard_;
  SubscriberLimits limits_;
  bool tracks_allowed_;
  Source source_;
  std::vector<std::shared_ptr<SubscriberSession>> sessions_;
  protocol::SubscriberStatistics figures_;
  /// Refusals, time-outs and cut-offs go to the log through this, rate-limited per kind
  /// (its counts are not reported: figures_ has them).
  Rejections log_;
  std::uint64_t next_id_ = 1;
  bool stopped_ = false;
  std::function<void()> on_empty_;
  friend class SubscriberSession;
};

}  // namespace kew::daemon
