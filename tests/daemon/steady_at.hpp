#pragma once
// The steady clock's time point `s` seconds after its epoch: the instants of the tests of
// the live tick's rules (FeedSilence, DataClock), which take time points, not the clock.

#include <chrono>

namespace kew::daemon::test {

inline std::chrono::steady_clock::time_point at(double s) {
  using Clock = std::chrono::steady_clock;
  return Clock::time_point{} + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace kew::daemon::test
