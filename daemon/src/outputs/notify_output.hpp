#pragma once
// A [[notify]] endpoint as one of kewd's outputs (design §5.10). It takes every alert
// event, active or standby, as the alert log does (its outbox is this instance's record
// of what is owed), and its notifier delivers only while this instance is active.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "../notify/notifier.hpp"
#include "kew/daemon/config.hpp"
#include "output.hpp"

namespace kew::daemon {

class SpeakingRight;

class NotifyOutput final : public Output {
 public:
  explicit NotifyOutput(std::unique_ptr<Notifier> notifier);

  std::string_view name() const override { return "notify"; }
  Audience audience() const override { return Audience::Journal; }
  std::string describe() const override;
  void alert(const AlertEvent& event, const SharedLine& line) override;
  void acknowledgement(const protocol::Acknowledgement&, std::uint64_t, const SharedLine&) override {}
  void alive(const AliveEvent&, const SharedLine&) override {}
  void role_changed(bool active) override;
  void report(protocol::ServiceStatistics& statistics) const override;

  bool failing() const { return notifier_->figures().failing; }
  /// At shutdown, before the service's thread ends.
  void close() { notifier_->stop(); }

 private:
  std::unique_ptr<Notifier> notifier_;
};

/// One output per [[notify]] endpoint of `config`, each with its outbox in
/// `state_directory` ("": none, what is owed kept in memory). With hot standby (`right`
/// set), the delivery progress is the pair's, in its NATS key-value bucket, and a notifier
/// delivers only while this instance may speak.
std::vector<std::unique_ptr<NotifyOutput>> open_notify_outputs(const Config& config, const std::string& state_directory,
                                                               const std::shared_ptr<SpeakingRight>& right);

}  // namespace kew::daemon
