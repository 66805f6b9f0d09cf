#pragma once
// NATS (design §5.9) as an output: alerts to <alerts_subject>.<zone> (conflicts) and
// <alerts_subject>.apw.<zone> (area proximity warnings) and acknowledgements kept in
// JetStream, the status now or never, a TRACKS snapshot at its own interval.

#include <memory>
#include <string>

#include "../nats/nats_publisher.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "output.hpp"

namespace kew::daemon {

/// What follows <alerts_subject>. in an alert's subject: the subject token of the zone
/// that owns a conflict's pair, or "apw." and that of the zone holding an area warning's
/// aircraft ("single" for either without `tiling`, in single-zone mode).
std::string alert_subject_tail(const AlertEvent& event, const std::optional<zone::ZoneTiling>& tiling);

class NatsOutput final : public Output {
 public:
  /// Connects (see NatsPublisher); `pipeline` (its zones name the subjects) outlives it;
  /// `right`: hot standby's right to speak (null without hot standby).
  NatsOutput(const NatsConfig& config, std::string run_id, const Pipeline& pipeline,
             std::shared_ptr<const SpeakingRight> right);

  std::string_view name() const override { return "nats"; }
  Audience audience() const override { return Audience::Shared; }
  std::string describe() const override { return description_; }
  void alert(const AlertEvent& event, const SharedLine& line) override;
  void acknowledgement(const protocol::Acknowledgement& ack, std::uint64_t seq, const SharedLine& line) override;
  void alive(const AliveEvent& alive, const SharedLine& line) override;
  /// Stepping down, what the outbox has not published is the next active's to send.
  void role_changed(bool active) override;
  void report(protocol::ServiceStatistics& statistics) const override;

  /// A TRACKS object (its line) while active.
  void tracks(const std::string& line, std::uint64_t seq);
  /// NatsPublisher::mark_published (a broken future once closed).
  std::future<std::uint64_t> mark_published() {
    if (publisher_) return publisher_->mark_published();
    return std::promise<std::uint64_t>().get_future();
  }
  /// The publisher stops, with the last events given their chance to reach the server.
  void close() { publisher_.reset(); }

 private:
  std::unique_ptr<NatsPublisher> publisher_;
  const Pipeline& pipeline_;
  std::string description_;
  bool hot_standby_;
  bool active_ = true;
};

}  // namespace kew::daemon
