#pragma once
// What kewd says of itself (design §6.6): the health verdict every interface reports, the
// ALIVE object's figures and rates, the uptime, and the alarm state the Modbus panel
// reads.

#include <chrono>
#include <cstdint>
#include <optional>

#include "feed_health.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/protocol/modbus_map.hpp"

namespace kew::daemon {

class ServiceStatus {
 public:
  using Clock = std::chrono::steady_clock;
  /// What the feed alone does not tell.
  struct Conditions {
    bool alert_log_failing = false;  ///< the alert log cannot be written
    bool standby = false;            ///< hot standby, not active
    bool syncing = false;            ///< standby, and not in step with the active
    bool feed_unreachable = false;   ///< a durable feed's NATS server cannot be reached
    bool notify_failing = false;     ///< a notifier has failed for longer than its grace
  };

  /// `pipeline` outlives this; `track_timeout_s` (s, > 0) makes a silent feed stale.
  ServiceStatus(const Pipeline& pipeline, double track_timeout_s);

  /// A record was applied now.
  void record_applied(Clock::time_point now) { feed_.accepted(now); }
  /// Once per ALIVE: the rates since the last sample, the feed's share of refusals, and
  /// `input_losses`, the datagrams and messages every input has lost before kewd read
  /// them since the start.
  void sample(Clock::time_point now, std::uint64_t input_losses);

  /// The alert log first (the feed's state is also told by register 4 and ALIVE's "t", a
  /// lost record of the alerts by nothing else), then standby (a display connected to a
  /// standby must not take its silence for a quiet sky), then an unreachable feed (its
  /// tracks stand still at their last data time), then the feed's.
  protocol::HealthReason health(Clock::time_point now, const Conditions& conditions) const;
  protocol::AliveStatus alive(Clock::time_point now, const Conditions& conditions) const;
  protocol::AlarmSnapshot alarm_state(Clock::time_point now, const Conditions& conditions) const;
  /// Seconds since a record was last applied; nullopt before the first.
  std::optional<double> seconds_since_applied(Clock::time_point now) const {
    return feed_.seconds_since_accepted(now);
  }
  double uptime_s(Clock::time_point now) const { return std::chrono::duration<double>(now - started_).count(); }
  /// The start, UTC seconds.
  double started_unix_s() const { return started_unix_s_; }

 private:
  const Pipeline& pipeline_;
  FeedHealth feed_;
  Clock::time_point started_;
  double started_unix_s_;
  Clock::time_point last_sample_;
  std::uint64_t accepted_at_last_sample_ = 0;
  std::uint64_t updates_at_last_sample_ = 0;
  double records_per_s_ = 0.0;
  double updates_per_s_ = 0.0;
};

}  // namespace kew::daemon
