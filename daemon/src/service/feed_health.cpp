#include "feed_health.hpp"

namespace kew::daemon {

void FeedHealth::sample(std::uint64_t offered, std::uint64_t accepted, std::uint64_t input_losses) {
  history_[samples_ % history_.size()] = {offered, accepted, input_losses};
  ++samples_;
}

protocol::HealthReason FeedHealth::reason(Clock::time_point now) const {
  using protocol::HealthReason;
  const std::optional<double> age = seconds_since_accepted(now);
  if (!age) return HealthReason::NoData;
  if (*age > stale_after_s_) return HealthReason::FeedStale;
  if (samples_ >= 2) {
    const std::size_t span = samples_ - 1 < kWindow ? samples_ - 1 : kWindow;
    const Totals& newest = history_[(samples_ - 1) % history_.size()];
    const Totals& oldest = history_[(samples_ - 1 - span) % history_.size()];
    const std::uint64_t offered = newest.offered - oldest.offered;
    const std::uint64_t accepted = newest.accepted - oldest.accepted;
    if (offered >= kMinOffered && 2 * accepted < offered) return HealthReason::RecordsRefused;
  }
  if (samples_ >= 1) {
    // Counted from zero at the start: a loss before the first sample counts too.
    const std::uint64_t losses_before =
        samples_ > kWindow ? history_[(samples_ - 1 - kWindow) % history_.size()].input_losses : 0;
    if (history_[(samples_ - 1) % history_.size()].input_losses > losses_before) return HealthReason::InputDropping;
  }
  return HealthReason::Healthy;
}

std::optional<double> FeedHealth::seconds_since_accepted(Clock::time_point now) const {
  if (!last_accepted_) return std::nullopt;
  return std::chrono::duration<double>(now - *last_accepted_).count();
}

}  // namespace kew::daemon
