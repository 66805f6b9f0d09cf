#pragma once
// The alert log (design §5.7): every alert event and acknowledgement of this instance, one
// JSON line each, written per event so that an alert nobody was subscribed to survives a
// crash; while the file cannot take them, events wait in memory (the oldest dropped beyond
// alert_log_queue_bytes) and the file is retried once a second.

#include <string>
#include <string_view>

#include "../service/line_file.hpp"
#include "kew/daemon/config.hpp"
#include "output.hpp"

namespace kew::daemon {

class AlertLogOutput final : public Output {
 public:
  /// Opens (or creates) `config.alert_log`; throws std::exception when it cannot.
  explicit AlertLogOutput(const ServiceConfig& config);

  std::string_view name() const override { return "alert log"; }
  Audience audience() const override { return Audience::Journal; }
  /// The path as resolved (design §5.7: relative to the working directory kewd started in).
  std::string describe() const override { return "alert log: " + file_.path(); }
  void alert(const AlertEvent& event, const SharedLine& line) override;
  void acknowledgement(const protocol::Acknowledgement& ack, std::uint64_t seq, const SharedLine& line) override;
  void alive(const AliveEvent&, const SharedLine&) override {}
  void report(protocol::ServiceStatistics& statistics) const override;

  /// A line this run writes beside the events (its START object).
  void append(std::string_view line);
  /// Once a second: retries a failing file, syncs it (alert_log_sync "interval").
  void housekeeping();
  /// At shutdown: writes what waits and syncs unless alert_log_sync is "none".
  void close();
  bool failing() const { return file_.failing(); }
  const std::string& path() const { return file_.path(); }

 private:
  void write(std::string_view line);

  LineFile file_;
  AlertLogSync sync_;
};

}  // namespace kew::daemon
