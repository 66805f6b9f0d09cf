#include "alert_log_output.hpp"

#include <spdlog/spdlog.h>

namespace kew::daemon {

AlertLogOutput::AlertLogOutput(const ServiceConfig& config)
    : file_(config.alert_log, config.alert_log_max_bytes, config.alert_log_keep,
            config.alert_log_sync == AlertLogSync::Every, config.alert_log_queue_bytes),
      sync_(config.alert_log_sync) {}

void AlertLogOutput::alert(const AlertEvent&, const SharedLine& line) { write(*line); }

void AlertLogOutput::acknowledgement(const protocol::Acknowledgement&, std::uint64_t, const SharedLine& line) {
  write(*line);
}

void AlertLogOutput::append(std::string_view line) { write(line); }

void AlertLogOutput::write(std::string_view line) {
  file_.append(line);
  // A failing file is retried by housekeeping, once a second: a disk that fails can be
  // slow to say so, and a retry per event would slow the I/O thread with it.
  if (!file_.failing()) file_.flush();
}

void AlertLogOutput::housekeeping() {
  if (file_.failing()) file_.flush();
  if (sync_ == AlertLogSync::Interval) file_.sync();
}

void AlertLogOutput::close() {
  if (!file_.flush())
    spdlog::error("kewd stops with {} bytes of alert events the alert log could not take", file_.pending_bytes());
  if (sync_ != AlertLogSync::None) file_.sync();
}

void AlertLogOutput::report(protocol::ServiceStatistics& statistics) const {
  statistics.alert_log_errors = file_.write_errors();
  statistics.alert_log_queued_bytes = file_.pending_bytes();
  statistics.alert_log_dropped = file_.dropped_lines();
}

}  // namespace kew::daemon
