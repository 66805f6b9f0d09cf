#pragma once
// Hot standby's NATS side (design §5.9): the pair's origin and the active's published
// events and acknowledgements (PairFollower), and the lease that elects the active
// (LeaderLease), each on its own thread, their news posted to the service's I/O thread.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "checkpoint_store.hpp"
#include "leader_lease.hpp"
#include "pair_follower.hpp"

namespace kew::daemon {

class HotStandby {
 public:
  /// Called on the I/O thread.
  struct Handlers {
    /// Where this instance begins: judge the feed from there with its numbering, from
    /// the checkpoint's state when there is one. Once, first.
    std::function<void(const PairOrigin& start, std::shared_ptr<const PairCheckpoint> checkpoint)> on_origin;
    /// PairFollower::Handlers::usable, called on the follower's thread; unset: no
    /// checkpoint is read or written.
    std::function<bool(const std::string& state, std::string& why)> usable;
    /// The lease is this instance's; the previous active published up to `published`.
    std::function<void(std::uint64_t published)> on_acquired;
    std::function<void()> on_lost;
    /// What the active published (PairFollower::Handlers).
    std::function<void(const AlertEvent&)> on_active_alert;
    std::function<void(std::uint64_t seq, std::vector<std::string> ids)> on_active_acknowledgement;
    std::function<void(std::uint64_t seq)> on_stream_read_up_to;
  };

  /// Starts the threads. The instance name is `config.instance`, else "HOST-PID".
  /// `feed_stream`, `last_seq` and `next_number`: PairFollower's. Throws nats::NatsError
  /// for a malformed url.
  HotStandby(boost::asio::io_context& io, const NatsConfig& config, const std::string& feed_stream,
             std::uint64_t last_seq, std::uint16_t next_number, Handlers handlers,
             std::shared_ptr<SpeakingRight> right);

  /// Whether this instance is in step with the pair (StandbySync): only then does it try
  /// to take a free lease at once; out of step, only once no instance has taken it for a
  /// whole TTL. Thread-safe.
  void set_in_step(bool in_step) { in_step_ = in_step; }
  /// The pair's origin is known: the lease may be taken (unsynced at worst). Thread-safe.
  void set_origin_known() { origin_known_ = true; }
  const std::string& instance() const { return instance_; }
  /// Hands a checkpoint to the writer (CheckpointPublisher::write); false while it is
  /// busy or when checkpoints are off.
  std::uint64_t checkpoints_written() const { return checkpoints_ ? checkpoints_->written() : 0; }
  bool write_checkpoint(PairCheckpoint checkpoint, std::future<std::uint64_t> published) {
    return checkpoints_ && checkpoints_->write(std::move(checkpoint), std::move(published));
  }

 private:
  Handlers handlers_;
  std::string instance_;
  std::atomic<bool> in_step_{false};
  std::atomic<bool> origin_known_{false};
  std::unique_ptr<LeaderLease> lease_;
  std::unique_ptr<PairFollower> follower_;
  std::unique_ptr<CheckpointPublisher> checkpoints_;
};

}  // namespace kew::daemon
