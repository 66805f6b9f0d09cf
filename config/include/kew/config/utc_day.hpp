#pragma once
// Calendar days in configuration values (the data day of ASTERIX time of day).

#include <optional>
#include <string_view>

namespace kew::config {

/// "YYYY-MM-DD" (proleptic Gregorian, month 1–12, day 1–31) → UTC seconds of that
/// midnight since the Unix epoch; nullopt when malformed.
std::optional<double> parse_utc_day(std::string_view text);

}  // namespace kew::config
