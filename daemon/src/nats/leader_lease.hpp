#pragma once
// Hot standby (design §5.9): kewd instances fed the same records elect one active through
// a lease in a JetStream key-value bucket. The active holds the key `lease_key` and
// renews it every quarter of `lease_ttl_s`; the bucket's TTL removes a key not renewed
// for lease_ttl_s, and a standby that tries every quarter of it then creates the key and
// becomes active: a dead active is replaced within 1.25 × lease_ttl_s. An active that
// cannot renew for three quarters of lease_ttl_s (its server gone, another holding the
// key) steps down before anyone else can take over, so two never speak at once. A clean stop deletes the
// key: the standby takes over at its next try.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "kew/daemon/config.hpp"
#include "nats_connection.hpp"

namespace kew::daemon {

class LeaderLease {
 public:
  /// Called on the lease's thread. `on_acquired(last_seq)`: this instance is active now;
  /// `last_seq` is the Kew-Seq of the last message in [nats] stream (0: none, or no
  /// stream), what the previous active published last. `on_lost()`: it is not any more.
  struct Handlers {
    std::function<void(std::uint64_t last_seq)> on_acquired;
    std::function<void()> on_lost;
  };

  /// Starts trying at once. Throws nats::NatsError for a malformed url.
  LeaderLease(const NatsConfig& config, std::string instance, Handlers handlers);
  /// Stops, and gives the lease up when held.
  ~LeaderLease();
  LeaderLease(const LeaderLease&) = delete;
  LeaderLease& operator=(const LeaderLease&) = delete;

  bool active() const { return active_.load(); }
  /// Active, and still within the time the last renewal the server took guarantees that
  /// no other instance can hold the lease (its send time + lease_ttl_s − a renewal
  /// period). The service checks it before sending anything, so that a lease thread
  /// stuck in a slow call cannot let two instances speak at once.
  bool may_speak() const;
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
  /// Waits `period` or until stopping; true when stopping.
  bool wait(std::chrono::steady_clock::duration period);

  NatsConfig config_;
  std::string instance_;
  Handlers handlers_;
  nats::NatsConnection connection_;
  kvStore* bucket_ = nullptr;  // lease thread
  std::atomic<bool> active_{false};
  std::atomic<std::int64_t> speak_until_ns_{0};  // steady clock
  std::chrono::steady_clock::time_point renewed_{};  // lease thread: send time of the last renewal taken
  std::mutex mutex_;
  std::condition_variable stop_;
  bool stopping_ = false;  // guarded by mutex_
  std::thread thread_;
};

}  // namespace kew::daemon
