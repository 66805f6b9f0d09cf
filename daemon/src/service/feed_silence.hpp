#pragma once
// How long kewd's feed has been silent, as the live tick counts it (design §4.1 "Live
// mode", §5.9). The tick moves the data clock on by this silence so that the tracks of a
// dead feed time out. A source that is unreachable or still delivering a backlog is not
// silent: its records are on their way, dated before the wall clock's "now", and moving
// the clock past them would make them too late. So the silence is nothing while any
// source is behind or unreachable, and counts from the later of the last applied record
// and the moment the last source caught up.

#include <chrono>
#include <cstddef>
#include <optional>
#include <vector>

#include "source_state.hpp"

namespace kew::daemon {

class FeedSilence {
 public:
  using Clock = std::chrono::steady_clock;

  /// `inputs`: how many inputs may tell their source's state; each starts caught up.
  explicit FeedSilence(std::size_t inputs) : states_(inputs, SourceState::CaughtUp) {}

  /// Input `input` (< inputs) learnt at `now` that its source is `state`.
  void source(std::size_t input, SourceState state, Clock::time_point now);

  /// Seconds (≥ 0) the live tick may add to the last record's data time at `now`, given
  /// `since_applied_s`, the wall seconds since a record was last applied (nullopt before
  /// the first: nullopt). 0 while a source is behind or unreachable.
  std::optional<double> silent_s(std::optional<double> since_applied_s, Clock::time_point now) const;

  /// Some source is unreachable: the feed's state is unknown, not quiet.
  bool unreachable() const;

 private:
  bool all_caught_up() const;

  std::vector<SourceState> states_;
  /// When the last source that was behind or unreachable caught up; nullopt if none ever was.
  std::optional<Clock::time_point> caught_up_since_;
};

}  // namespace kew::daemon
