#include "feed_silence.hpp"

#include <algorithm>

namespace kew::daemon {

void FeedSilence::source(std::size_t input, SourceState state, Clock::time_point now) {
  const bool was_caught_up = all_caught_up();
  states_.at(input) = state;
  if (!was_caught_up && all_caught_up()) caught_up_since_ = now;
}

std::optional<double> FeedSilence::silent_s(std::optional<double> since_applied_s, Clock::time_point now) const {
  if (!since_applied_s) return std::nullopt;
  if (!all_caught_up()) return 0.0;
  if (!caught_up_since_) return since_applied_s;
  // The time a source was away is not silence: what it sent meanwhile may still come.
  return std::max(0.0, std::min(*since_applied_s, std::chrono::duration<double>(now - *caught_up_since_).count()));
}

bool FeedSilence::unreachable() const {
  return std::ranges::find(states_, SourceState::Unreachable) != states_.end();
}

bool FeedSilence::all_caught_up() const {
  return std::ranges::all_of(states_, [](SourceState s) { return s == SourceState::CaughtUp; });
}

}  // namespace kew::daemon
