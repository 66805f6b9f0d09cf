#include "kew/replay/run_statistics.hpp"

#include <fmt/format.h>

#include "kew/protocol/encoders/alert_json.hpp"

namespace kew::replay {

std::string run_statistics_json(const Pipeline& pipeline, const Rejections& decoding, const RunFigures& figures) {
  Rejections rejected;
  rejected.merge(decoding);
  rejected.merge(pipeline.rejections());
  const PipelineStatistics& p = pipeline.statistics();
  const kinetic::KineticStatistics& k = pipeline.kinetic_statistics();
  const alert::AlertManager::Counters& a = pipeline.alerts().counters();

  std::string out = "{";
  const auto field = [&out](std::string_view key, const auto& value) {
    if (out.size() > 1) out += ',';
    out += fmt::format("\"{}\":{}", key, value);
  };
  field("records", figures.records_decoded);
  std::string reasons = "{";
  for (const auto& [reason, n] : rejected.by_reason()) {
    if (reasons.size() > 1) reasons += ',';
    protocol::append_json_string(reasons, reason);
    reasons += fmt::format(":{}", n);
  }
  reasons += '}';
  field("rejected", reasons);
  field("rejected_total", rejected.total());
  field("accepted", p.accepted);
  field("tracks_max", pipeline.tracks().max_size());
  field("tracks_dropped", p.tracks_dropped);
  field("updates", k.updates);
  field("insertions", k.insertions);
  field("reinsertions", k.reinsertions);
  field("velocity_updates", k.velocity_updates);
  field("events_computed", k.events_computed);
  field("events_executed", k.events_executed);
  field("events_discarded", k.events_discarded);
  field("tangencies_ignored", k.tangencies_ignored);
  field("renewals", k.renewals);
  field("repairs", k.repairs);
  field("rebuilds", k.rebuilds);
  field("audits", figures.audits);
  field("audit_violations_found", figures.audit_violations_found);
  field("audit_violations_unrepaired", figures.audit_violations_unrepaired);
  field("queue_max", k.queue_max);
  field("queue_mean", fmt::format("{:.1f}", k.queue_mean()));
  field("probes", p.probes);
  field("pairs_evaluated", p.candidates);
  field("probe", fmt::format("\"{}\"", probe::to_string(pipeline.config().probe_mode)));
  field("alerts_new", a.opened);
  field("alerts_updated", a.updated);
  field("alerts_ended", a.ended);
  field("data_time_last", fmt::format("{:.3f}", p.last_data_time));
  field("wall_s", fmt::format("{:.3f}", figures.wall_s));
  out += "}\n";
  return out;
}

}  // namespace kew::replay
