#pragma once
// Hot standby (design §5.9): a standby follows the acknowledgements the active publishes
// on [nats] acks_subject, so that an alert acknowledged before a takeover stays
// acknowledged after it. Each ACK object's ids go to `on_ids` (called on this class's
// thread); what to do with them (nothing while active) is the caller's.

#include <atomic>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "kew/daemon/config.hpp"
#include "nats_connection.hpp"

namespace kew::daemon {

class AckFollower {
 public:
  using IdsHandler = std::function<void(std::vector<std::string> ids)>;
  /// Subscribes (again after any loss) on its own connection. Throws nats::NatsError for
  /// a malformed url.
  AckFollower(const NatsConfig& config, IdsHandler on_ids);
  ~AckFollower();
  AckFollower(const AckFollower&) = delete;
  AckFollower& operator=(const AckFollower&) = delete;

 private:
  void run();

  NatsConfig config_;
  IdsHandler on_ids_;
  nats::NatsConnection connection_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace kew::daemon
