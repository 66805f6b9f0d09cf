#include "metrics.hpp"

#include <dirent.h>
#include <unistd.h>

#include <fstream>
#include <initializer_list>
#include <iterator>
#include <utility>

#include <fmt/format.h>

#include "http_server.hpp"
#include "kew/protocol/version.hpp"

namespace kew::daemon::http {

namespace {

using Label = std::pair<std::string_view, std::string_view>;

/// Writes families of samples: the HELP and TYPE lines once per family, then its samples.
class Exposition {
 public:
  void family(std::string_view name, std::string_view type, std::string_view help) {
    fmt::format_to(std::back_inserter(out_), "# HELP {} {}\n# TYPE {} {}\n", name, help, name, type);
  }
  void sample(std::string_view name, std::initializer_list<Label> labels, double value) {
    out_.append(name);
    if (labels.size()) {
      out_.push_back('{');
      bool first = true;
      for (const auto& [key, text] : labels) {
        if (!first) out_.push_back(',');
        first = false;
        out_.append(key);
        out_.append("=\"");
        escape(text);
        out_.push_back('"');
      }
      out_.push_back('}');
    }
    fmt::format_to(std::back_inserter(out_), " {}\n", value);
  }
  /// A family of one unlabelled sample.
  void single(std::string_view name, std::string_view type, std::string_view help, double value) {
    family(name, type, help);
    sample(name, {}, value);
  }
  std::string take() { return std::move(out_); }

 private:
  void escape(std::string_view text) {
    for (const char c : text) {
      if (c == '\\') out_.append("\\\\");
      else if (c == '"') out_.append("\\\"");
      else if (c == '\n') out_.append("\\n");
      else out_.push_back(c);
    }
  }
  std::string out_;
};

double num(std::uint64_t n) { return static_cast<double>(n); }

struct KineticCounter {
  std::string_view name, help;
  std::uint64_t kinetic::KineticStatistics::*member;
};
constexpr std::array<KineticCounter, 17> kKineticCounters{{
    {"kew_kinetic_certificates_solved_total", "Sturm certificate solves run.", &kinetic::KineticStatistics::certificates_solved},
    {"kew_kinetic_events_computed_total", "Certificate failures found and scheduled.", &kinetic::KineticStatistics::events_computed},
    {"kew_kinetic_events_executed_total", "Certificate failures that flipped an edge.", &kinetic::KineticStatistics::events_executed},
    {"kew_kinetic_events_discarded_total", "Scheduled failures descheduled before their time.", &kinetic::KineticStatistics::events_discarded},
    {"kew_kinetic_tangencies_ignored_total", "Even-multiplicity roots (no event).", &kinetic::KineticStatistics::tangencies_ignored},
    {"kew_kinetic_renewals_total", "Expired certificate windows re-examined.", &kinetic::KineticStatistics::renewals},
    {"kew_kinetic_insertions_total", "Points inserted into the kinetic triangulation.", &kinetic::KineticStatistics::insertions},
    {"kew_kinetic_removals_total", "Points removed from the kinetic triangulation.", &kinetic::KineticStatistics::removals},
    {"kew_kinetic_updates_total", "Track updates applied to the kinetic triangulation.", &kinetic::KineticStatistics::updates},
    {"kew_kinetic_reinsertions_total", "Updates beyond the tolerance: removed and reinserted.", &kinetic::KineticStatistics::reinsertions},
    {"kew_kinetic_kept_updates_total", "Updates within the tolerance for long enough: the model kept.", &kinetic::KineticStatistics::kept_updates},
    {"kew_kinetic_drift_reinsertions_total", "Kept models reinserted on their report when their bound ran out.", &kinetic::KineticStatistics::drift_reinsertions},
    {"kew_kinetic_repairs_total", "Defects found by audits or degenerate events and fixed.", &kinetic::KineticStatistics::repairs},
    {"kew_kinetic_degenerate_flips_total", "Flips of edges whose certificate is zero within rounding.", &kinetic::KineticStatistics::degenerate_flips},
    {"kew_kinetic_rebuilds_total", "Full retriangulations (last-resort repair).", &kinetic::KineticStatistics::rebuilds},
    {"kew_kinetic_renumberings_total", "Engines rebuilt in Hilbert order for memory locality.", &kinetic::KineticStatistics::renumberings},
    {"kew_kinetic_twins_created_total", "Points made twins (exact duplicates and approaches).", &kinetic::KineticStatistics::twins_created},
}};

void write_inputs(Exposition& e, const std::vector<InputMetrics>& inputs) {
  e.family("kew_records_total", "counter", "Records decoded from each input.");
  for (const InputMetrics& in : inputs) e.sample("kew_records_total", {{"input", in.name}}, num(in.records));
  e.family("kew_records_rejected_total", "counter",
           "Records refused, by input and reason (decoder and pipeline refusals).");
  for (const InputMetrics& in : inputs)
    for (const auto& [reason, n] : in.rejected.by_reason())
      e.sample("kew_records_rejected_total", {{"input", in.name}, {"reason", reason}}, num(n));
  e.family("kew_input_received_bytes_total", "counter", "Bytes received by each input.");
  for (const InputMetrics& in : inputs) e.sample("kew_input_received_bytes_total", {{"input", in.name}}, num(in.bytes));
  e.family("kew_input_datagrams_dropped_total", "counter",
           "Datagrams the kernel dropped before kewd read them (UDP inputs: the receive buffer was full).");
  for (const InputMetrics& in : inputs)
    e.sample("kew_input_datagrams_dropped_total", {{"input", in.name}}, num(in.datagrams_dropped));
  e.family("kew_input_last_record_timestamp_seconds", "gauge",
           "Wall-clock time (Unix seconds) each input last delivered a decoded record; absent before the first.");
  for (const InputMetrics& in : inputs)
    if (in.last_record_unix_s)
      e.sample("kew_input_last_record_timestamp_seconds", {{"input", in.name}}, *in.last_record_unix_s);
  e.family("kew_input_polls_total", "counter",
           "Requests of each http input, by result: taken (answered 200), unchanged (304), failed (no answer, an "
           "error status, too large).");
  for (const InputMetrics& in : inputs) {
    if (!in.polls) continue;
    e.sample("kew_input_polls_total", {{"input", in.name}, {"result", "taken"}}, num(in.polls->taken));
    e.sample("kew_input_polls_total", {{"input", in.name}, {"result", "unchanged"}}, num(in.polls->unchanged));
    e.sample("kew_input_polls_total", {{"input", in.name}, {"result", "failed"}}, num(in.polls->failed));
  }
}

/// Every kind and severity has its sample, 0 included: a sum over either label, and a
/// rule on one series, finds it before the first alert of its kind.
void write_alerts_active(Exposition& e, const std::vector<AlertEvent>& active) {
  constexpr std::array kKinds{AlertKind::Stca, AlertKind::Apw};
  std::array<std::array<std::uint64_t, 4>, kKinds.size()> count{};
  for (const AlertEvent& a : active) ++count[static_cast<std::size_t>(a.kind)][static_cast<std::size_t>(a.severity)];
  e.family("kew_alerts_active", "gauge", "Active alerts by severity and kind (stca: a pair; apw: an aircraft and a volume).");
  for (const AlertKind kind : kKinds)
    for (const Severity s : {Severity::Caution, Severity::Warning, Severity::Loss})
      e.sample("kew_alerts_active", {{"severity", to_string(s)}, {"kind", to_string(kind)}},
               num(count[static_cast<std::size_t>(kind)][static_cast<std::size_t>(s)]));
}

void write_pipeline(Exposition& e, const Pipeline& pipeline) {
  const PipelineStatistics& p = pipeline.statistics();
  e.single("kew_records_accepted_total", "counter", "Records the track table accepted (all inputs).", num(p.accepted));
  e.single("kew_tracks", "gauge", "Live tracks (in the kinetic engine), as ALIVE and ?STATS report.",
           num(pipeline.live_tracks()));
  e.single("kew_tracks_dropped_total", "counter", "Tracks dropped (timeout, end of track, restart).",
           num(p.tracks_dropped));
  e.single("kew_data_time_seconds", "gauge", "The pipeline clock: data time of the latest record (Unix seconds).",
           p.last_data_time);

  write_alerts_active(e, pipeline.alerts().snapshot());
  e.single("kew_alerts_unacknowledged", "gauge", "Active alerts not acknowledged.",
           num(pipeline.alerts().unacknowledged_count()));
  const auto& c = pipeline.alerts().counters();
  e.family("kew_alert_events_total", "counter", "Alert events by state (new, update, end).");
  e.sample("kew_alert_events_total", {{"state", "new"}}, num(c.opened));
  e.sample("kew_alert_events_total", {{"state", "update"}}, num(c.updated));
  e.sample("kew_alert_events_total", {{"state", "end"}}, num(c.ended));

  e.single("kew_zones", "gauge", "Zones that exist now (design §4.9: where traffic is).", num(pipeline.zone_count()));
  e.family("kew_zone_tracks", "gauge", "Tracks in each zone's core and margin.");
  pipeline.for_each_zone([&](const zone::Zone& z) { e.sample("kew_zone_tracks", {{"zone", z.name()}}, num(z.members())); });
  e.family("kew_zone_updates_total", "counter", "Track updates each zone's engine applied since the zone came to exist.");
  pipeline.for_each_zone(
      [&](const zone::Zone& z) { e.sample("kew_zone_updates_total", {{"zone", z.name()}}, num(z.statistics().updates)); });
  e.family("kew_zone_busy_seconds_total", "counter", "Wall seconds each zone's work took since the zone came to exist.");
  pipeline.for_each_zone(
      [&](const zone::Zone& z) { e.sample("kew_zone_busy_seconds_total", {{"zone", z.name()}}, z.statistics().busy_s); });

  const kinetic::KineticStatistics& k = pipeline.kinetic_statistics();
  for (const KineticCounter& counter : kKineticCounters) e.single(counter.name, "counter", counter.help, num(k.*counter.member));
  e.single("kew_kinetic_event_queue", "gauge", "Certificate failures and approaches scheduled now.", num(k.queue_now));
}

void write_latency(Exposition& e, const LatencyHistogram& h) {
  constexpr std::string_view kName = "kew_record_to_alert_latency_seconds";
  e.family(kName, "histogram",
           "Wall time from a decoded record reaching the service to each alert event it caused reaching the sinks.");
  std::uint64_t cumulative = 0;
  for (std::size_t i = 0; i < LatencyHistogram::kBounds.size(); ++i) {
    cumulative += h.counts()[i];
    e.sample("kew_record_to_alert_latency_seconds_bucket", {{"le", fmt::format("{:f}", LatencyHistogram::kBounds[i])}},
             num(cumulative));
  }
  e.sample("kew_record_to_alert_latency_seconds_bucket", {{"le", "+Inf"}}, num(h.count()));
  e.sample("kew_record_to_alert_latency_seconds_sum", {}, h.sum());
  e.sample("kew_record_to_alert_latency_seconds_count", {}, num(h.count()));
}


/// One sample per notifier of each family (design §5.10).
void notify_metrics(Exposition& e, const std::vector<protocol::NotifyStatistics>& notifiers) {
  struct Family {
    std::string_view name, type, help;
    double (*value)(const protocol::NotifyStatistics&);
  };
  static constexpr std::array<Family, 5> kFamilies{{
      {"kew_notify_delivered_total", "counter", "Messages each notifier's endpoint took.",
       [](const protocol::NotifyStatistics& n) { return num(n.delivered); }},
      {"kew_notify_failures_total", "counter", "Delivery attempts that failed (no answer, or not 2xx).",
       [](const protocol::NotifyStatistics& n) { return num(n.failures); }},
      {"kew_notify_dropped_total", "counter", "Events dropped from a notifier's full outbox.",
       [](const protocol::NotifyStatistics& n) { return num(n.dropped); }},
      {"kew_notify_queued", "gauge", "Events waiting in each notifier's outbox.",
       [](const protocol::NotifyStatistics& n) { return num(n.queued); }},
      {"kew_notify_failing", "gauge", "1 while a notifier has failed for longer than its failing_after_s.",
       [](const protocol::NotifyStatistics& n) { return n.failing ? 1.0 : 0.0; }},
  }};
  for (const Family& family : kFamilies) {
    e.family(family.name, family.type, family.help);
    for (const protocol::NotifyStatistics& n : notifiers) e.sample(family.name, {{"notifier", n.name}}, family.value(n));
  }
}

void write_listeners(Exposition& e, const MetricsSources& s) {
  e.single("kew_subscribers", "gauge", "Alert stream subscribers connected.", num(s.subscribers));
  e.single("kew_subscriber_queued_bytes", "gauge", "Bytes queued for every alert stream subscriber together.",
           num(s.subscriber_queued_bytes));
  e.single("kew_subscribers_cut_off_total", "counter", "Subscribers disconnected for falling behind.",
           num(s.subscriber_figures.cut_off));
  e.single("kew_subscribers_evicted_total", "counter",
           "Silent alert stream connections closed to make room for a newcomer.", num(s.subscriber_figures.evicted));
  if (s.alert_log_queued_bytes)
    e.single("kew_alert_log_queued_bytes", "gauge", "Bytes of alert events waiting for the alert log.",
             num(*s.alert_log_queued_bytes));
  if (s.alert_log_errors)
    e.single("kew_alert_log_errors_total", "counter",
             "Alert log errors: failed writes, truncations, rotations and syncs.",
             num(*s.alert_log_errors));
  if (s.health) {
    e.family("kew_health", "gauge",
             "kewd's health verdict (ALIVE \"health\"): 1 for the current reason, 0 for the others.");
    for (const auto& [reason, name] : protocol::kHealthReasonNames.entries())
      e.sample("kew_health", {{"reason", name}}, reason == *s.health ? 1.0 : 0.0);
  }
  if (s.nats) {
    const protocol::NatsStatistics& n = *s.nats;
    e.single("kew_nats_connected", "gauge", "1 while the publisher is connected to its NATS server.",
             n.connected ? 1.0 : 0.0);
    e.single("kew_nats_disconnects_total", "counter", "Connections to the NATS server lost.", num(n.disconnects));
    e.single("kew_nats_published_total", "counter", "Alert events and acknowledgements the NATS server took.",
             num(n.published));
    e.single("kew_nats_retries_total", "counter", "Publications tried again.", num(n.retries));
    e.single("kew_nats_queued", "gauge", "Events waiting for the NATS server.", num(n.queued));
    e.single("kew_nats_dropped_total", "counter", "Events dropped from a full NATS outbox.", num(n.dropped));
    e.single("kew_nats_fenced_total", "counter",
             "Hot standby: publications refused because another publisher had added to the stream.", num(n.fenced));
    if (n.active) {
      e.single("kew_standby_active", "gauge", "Hot standby: 1 while this kewd holds the lease and sends alerts.",
               *n.active ? 1.0 : 0.0);
      e.single("kew_standby_bus_away", "gauge",
               "Hot standby: 1 while this active kewd reaches no NATS server and serves the other outputs alone.",
               n.bus_away ? 1.0 : 0.0);
      e.single("kew_standby_checkpoints_written_total", "counter",
               "Hot standby: checkpoints of the computation this kewd wrote as the active.",
               num(n.checkpoints_written));
    }
  }
  if (!s.notify.empty()) notify_metrics(e, s.notify);
  if (!s.http) return;
  const HttpStatistics& h = *s.http;
  e.single("kew_http_connections", "gauge", "HTTP and WebSocket connections open.", num(s.http_connections));
  e.single("kew_websockets", "gauge", "WebSocket (/ws) clients connected.", num(s.websockets));
  e.single("kew_websocket_queued_bytes", "gauge", "Bytes queued for every WebSocket client together.",
           num(s.websocket_queued_bytes));
  e.single("kew_http_connections_accepted_total", "counter", "HTTP connections accepted.", num(h.connections_accepted));
  e.family("kew_http_connections_refused_total", "counter",
           "HTTP connections closed at once by reason: full (every slot busy), evicted (made room), "
           "accept_failed (out of descriptors).");
  e.sample("kew_http_connections_refused_total", {{"reason", "full"}}, num(h.connections_refused));
  e.sample("kew_http_connections_refused_total", {{"reason", "evicted"}}, num(h.connections_evicted));
  e.sample("kew_http_connections_refused_total", {{"reason", "accept_failed"}}, num(h.accept_failures));
  e.family("kew_http_responses_total", "counter", "HTTP responses by status code.");
  for (const auto& [code, n] : h.responses) e.sample("kew_http_responses_total", {{"code", fmt::format("{}", code)}}, num(n));
  e.family("kew_http_requests_refused_total", "counter",
           "HTTP requests refused by reason (malformed, header_too_large, timeout, ack_*, not_found, ...).");
  for (const auto& [reason, n] : h.bad_requests.by_reason())
    e.sample("kew_http_requests_refused_total", {{"reason", reason}}, num(n));
  e.single("kew_websockets_accepted_total", "counter", "WebSocket handshakes completed.", num(h.websockets_accepted));
  e.family("kew_websockets_closed_total", "counter",
           "WebSocket clients closed by kewd by reason (client_message, protocol_error, cut_off, timeout, handshake).");
  for (const auto& [reason, n] : h.websocket_closed.by_reason())
    e.sample("kew_websockets_closed_total", {{"reason", reason}}, num(n));
}

}  // namespace

void LatencyHistogram::observe(double seconds) {
  ++count_;
  sum_ += seconds;
  for (std::size_t i = 0; i < kBounds.size(); ++i) {
    if (seconds <= kBounds[i]) {
      ++counts_[i];
      return;
    }
  }
}

std::string alerts_active_text(const std::vector<AlertEvent>& active) {
  Exposition e;
  write_alerts_active(e, active);
  return e.take();
}

std::string metrics_text(const MetricsSources& s) {
  Exposition e;
  e.family("kew_build_info", "gauge", "kewd's release and source revision (value 1).");
  e.sample("kew_build_info", {{"version", protocol::release()}, {"revision", protocol::revision()}}, 1);
  write_inputs(e, s.inputs);
  if (s.pipeline) write_pipeline(e, *s.pipeline);
  if (s.latency) write_latency(e, *s.latency);
  write_listeners(e, s);
  if (const auto rss = resident_bytes())
    e.single("process_resident_memory_bytes", "gauge", "Resident memory size in bytes.", num(*rss));
  if (const auto fds = open_fds()) e.single("process_open_fds", "gauge", "Number of open file descriptors.", num(*fds));
  e.single("process_start_time_seconds", "gauge", "Start time of the process since the Unix epoch in seconds.",
           s.start_time_unix_s);
  return e.take();
}

std::optional<std::uint64_t> resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages_total = 0, pages_resident = 0;
  if (!(statm >> pages_total >> pages_resident)) return std::nullopt;
  return pages_resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

std::optional<std::uint64_t> open_fds() {
  DIR* dir = ::opendir("/proc/self/fd");
  if (!dir) return std::nullopt;
  std::uint64_t n = 0;
  while (const dirent* entry = ::readdir(dir))
    if (entry->d_name[0] != '.') ++n;
  ::closedir(dir);
  return n - 1;  // the descriptor of the listing itself
}

}  // namespace kew::daemon::http
