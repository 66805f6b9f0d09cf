// The exposition of GET /metrics (daemon/src/http/metrics.hpp, docs/protocol.md
// "Metrics"): the health verdict as one kew_health sample per reason, the alert log's
// error counter, each only when the service gives it, and the active alerts by severity
// and kind.

#include <gtest/gtest.h>

#include <string>
#include <vector>

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

TEST(Metrics, ActiveAlertsBySeverityAndKind) {
  std::vector<AlertEvent> active(4);
  active[0].severity = Severity::Warning;
  active[1].severity = Severity::Warning;
  active[2].severity = Severity::Loss;
  active[2].kind = AlertKind::Apw;
  active[3].severity = Severity::Caution;
  active[3].kind = AlertKind::Apw;
  const std::string text = alerts_active_text(active);
  EXPECT_EQ(text.rfind("# HELP kew_alerts_active ", 0), 0u) << text;
  EXPECT_NE(text.find("# TYPE kew_alerts_active gauge\n"), std::string::npos) << text;
  for (const char* sample : {"kew_alerts_active{severity=\"caution\",kind=\"stca\"} 0\n",
                             "kew_alerts_active{severity=\"warning\",kind=\"stca\"} 2\n",
                             "kew_alerts_active{severity=\"loss\",kind=\"stca\"} 0\n",
                             "kew_alerts_active{severity=\"caution\",kind=\"apw\"} 1\n",
                             "kew_alerts_active{severity=\"warning\",kind=\"apw\"} 0\n",
                             "kew_alerts_active{severity=\"loss\",kind=\"apw\"} 1\n"})
    EXPECT_NE(text.find(sample), std::string::npos) << sample << text;
}

}  // namespace
}  // namespace kew::daemon::http
