#pragma once
// The wall clock as kew's documents and records date it: seconds since 1970-01-01 00:00:00
// UTC (Unix time, leap seconds not counted), from the system clock. The one place that
// reads it, so that every "now" a document states is the same kind of number. The data
// clock of a feed is a different clock (the time of its records); durations and timers use
// std::chrono::steady_clock, which a clock step cannot move.

#include <chrono>

namespace kew::util {

/// Now on the system clock, Unix seconds with the clock's resolution (ns on Linux).
inline double unix_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace kew::util
