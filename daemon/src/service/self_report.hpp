#pragma once
// What kewd reports of itself beyond the pipeline (design §5.8, §6.6): the service part
// of the STATS object (?STATS, GET /api/status) and the Prometheus exposition (/metrics),
// each gathered from the parts that count at the moment it is asked for.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "../http/http_server.hpp"
#include "../inputs/inputs.hpp"
#include "../outputs/fan_out.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"
#include "record_intake.hpp"
#include "service_status.hpp"
#include "subscribers.hpp"

namespace kew::daemon {

class PairMember;

/// The service's parts as they stand; every reference outlives the call it is passed to.
struct ReportedParts {
  const Pipeline& pipeline;
  const ServiceStatus& status;
  ServiceStatus::Conditions conditions;
  std::uint64_t last_alert_seq;
  const std::vector<std::unique_ptr<Input>>& inputs;
  const RecordIntake& intake;
  const FanOut& fan_out;
  const SubscriberServer& subscribers;
  const PairMember* pair = nullptr;         ///< hot standby only
  const http::HttpServer* http = nullptr;   ///< [http] enabled only
};

/// The STATS object's service part: seq, uptime, inputs, outputs, standby, intake, memory.
protocol::ServiceStatistics gather_statistics(const ReportedParts& parts);
/// The /metrics exposition (Prometheus text format 0.0.4).
std::string gather_metrics(const ReportedParts& parts);

}  // namespace kew::daemon
