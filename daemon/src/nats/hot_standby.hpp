#pragma once
// Hot standby's NATS side (design §5.9): the lease that elects the active instance and
// the follower of the active's acknowledgements, each on its own thread, their news
// posted to the service's I/O thread.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "ack_follower.hpp"
#include "leader_lease.hpp"

namespace kew::daemon {

class HotStandby {
 public:
  /// Called on the I/O thread.
  struct Handlers {
    /// The lease is this instance's; the previous active published up to `published`.
    std::function<void(std::uint64_t published)> on_acquired;
    std::function<void()> on_lost;
    /// The active acknowledged these alerts.
    std::function<void(const std::vector<std::string>& ids)> on_acknowledged;
  };

  /// Starts both threads. The instance name is `config.instance`, else "HOST-PID".
  /// Throws nats::NatsError for a malformed url.
  HotStandby(boost::asio::io_context& io, const NatsConfig& config, Handlers handlers);

  /// See LeaderLease::may_speak(). Thread-safe.
  bool may_speak() const { return lease_->may_speak(); }
  const std::string& instance() const { return lease_->instance(); }

 private:
  Handlers handlers_;
  std::unique_ptr<LeaderLease> lease_;
  std::unique_ptr<AckFollower> acks_;
};

}  // namespace kew::daemon
