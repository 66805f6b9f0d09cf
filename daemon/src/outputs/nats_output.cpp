#include "nats_output.hpp"

#include <fmt/format.h>

#include "kew/config/nats_subject.hpp"

namespace kew::daemon {

NatsOutput::NatsOutput(const NatsConfig& config, std::string run_id, const Pipeline& pipeline,
                       std::shared_ptr<const SpeakingRight> right)
    : publisher_(std::make_unique<NatsPublisher>(config, std::move(run_id), std::move(right))),
      pipeline_(pipeline),
      description_(fmt::format("NATS: alerts to {0}.<zone> and {0}.apw.<zone>{1}, status to {2}",
                               config.alerts_subject,
                               config.stream.empty() ? ""
                                                     : fmt::format(" (kept in the JetStream stream {})", config.stream),
                               config.status_subject)),
      hot_standby_(config.hot_standby) {}

void NatsOutput::alert(const AlertEvent& event, const SharedLine& line) {
  if (publisher_) publisher_->publish_alert(alert_subject_tail(event, pipeline_.tiling()), *line, event.seq);
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

std::string alert_subject_tail(const AlertEvent& event, const std::optional<zone::ZoneTiling>& tiling) {
  // Area warnings in a subtree of their own: a reader of <alerts_subject>.* or of one
  // zone's subject, written for pairs, gets pairs alone; <alerts_subject>.apw.> is every
  // area warning, <alerts_subject>.> everything.
  const bool area = event.kind == AlertKind::Apw;
  std::string zone = "single";
  if (tiling) {
    const geo::GeodeticPosition a{event.a.lat_deg, event.a.lon_deg};
    const zone::ZoneKey key = area ? tiling->home(a) : tiling->owner(a, {event.b.lat_deg, event.b.lon_deg});
    zone = config::nats_subject_token(tiling->name(key));
  }
  return area ? "apw." + zone : zone;
}

}  // namespace kew::daemon
