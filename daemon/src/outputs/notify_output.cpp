#include "notify_output.hpp"

#include <fmt/format.h>

namespace kew::daemon {

NotifyOutput::NotifyOutput(std::unique_ptr<Notifier> notifier) : notifier_(std::move(notifier)) {}

std::string NotifyOutput::describe() const {
  const NotifyConfig& c = notifier_->config();
  return fmt::format("notify {}: template {}, {} and above", c.name, to_string(c.format), to_string(c.min_severity));
}

void NotifyOutput::alert(const AlertEvent& event, const SharedLine& line) { notifier_->alert(event, *line); }

void NotifyOutput::role_changed(bool active) { notifier_->set_active(active); }

void NotifyOutput::report(protocol::ServiceStatistics& statistics) const {
  const NotifierFigures f = notifier_->figures();
  statistics.notify.push_back({notifier_->config().name, f.delivered, f.failures, f.dropped, f.queued, f.failing});
}

}  // namespace kew::daemon
