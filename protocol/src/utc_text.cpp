#include "kew/protocol/utc_text.hpp"

#include <cmath>
#include <ctime>

#include <fmt/format.h>

namespace kew::protocol {

std::string utc_time_of_day(double utc_s) {
  if (!std::isfinite(utc_s)) return "--:--:--";
  const std::time_t seconds = static_cast<std::time_t>(std::floor(utc_s));
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  return fmt::format("{:02}:{:02}:{:02}Z", tm.tm_hour, tm.tm_min, tm.tm_sec);
}

}  // namespace kew::protocol
