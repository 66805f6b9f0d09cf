#pragma once
// The two clocks kew reads, each read in one place.
// - The wall clock, as kew's documents and records date it: seconds since 1970-01-01
//   00:00:00 UTC (Unix time, leap seconds not counted), from the system clock.
// - The steady clock, for durations, back-off and timers: a clock step cannot move it;
//   its epoch is arbitrary (the boot on Linux), so only differences mean anything.
// The data clock of a feed is neither: it is the time of its records.

#include <chrono>

namespace kew::util {

/// Now on the system clock, Unix seconds with the clock's resolution (ns on Linux).
inline double unix_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

/// Now on the steady clock, seconds since its epoch; compare only with other readings.
inline double steady_now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace kew::util
