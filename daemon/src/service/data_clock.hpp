#pragma once
// kewd's data clock between records (design §4.1 "Live mode", §5.6): the last applied
// record's data time, run on by the feed's silence (FeedSilence) at the wall clock's pace,
// so that the tracks of a silent feed time out and kinetic events fall on time. A replay
// (kewd --replay) runs it at its speed while the file is read and stops it at the file's
// end, so that the last state stays on show; a replay as fast as possible (speed 0)
// leaves it to the records alone, as kew-replay does.

#include <chrono>
#include <cstddef>
#include <optional>

#include "feed_silence.hpp"

namespace kew::daemon {

class DataClock {
 public:
  using Clock = std::chrono::steady_clock;
  struct Pace {
    bool replay = false;  ///< kewd --replay
    double speed = 1.0;   ///< a replay's data seconds per wall second (≥ 0; 0: records alone)
  };

  /// `inputs`: how many inputs may tell their source's state (FeedSilence).
  DataClock(std::size_t inputs, Pace pace) : silence_(inputs), pace_(pace) {}

  /// Input `input` learnt at `now` that its source is `state` (FeedSilence::source).
  void source(std::size_t input, SourceState state, Clock::time_point now) { silence_.source(input, state, now); }
  /// Some source is unreachable (FeedSilence::unreachable).
  bool unreachable() const { return silence_.unreachable(); }
  /// The replayed file ended: the clock stands still from now on.
  void end_of_replay() { replay_ended_ = true; }
  bool replay_ended() const { return replay_ended_; }

  /// The data time (UTC s) at `now`. `last_data_time`: the last applied record's (s);
  /// `since_applied_s`: wall seconds since it was applied (nullopt before the first).
  double at(double last_data_time, std::optional<double> since_applied_s, Clock::time_point now) const;
  /// What the live tick moves the pipeline's clock to at `now`: the data time, once the
  /// feed has been silent (or wholly refused) for at least `tick_s` wall seconds; nullopt
  /// while records drive the clock, or while a replay's clock stands still.
  std::optional<double> tick(double last_data_time, std::optional<double> since_applied_s, Clock::time_point now,
                             double tick_s) const;

 private:
  bool standing_still() const { return pace_.replay && (replay_ended_ || pace_.speed <= 0.0); }

  FeedSilence silence_;
  Pace pace_;
  bool replay_ended_ = false;
};

}  // namespace kew::daemon
