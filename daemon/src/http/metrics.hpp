#pragma once
// The Prometheus text exposition (format 0.0.4) of GET /metrics (design §5.8;
// docs/protocol.md "Metrics" lists every metric). This module is the only writer of it:
// the service gathers the figures into MetricsSources, metrics_text() writes them.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"
#include "kew/util/rejections.hpp"

namespace kew::daemon::http {

struct HttpStatistics;

/// Record-to-alert latency (kew_record_to_alert_latency_seconds): a histogram with
/// sub-millisecond buckets.
class LatencyHistogram {
 public:
  static constexpr std::array<double, 12> kBounds{0.00001, 0.000025, 0.00005, 0.0001, 0.00025, 0.0005,
                                                  0.001,   0.0025,   0.005,   0.01,   0.05,    0.25};
  void observe(double seconds);
  const std::array<std::uint64_t, kBounds.size()>& counts() const { return counts_; }  ///< per bucket, not cumulative
  std::uint64_t count() const { return count_; }
  double sum() const { return sum_; }

 private:
  std::array<std::uint64_t, kBounds.size()> counts_{};
  std::uint64_t count_ = 0;
  double sum_ = 0.0;
};

/// One input's figures.
struct InputMetrics {
  std::string name;
  std::uint64_t records = 0;  ///< decoded
  std::uint64_t bytes = 0;
  std::uint64_t datagrams_dropped = 0;  ///< by the kernel before kewd read them (UDP)
  /// Its decoders' refusals and the pipeline's refusals of its records, by reason.
  Rejections rejected;
  std::optional<double> last_record_unix_s;  ///< wall clock of its last decoded record
  /// http inputs: answers taken, "not modified" answers, failed requests.
  struct Polls {
    std::uint64_t taken = 0, unchanged = 0, failed = 0;
  };
  std::optional<Polls> polls;
};

struct MetricsSources {
  const Pipeline* pipeline = nullptr;
  std::vector<InputMetrics> inputs;
  std::uint64_t subscribers = 0;
  std::uint64_t subscriber_queued_bytes = 0;
  protocol::SubscriberStatistics subscriber_figures;
  const HttpStatistics* http = nullptr;
  std::uint64_t http_connections = 0, websockets = 0, websocket_queued_bytes = 0;
  std::optional<std::uint64_t> alert_log_queued_bytes;
  std::optional<std::uint64_t> alert_log_errors;  ///< with an alert log
  /// The health verdict of ALIVE (kew_health); absent leaves the family out.
  std::optional<protocol::HealthReason> health;
  std::optional<protocol::NatsStatistics> nats;  ///< with [nats] url
  std::vector<protocol::NotifyStatistics> notify;  ///< one per [[notify]]
  const LatencyHistogram* latency = nullptr;
  double start_time_unix_s = 0.0;
};

std::string metrics_text(const MetricsSources& sources);
/// The family kew_alerts_active of `active` (the pipeline's snapshot), as metrics_text
/// writes it.
std::string alerts_active_text(const std::vector<AlertEvent>& active);

/// Resident set size of this process (bytes) from /proc/self/statm; nullopt if unknown.
std::optional<std::uint64_t> resident_bytes();
/// Open file descriptors of this process (/proc/self/fd); nullopt if unknown.
std::optional<std::uint64_t> open_fds();

}  // namespace kew::daemon::http
