#pragma once
// One connection to a NATS server (or cluster) through the NATS C client, with its
// JetStream context (design §5.9). It connects in the background when no server answers
// yet and reconnects for ever; what happens to it is told through `on_event` (called on
// the client's own threads). kewd's NATS inputs and its publisher each own one, as does
// kew-watch --nats.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nats/nats.h>

namespace kew::nats {

/// The header of every message kewd publishes: the seq of the last alert event at that
/// point (an ALERT's own), by which `kew-watch --since` finds where to start.
inline constexpr const char* kSeqHeader = "Kew-Seq";
/// Hot standby: the fencing token of the holding that published a message (design
/// §5.9): the lease's revision when its publisher took it. A message whose token is
/// below one already read comes from an instance that no longer holds the lease.
inline constexpr const char* kLeaseHeader = "Kew-Lease";

/// A NATS C client call failed: its status text and the client's last error.
class NatsError : public std::runtime_error {
 public:
  NatsError(std::string_view what, natsStatus status);
  natsStatus status() const { return status_; }

 private:
  natsStatus status_;
};

/// Throws NatsError unless `status` is NATS_OK.
void check(natsStatus status, std::string_view what);

/// The Kew-Seq header of message `stream_seq` of JetStream stream `stream` (0 when it has
/// none). Throws NatsError when the message cannot be read.
std::uint64_t kept_seq(jsCtx* jetstream, const std::string& stream, std::uint64_t stream_seq);

/// The key-value bucket `name` on file (a server restart keeps it), keeping one value per
/// key, its values removed `ttl_s` seconds after their last write (0: never), on
/// `replicas` servers (1–5): made when missing, else bound as it is (another instance or
/// an earlier run made it) and scaled to `replicas`, `scaled` then saying what was done
/// or why it could not be (ensure_replicas, stream_setup.hpp). Null when the server
/// did not answer.
kvStore* bind_key_value(jsCtx* jetstream, const std::string& name, double ttl_s, int replicas, std::string& scaled);

/// "no such stream", "timeout", …: the text of a status and the client's last error.
std::string describe(natsStatus status);

class NatsConnection {
 public:
  using EventHandler = std::function<void(std::string_view)>;
  /// Told true when a server is reached (first or again), false when the one in use is
  /// lost; on the client's own threads.
  using LinkHandler = std::function<void(bool up)>;
  /// Connects to one of `servers` ("nats://HOST:PORT" each, the servers of one cluster;
  /// not empty) naming the connection `name` on the server. Returns at once when no
  /// server answers: the client keeps trying every `reconnect_wait_s` seconds (> 0), then
  /// and after any later loss, each listed server (and those the cluster announces) in
  /// turn. Throws NatsError for a malformed URL or a client that cannot start.
  /// `request_wait_s` (> 0): how long a JetStream call waits for the server's answer;
  /// it is also the ping interval, so that a silent server is noticed that soon.
  NatsConnection(const std::vector<std::string>& servers, const std::string& name, EventHandler on_event,
                 double reconnect_wait_s = 1.0, double request_wait_s = 5.0, LinkHandler on_link = {});
  /// Closes, and returns once the client will call nothing of this object any more.
  ~NatsConnection();
  NatsConnection(const NatsConnection&) = delete;
  NatsConnection& operator=(const NatsConnection&) = delete;

  natsConnection* get() const { return connection_; }
  jsCtx* jetstream() const { return jetstream_; }
  bool connected() const;
  /// Connections made (the first one included) and lost so far.
  std::uint64_t connects() const { return connects_.load(); }
  std::uint64_t disconnects() const { return disconnects_.load(); }
  /// The servers, comma-separated (for messages).
  const std::string& servers() const { return servers_; }

 private:
  static void on_connected(natsConnection* connection, void* self);
  static void on_disconnected(natsConnection*, void* self);
  static void on_reconnected(natsConnection* connection, void* self);
  static void on_error(natsConnection*, natsSubscription*, natsStatus, void* self);
  static void on_closed(natsConnection*, void* self);

  std::string servers_;
  EventHandler on_event_;
  LinkHandler on_link_;
  natsConnection* connection_ = nullptr;
  jsCtx* jetstream_ = nullptr;
  std::atomic<std::uint64_t> connects_{0};
  std::atomic<std::uint64_t> disconnects_{0};
  std::atomic<bool> closing_{false};  // the destructor's own disconnection is not news
  // The client calls back on its own thread, after natsConnection_Close has returned;
  // the closed callback comes last, and the destructor waits for it.
  std::mutex closed_mutex_;
  std::condition_variable closed_changed_;
  bool closed_ = false;
};

}  // namespace kew::nats
