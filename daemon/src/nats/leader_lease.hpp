#pragma once
// Hot standby (design §5.9): kewd instances fed the same records elect one active through
// a lease in a JetStream key-value bucket. The active holds the key `lease_key` and
// renews it every quarter of `lease_ttl_s`; the bucket's TTL removes a key not renewed
// for lease_ttl_s, and a standby that tries every quarter of it then creates the key and
// becomes active: a dead active is replaced within 1.25 × lease_ttl_s. An active that
// cannot renew for three quarters of lease_ttl_s (its server gone, another holding the
// key) steps down before anyone else can take over, so two never speak at once. A clean stop deletes the
// key: the standby takes over at its next try. Only an instance in step with the pair
// tries at once; one out of step waits until the key has stayed free for a whole TTL.
//
// Losing every server is not losing the lease: the key lives on the servers, and nobody
// can take it while none answers. An active whose servers all go away while its last
// renewal vouches for it stays active for the outputs that do not need NATS
// (SpeakingRight::bus_away) and, as soon as a server answers, renews its key, or takes
// it again when it expired meanwhile, or steps down when another instance holds it.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "kew/daemon/config.hpp"
#include "nats_connection.hpp"
#include "speaking_right.hpp"

namespace kew::daemon {

class LeaderLease {
 public:
  /// Where a standby stands with the pair (design §5.9).
  enum class Readiness : std::uint8_t {
    NotReady,  ///< the pair's origin is not known yet: never takes the lease
    Unsynced,  ///< out of step: takes a free lease only when nobody has taken it for a
               ///< whole TTL since it was first seen free (no instance in step is left)
    InStep,    ///< takes a free lease at once
  };
  /// Called on the lease's thread. `on_acquired(last_seq)`: this instance is active now;
  /// `last_seq` is the Kew-Seq of the last message in [nats] stream (0: none, or no
  /// stream), what the previous active published last. `on_lost()`: it is not any more.
  struct Handlers {
    std::function<void(std::uint64_t last_seq)> on_acquired;
    std::function<void()> on_lost;
    /// Whether this instance may take a free lease (HotStandby); unset: InStep.
    std::function<Readiness()> readiness;
  };

  /// Starts trying at once; keeps `right` current (the revision held, the time the last
  /// renewal vouches for). Throws nats::NatsError for a malformed url.
  LeaderLease(const NatsConfig& config, std::string instance, Handlers handlers, std::shared_ptr<SpeakingRight> right);
  /// Stops, and gives the lease up when held.
  ~LeaderLease();
  LeaderLease(const LeaderLease&) = delete;
  LeaderLease& operator=(const LeaderLease&) = delete;

  bool active() const { return active_.load(); }
  const std::string& instance() const { return instance_; }

 private:
  void run();
  bool bind_bucket();
  /// The Kew-Seq of the stream's last message (0 for an empty stream or none); empty
  /// when the server did not answer: the floor of a takeover must be known.
  std::optional<std::uint64_t> last_published_seq();
  /// A call failed because the bucket is gone (a server restarted without it): bind
  /// again at the next try.
  void forget_bucket_if_gone(natsStatus status);
  /// Out of step: whether the lease has been free for a whole TTL (checked each period).
  bool free_for_a_ttl();
  /// The connection's news: a lost bus (SpeakingRight::bus_lost), or a server answering
  /// again (the lease thread wakes to renew at once). On the client's threads.
  void on_link(bool up);
  /// After the bus came back without the key: creates it again (`taken` its revision),
  /// or finds another instance holding it, or no server answering yet.
  enum class Retake : std::uint8_t { Taken, Another, NoAnswer };
  /// `sent`: when the create was sent, from which the new key's TTL counts.
  Retake take_again(std::uint64_t& taken, std::chrono::steady_clock::time_point& sent);
  /// Connected, and the loss of the last connection told (on_link): a call made
  /// otherwise would wait in the client's reconnect buffer and reach the server at the
  /// reconnection, long after this thread stopped waiting for its answer (a create that
  /// takes the key for an instance that believes it failed).
  bool link_up();
  /// A standby whose bus came back lets the key alone for a TTL: an active whose bus went
  /// away with it takes its expired key again first (design §5.9).
  bool yielding_to_a_returning_active();
  /// Waits `period`, or until stopping (true) or a server answers again.
  bool wait(std::chrono::steady_clock::duration period);

  NatsConfig config_;
  std::string instance_;
  Handlers handlers_;
  std::shared_ptr<SpeakingRight> right_;
  nats::NatsConnection connection_;
  kvStore* bucket_ = nullptr;  // lease thread
  std::atomic<bool> active_{false};
  std::chrono::steady_clock::time_point renewed_{};  // lease thread: send time of the last renewal taken
  std::optional<std::chrono::steady_clock::time_point> free_since_;  // lease thread: first seen free
  std::mutex mutex_;
  std::condition_variable stop_;
  bool stopping_ = false;  // guarded by mutex_
  bool bus_back_ = false;  // guarded by mutex_: a server answers again, renew at once
  bool link_lost_ = false;  // guarded by mutex_: every server lost since the last answer
  std::optional<std::chrono::steady_clock::time_point> link_back_at_;  // guarded by mutex_: the last reconnection
  std::thread thread_;
};

}  // namespace kew::daemon
