#include "nats_output.hpp"

#include <fmt/format.h>

#include "kew/config/nats_subject.hpp"

namespace kew::daemon {

NatsOutput::NatsOutput(const NatsConfig& config, std::string run_id, const Pipeline& pipeline,
                       std::shared_ptr<const SpeakingRight> right)
    : publisher_(std::make_unique<NatsPublisher>(config, std::move(run_id), std::move(right))),
      pipeline_(pipeline),
      description_(fmt::format("NATS: alerts to {}.<zone>{}, status to {}", config.alerts_subject,
                               config.stream.empty() ? ""
                                                     : fmt::format(" (kept in the JetStream stream {})", config.stream),
                               config.status_subject)),
      hot_standby_(config.hot_standby) {}

void NatsOutput::alert(const AlertEvent& event, const SharedLine& line) {
  if (publisher_) publisher_->publish_alert(zone(event), *line, event.seq);
}

void NatsOutput::acknowledgement(const protocol::Acknowledgement&, std::uint64_t seq, const SharedLine& line) {
  if (publisher_) publisher_->publish_ack(*line, seq);
}

void NatsOutput::alive(const AliveEvent& alive, const SharedLine& line) {
  if (publisher_) publisher_->publish_status(*line, alive.seq);
}

void NatsOutput::tracks(const std::string& line, std::uint64_t seq) {
  if (publisher_ && active_) publisher_->publish_tracks(line, seq);
}

void NatsOutput::role_changed(bool active) {
  if (active_ && !active && publisher_) publisher_->discard_outbox();
  active_ = active;
}

void NatsOutput::report(protocol::ServiceStatistics& statistics) const {
  if (!publisher_) return;
  statistics.nats = publisher_->statistics();
  if (hot_standby_) statistics.nats->active = active_;
}

std::string NatsOutput::zone(const AlertEvent& event) const {
  const std::optional<zone::ZoneTiling>& tiling = pipeline_.tiling();
  if (!tiling) return "single";
  const zone::ZoneKey owner = tiling->owner({event.a.lat_deg, event.a.lon_deg}, {event.b.lat_deg, event.b.lon_deg});
  return config::nats_subject_token(tiling->name(owner));
}

}  // namespace kew::daemon
