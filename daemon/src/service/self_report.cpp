#include "self_report.hpp"

#include <chrono>

#include "../http/metrics.hpp"
#include "../standby/pair_member.hpp"

namespace kew::daemon {

protocol::ServiceStatistics gather_statistics(const ReportedParts& parts) {
  protocol::ServiceStatistics service;
  service.seq = parts.last_alert_seq;
  service.uptime_s = parts.status.uptime_s(std::chrono::steady_clock::now());
  for (const auto& input : parts.inputs) service.inputs.push_back(input->statistics());
  parts.fan_out.report(service);
  if (parts.pair && service.nats) parts.pair->report(*service.nats);
  parts.intake.report(service);
  service.resident_bytes = http::resident_bytes();
  return service;
}

std::string gather_metrics(const ReportedParts& parts) {
  http::MetricsSources m;
  m.pipeline = &parts.pipeline;
  const protocol::ServiceStatistics service = gather_statistics(parts);
  for (std::size_t i = 0; i < service.inputs.size(); ++i) {
    const protocol::InputStatistics& in = service.inputs[i];
    const RecordIntake::InputFigures& figures = parts.intake.figures(i);
    http::InputMetrics metrics{in.name, in.reports, in.bytes, in.datagrams_dropped, in.rejected,
                               figures.last_record_unix_s, std::nullopt};
    metrics.rejected.merge(figures.pipeline_refused);
    if (parts.inputs[i]->config().transport == Transport::Http)
      metrics.polls = http::InputMetrics::Polls{in.polls, in.polls_unchanged, in.poll_failures};
    m.inputs.push_back(std::move(metrics));
  }
  m.subscribers = parts.subscribers.sessions();
  m.subscriber_queued_bytes = parts.subscribers.queued_bytes();
  m.subscriber_figures = service.subscribers;
  if (parts.http) {
    m.http = &parts.http->statistics();
    m.http_connections = parts.http->connections();
    m.websockets = parts.http->websockets();
    m.websocket_queued_bytes = parts.http->queued_bytes();
  }
  m.alert_log_queued_bytes = service.alert_log_queued_bytes;
  m.alert_log_errors = service.alert_log_errors;
  m.health = parts.status.health(std::chrono::steady_clock::now(), parts.conditions);
  m.nats = service.nats;
  m.notify = service.notify;
  m.latency = &parts.intake.latency();
  m.start_time_unix_s = parts.status.started_unix_s();
  return http::metrics_text(m);
}

}  // namespace kew::daemon
