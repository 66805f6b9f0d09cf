#include "kew/protocol/asterix/day_clock.hpp"

#include <cmath>

namespace kew::protocol::asterix {

namespace {
constexpr double kHalfDay = kSecondsPerDay / 2;
}

double DayClock::to_utc(double tod_s) {
  if (capture_utc_) {
    const double capture = *capture_utc_;
    double t = std::floor(capture / kSecondsPerDay) * kSecondsPerDay + tod_s;
    if (t - capture > kHalfDay) t -= kSecondsPerDay;
    if (capture - t > kHalfDay) t += kSecondsPerDay;
    return t;
  }
  if (latest_tod_) {
    if (tod_s < *latest_tod_ - kHalfDay) {
      day_start_ += kSecondsPerDay;
    } else if (tod_s > *latest_tod_ + kHalfDay) {
      return day_start_ - kSecondsPerDay + tod_s;
    }
  }
  latest_tod_ = tod_s;
  return day_start_ + tod_s;
}

}  // namespace kew::protocol::asterix
