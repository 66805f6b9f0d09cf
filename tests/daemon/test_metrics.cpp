// The exposition of GET /metrics (daemon/src/http/metrics.hpp, docs/protocol.md
// "Metrics"): the health verdict as one kew_health sample per reason, and the alert log's
// error counter, each only when the service gives it.

#include <gtest/gtest.h>

#include <string>

#include "metrics.hpp"

namespace kew::daemon::http {
namespace {

TEST(Metrics, HealthIsOneSamplePerReasonWithTheCurrentOneSet) {
  MetricsSources sources;
  sources.health = protocol::HealthReason::FeedStale;
  const std::string text = metrics_text(sources);
  EXPECT_NE(text.find("# TYPE kew_health gauge\n"), std::string::npos) << text;
  for (const auto& [reason, name] : protocol::kHealthReasonNames.entries()) {
    const std::string sample = "kew_health{reason=\"" + std::string(name) + "\"} " +
                               (reason == protocol::HealthReason::FeedStale ? "1" : "0") + "\n";
    EXPECT_NE(text.find(sample), std::string::npos) << sample << text;
  }
}

TEST(Metrics, AlertLogErrorsAndHealthOnlyWhenGiven) {
  MetricsSources sources;
  std::string text = metrics_text(sources);
  EXPECT_EQ(text.find("kew_health"), std::string::npos);
  EXPECT_EQ(text.find("kew_alert_log_errors_total"), std::string::npos);
  sources.alert_log_errors = 3;
  text = metrics_text(sources);
  EXPECT_NE(text.find("# TYPE kew_alert_log_errors_total counter\nkew_alert_log_errors_total 3\n"), std::string::npos)
      << text;
}

}  // namespace
}  // namespace kew::daemon::http
