#include "notify_output.hpp"

#include <fmt/format.h>

#include "../nats/notify_progress_store.hpp"
#include "../nats/speaking_right.hpp"

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

std::vector<std::unique_ptr<NotifyOutput>> open_notify_outputs(const Config& config, const std::string& state_directory,
                                                               const std::shared_ptr<SpeakingRight>& right) {
  std::vector<std::unique_ptr<NotifyOutput>> outputs;
  for (const NotifyConfig& notify : config.notify) {
    std::unique_ptr<ProgressStore> store;
    std::function<bool()> may_speak;
    if (right) {
      store = std::make_unique<NatsProgressStore>(config.nats, notify.name);
      may_speak = [right] { return right->may_speak(); };
    }
    const std::string outbox =
        state_directory.empty() ? std::string() : state_directory + "/notify-" + notify.name + ".outbox";
    outputs.push_back(std::make_unique<NotifyOutput>(
        std::make_unique<Notifier>(notify, outbox, std::move(store), std::move(may_speak))));
  }
  return outputs;
}

}  // namespace kew::daemon
