#pragma once
// A hot-standby instance's view of its pair on NATS (design §5.9), on a thread and a
// connection of its own: first where this instance begins (the pair's origin, read from
// the key-value bucket [nats] pair_bucket or written there when the pair has none; moved
// on to the pair's latest checkpoint when there is one this instance can load), then
// every event and acknowledgement the active publishes into the alert stream from there
// on, in stream order. Its news goes to the handlers, called on its thread.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <memory>

#include "../standby/pair_checkpoint.hpp"
#include "../standby/pair_origin.hpp"
#include "kew/alert/alert_event.hpp"
#include "kew/daemon/config.hpp"
#include "nats_connection.hpp"

namespace kew::daemon {

class PairFollower {
 public:
  struct Handlers {
    /// Where this instance begins, once: the pair's origin, or the latest checkpoint's
    /// continuation of it (feed_seq, alerts_seq and last_seq moved to the checkpoint's;
    /// `checkpoint` then not null).
    std::function<void(const PairOrigin& start, std::shared_ptr<const PairCheckpoint> checkpoint)> on_origin;
    /// Whether this instance can load a checkpoint's pipeline state (`why` when not).
    /// Unset: checkpoints are not read (the feed cannot be judged from one).
    std::function<bool(const std::string& state, std::string& why)> usable;
    /// The active's events and acknowledgements (the seq their object carries).
    std::function<void(const AlertEvent&)> on_alert;
    std::function<void(std::uint64_t seq, std::vector<std::string> ids)> on_acknowledgement;
    /// Every message the stream held when following began has been read; the last one
    /// carried `seq` (the origin's last_seq when none did). Once.
    std::function<void(std::uint64_t seq)> on_read_up_to;
  };

  /// `feed_stream`: the JetStream stream of the pair's feed. `numbering`: this instance's
  /// own (its last seq and next alert number), the origin's when it writes one; the
  /// pair's numbering continues above the alert stream's last seq in any case.
  /// Starts the thread. Throws nats::NatsError for a malformed url.
  PairFollower(const NatsConfig& config, std::string feed_stream, std::string instance, std::uint64_t last_seq,
               std::uint16_t next_number, Handlers handlers);
  ~PairFollower();
  PairFollower(const PairFollower&) = delete;
  PairFollower& operator=(const PairFollower&) = delete;

 private:
  void run();
  /// The origin, written when there is none; nullopt when the server did not tell.
  std::optional<PairOrigin> origin();
  std::optional<PairOrigin> new_origin();
  /// The pair's latest checkpoint that continues `origin` and this instance can load.
  std::shared_ptr<const PairCheckpoint> latest_checkpoint(const PairOrigin& origin);
  bool bind_bucket();
  /// Follows the alert stream from `origin` until stopping.
  void follow(const PairOrigin& origin);
  /// First and last sequence of a stream (0, 0 when it does not exist yet).
  struct StreamBounds {
    std::uint64_t first = 0, last = 0;
  };
  std::optional<StreamBounds> bounds(const std::string& stream);
  bool sleep_unless_stopping();

  NatsConfig config_;
  std::string feed_stream_;
  std::string instance_;
  std::uint64_t last_seq_;
  std::uint16_t next_number_;
  Handlers handlers_;
  nats::NatsConnection connection_;
  kvStore* bucket_ = nullptr;  // the thread's
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace kew::daemon
