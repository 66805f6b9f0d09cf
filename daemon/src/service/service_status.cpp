#include "service_status.hpp"

#include "kew/util/clocks.hpp"

namespace kew::daemon {

ServiceStatus::ServiceStatus(const Pipeline& pipeline, double track_timeout_s)
    : pipeline_(pipeline),
      feed_(track_timeout_s),
      started_(Clock::now()),
      started_unix_s_(util::unix_now_s()),
      last_sample_(started_) {}

void ServiceStatus::sample(Clock::time_point now, std::uint64_t input_losses) {
  const double span = std::chrono::duration<double>(now - last_sample_).count();
  const PipelineStatistics s = pipeline_.statistics();
  const std::uint64_t updates = pipeline_.kinetic_statistics().updates;
  if (span > 0) {
    records_per_s_ = static_cast<double>(s.accepted - accepted_at_last_sample_) / span;
    updates_per_s_ = static_cast<double>(updates - updates_at_last_sample_) / span;
  }
  accepted_at_last_sample_ = s.accepted;
  updates_at_last_sample_ = updates;
  last_sample_ = now;
  // Targets on the ground are left out by configuration, not refused for a fault: a
  // receiver beside an airport at night sees mostly those and is healthy.
  const std::uint64_t on_ground = pipeline_.rejections().count(track::kRefusalNames.name(track::Refusal::OnGround));
  feed_.sample(s.records - on_ground, s.accepted, input_losses);
}

protocol::HealthReason ServiceStatus::health(Clock::time_point now, const Conditions& conditions) const {
  if (conditions.alert_log_failing) return protocol::HealthReason::AlertLogFailing;
  if (conditions.standby)
    return conditions.syncing ? protocol::HealthReason::StandbySyncing : protocol::HealthReason::Standby;
  if (conditions.feed_unreachable) return protocol::HealthReason::FeedUnreachable;
  const protocol::HealthReason feed = feed_.reason(now);
  // The feed first: without records there is nothing to notify.
  if (feed == protocol::HealthReason::Healthy && conditions.notify_failing) return protocol::HealthReason::NotifyFailing;
  return feed;
}

protocol::AliveStatus ServiceStatus::alive(Clock::time_point now, const Conditions& conditions) const {
  protocol::AliveStatus status;
  if (feed_.seconds_since_accepted(now)) status.last_data_t = pipeline_.statistics().last_data_time;
  status.tracks = pipeline_.live_tracks();
  status.alerts = pipeline_.alerts().active_count();
  status.records_per_s = records_per_s_;
  status.updates_per_s = updates_per_s_;
  status.uptime_s = static_cast<std::uint64_t>(uptime_s(now));
  status.health = health(now, conditions);
  return status;
}

protocol::AlarmSnapshot ServiceStatus::alarm_state(Clock::time_point now, const Conditions& conditions) const {
  protocol::AlarmSnapshot snapshot;
  snapshot.active = pipeline_.alerts().snapshot();
  snapshot.live_tracks = static_cast<std::uint32_t>(pipeline_.live_tracks());
  snapshot.seconds_since_last_record = feed_.seconds_since_accepted(now).value_or(1e9);
  snapshot.feed_healthy = !conditions.feed_unreachable && feed_.reason(now) == protocol::HealthReason::Healthy;
  snapshot.degraded = health(now, conditions) != protocol::HealthReason::Healthy;
  snapshot.uptime_s = static_cast<std::uint32_t>(uptime_s(now));
  snapshot.unacknowledged = static_cast<std::uint32_t>(pipeline_.alerts().unacknowledged_count());
  return snapshot;
}

}  // namespace kew::daemon
