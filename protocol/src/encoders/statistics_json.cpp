#include "kew/protocol/encoders/statistics_json.hpp"

#include <fmt/format.h>

#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/ndjson_writer.hpp"

namespace kew::protocol {

namespace {

// Members of one JSON object, written in call order with the commas between them.
class Members {
 public:
  explicit Members(std::string& out) : out_(out) { out_ += '{'; }
  void close() { out_ += '}'; }

  template <class Integer>
  void integer(std::string_view key, Integer value) {
    this->key(key);
    out_ += fmt::format("{}", value);
  }
  void fixed(std::string_view key, double value, int decimals) {
    this->key(key);
    out_ += fmt::format("{:.{}f}", value, decimals);
  }
  void string(std::string_view key, std::string_view value) {
    this->key(key);
    append_json_string(out_, value);
  }
  void boolean(std::string_view key, bool value) {
    this->key(key);
    out_ += value ? "true" : "false";
  }
  void rejections(std::string_view key, const Rejections& rejected) {
    this->key(key);
    Members reasons(out_);
    for (const auto& [reason, count] : rejected.by_reason()) reasons.integer(reason, count);
    reasons.close();
  }
  /// Opens a nested object under `key`; the caller closes it.
  Members object(std::string_view key) {
    this->key(key);
    return Members(out_);
  }
  /// Opens an array under `key`; elements go through element(), then close_array().
  void array(std::string_view key) {
    this->key(key);
    out_ += '[';
    first_element_ = true;
  }
  Members element() {
    if (!first_element_) out_ += ',';
    first_element_ = false;
    return Members(out_);
  }
  void close_array() { out_ += ']'; }

 private:
  void key(std::string_view key) {
    if (!first_) out_ += ',';
    first_ = false;
    append_json_string(out_, key);
    out_ += ':';
  }

  std::string& out_;
  bool first_ = true;
  bool first_element_ = true;
};

// The zones of design §4.9: how many, and each one's core, members and work.
void zones_members(Members& m, const Pipeline& pipeline) {
  const PipelineStatistics& p = pipeline.statistics();
  m.string("mode", kZoneModeNames.name(pipeline.config().zone_mode));
  m.integer("count", pipeline.zone_count());
  m.integer("created", p.zones_created);
  m.integer("retired", p.zones_retired);
  m.fixed("margin_km", pipeline.zone_margin_m() / 1000.0, 1);
  m.integer("threads", pipeline.config().threads);
  m.array("list");
  pipeline.for_each_zone([&](const zone::Zone& zone) {
    Members z = m.element();
    z.string("name", zone.name());
    if (const auto& tiling = pipeline.tiling()) {
      const zone::ZoneTiling::Core core = tiling->core(zone.key());
      z.fixed("south", core.south_deg, 4);
      z.fixed("north", core.north_deg, 4);
      z.fixed("west", core.west_deg, 4);
      z.fixed("east", core.east_deg, 4);
    }
    z.integer("tracks", zone.members());
    z.integer("updates", zone.statistics().updates);
    z.integer("probes", zone.statistics().probes);
    z.fixed("busy_s", zone.statistics().busy_s, 3);
    z.fixed("max_scale", zone.projection().max_scale(), 4);
    z.close();
  });
  m.close_array();
}

// `decoding`: the decoders' rejections, added to the pipeline's in `rejected`.
void pipeline_members(Members& m, const Pipeline& pipeline, const Rejections& decoding) {
  Rejections rejected;
  rejected.merge(decoding);
  rejected.merge(pipeline.rejections());
  const PipelineStatistics& p = pipeline.statistics();
  const kinetic::KineticStatistics& k = pipeline.kinetic_statistics();
  const alert::AlertManager& alerts = pipeline.alerts();
  const alert::AlertManager::Counters& a = alerts.counters();
  m.integer("records", p.records);
  m.integer("accepted", p.accepted);
  m.rejections("rejected", rejected);
  m.integer("rejected_total", rejected.total());
  m.rejections("fields_dropped", pipeline.dropped_fields());
  m.integer("tracks", pipeline.live_tracks());
  m.integer("tracks_max", pipeline.tracks().max_size());
  m.integer("tracks_dropped", p.tracks_dropped);
  m.integer("tracks_ended", p.tracks_ended);
  m.integer("tracks_restarted", p.tracks_restarted);
  m.integer("runs_restarted", p.runs_restarted);
  m.integer("updates", k.updates);
  m.integer("insertions", k.insertions);
  m.integer("reinsertions", k.reinsertions);
  m.integer("velocity_updates", k.velocity_updates);
  m.integer("kept_updates", k.kept_updates);
  m.integer("drift_reinsertions", k.drift_reinsertions);
  m.integer("events_computed", k.events_computed);
  m.integer("events_executed", k.events_executed);
  m.integer("events_discarded", k.events_discarded);
  m.integer("tangencies_ignored", k.tangencies_ignored);
  m.integer("renewals", k.renewals);
  m.integer("repairs", k.repairs);
  m.integer("rebuilds", k.rebuilds);
  m.integer("renumberings", k.renumberings);
  m.integer("queue_now", k.queue_now);
  m.integer("queue_max", k.queue_max);
  m.fixed("queue_mean", k.queue_mean(), 1);
  m.integer("probes", p.probes);
  m.integer("pairs_evaluated", p.candidates);
  m.string("probe", probe::to_string(pipeline.config().probe_mode));
  m.rejections("suppressed", pipeline.suppressed());
  m.integer("alerts_active", alerts.active_count());
  m.integer("alerts_new", a.opened);
  m.integer("alerts_updated", a.updated);
  m.integer("alerts_ended", a.ended);
  m.integer("unacknowledged", alerts.unacknowledged_count());
  m.fixed("data_time_last", p.last_data_time, 3);
  Members zones = m.object("zones");
  zones_members(zones, pipeline);
  zones.close();
}

}  // namespace

void append_zones_json(std::string& out, const Pipeline& pipeline) {
  Members m(out);
  m.string("class", "ZONES");
  zones_members(m, pipeline);
  m.close();
  out += '\n';
}

std::string stats_json(const Pipeline& pipeline, const ServiceStatistics& service) {
  Rejections decoding;
  for (const InputStatistics& input : service.inputs) decoding.merge(input.rejected);
  std::string out;
  Members m(out);
  m.string("class", "STATS");
  m.integer("seq", service.seq);
  m.fixed("uptime_s", service.uptime_s, 0);
  pipeline_members(m, pipeline, decoding);
  Members subscribers = m.object("subscribers");
  subscribers.integer("now", service.subscribers_now);
  subscribers.integer("accepted", service.subscribers.accepted);
  subscribers.integer("refused", service.subscribers.refused);
  subscribers.integer("admin", service.subscribers.admin);
  subscribers.integer("cut_off", service.subscribers.cut_off);
  subscribers.integer("timed_out", service.subscribers.timed_out);
  subscribers.integer("evicted", service.subscribers.evicted);
  subscribers.integer("bad_requests", service.subscribers.bad_requests);
  subscribers.integer("accept_failures", service.subscribers.accept_failures);
  subscribers.integer("backlog_bytes_max", service.subscribers.backlog_bytes_max);
  subscribers.close();
  m.array("inputs");
  for (const InputStatistics& input : service.inputs) {
    Members i = m.element();
    i.string("name", input.name);
    i.integer("bytes", input.bytes);
    i.integer("reports", input.reports);
    i.integer("connections", input.connections);
    i.integer("connections_refused", input.connections_refused);
    i.integer("connections_idle", input.connections_idle);
    i.integer("accept_failures", input.accept_failures);
    i.integer("oversized_datagrams", input.oversized_datagrams);
    i.integer("datagrams_dropped", input.datagrams_dropped);
    i.integer("messages_dropped", input.messages_dropped);
    i.integer("polls", input.polls);
    i.integer("polls_unchanged", input.polls_unchanged);
    i.integer("poll_failures", input.poll_failures);
    i.rejections("rejected", input.rejected);
    i.close();
  }
  m.close_array();
  if (service.cat004) {
    Members c = m.object("cat004");
    c.integer("datagrams", service.cat004->datagrams);
    c.integer("errors", service.cat004->errors);
    c.close();
  }
  if (service.nats) {
    const NatsStatistics& s = *service.nats;
    Members c = m.object("nats");
    c.boolean("connected", s.connected);
    c.integer("disconnects", s.disconnects);
    c.integer("published", s.published);
    c.integer("retries", s.retries);
    c.integer("queued", s.queued);
    c.integer("dropped", s.dropped);
    c.integer("status_published", s.status_published);
    c.integer("fenced", s.fenced);
    if (s.active) {
      c.boolean("active", *s.active);
      c.boolean("bus_away", s.bus_away);
      c.integer("checkpoints_written", s.checkpoints_written);
      c.boolean("began_from_checkpoint", s.began_from_checkpoint);
    }
    c.close();
  }
  if (!service.notify.empty()) {
    m.array("notify");
    for (const NotifyStatistics& n : service.notify) {
      Members c = m.element();
      c.string("name", n.name);
      c.integer("delivered", n.delivered);
      c.integer("failures", n.failures);
      c.integer("dropped", n.dropped);
      c.integer("queued", n.queued);
      c.boolean("failing", n.failing);
      c.close();
    }
    m.close_array();
  }
  if (service.modbus) {
    const ModbusStatistics& s = *service.modbus;
    Members c = m.object("modbus");
    c.integer("requests", s.requests);
    c.integer("exceptions", s.exceptions);
    c.integer("connections_open", s.connections_open);
    c.integer("accepted", s.connections_accepted);
    c.integer("refused", s.connections_refused);
    c.integer("dropped", s.connections_dropped);
    c.integer("acknowledgements", s.acknowledgements);
    c.rejections("rejected", s.rejected);
    c.close();
  }
  if (service.alert_log_errors) m.integer("alert_log_errors", *service.alert_log_errors);
  if (service.alert_log_queued_bytes) m.integer("alert_log_queued_bytes", *service.alert_log_queued_bytes);
  if (service.alert_log_dropped) m.integer("alert_log_dropped", *service.alert_log_dropped);
  if (service.record_file_queued_bytes) m.integer("record_file_queued_bytes", *service.record_file_queued_bytes);
  if (service.record_file_dropped) m.integer("record_file_dropped", *service.record_file_dropped);
  if (service.resident_bytes) m.integer("resident_bytes", *service.resident_bytes);
  m.close();
  out += '\n';
  return out;
}

std::string run_statistics_json(const Pipeline& pipeline, const Rejections& decoding,
                                const ReplayStatistics& replay) {
  std::string out;
  Members m(out);
  pipeline_members(m, pipeline, decoding);
  m.integer("audits", replay.audits);
  m.integer("audit_violations_found", replay.audit_violations_found);
  m.integer("audit_violations_unrepaired", replay.audit_violations_unrepaired);
  m.fixed("wall_s", replay.wall_s, 3);
  m.close();
  out += '\n';
  return out;
}

}  // namespace kew::protocol
