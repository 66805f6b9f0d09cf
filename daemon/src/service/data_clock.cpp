#include "data_clock.hpp"

namespace kew::daemon {

double DataClock::at(double last_data_time, std::optional<double> since_applied_s, Clock::time_point now) const {
  if (standing_still()) return last_data_time;
  const double silent = silence_.silent_s(since_applied_s, now).value_or(0.0);
  return last_data_time + silent * (pace_.replay ? pace_.speed : 1.0);
}

std::optional<double> DataClock::tick(double last_data_time, std::optional<double> since_applied_s,
                                      Clock::time_point now, double tick_s) const {
  if (standing_still()) return std::nullopt;
  // While records are accepted, their own times drive the clock.
  const std::optional<double> silent = silence_.silent_s(since_applied_s, now);
  if (!silent || *silent < tick_s) return std::nullopt;
  return at(last_data_time, since_applied_s, now);
}

}  // namespace kew::daemon
