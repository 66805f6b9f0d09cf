#include "kew/volume/watched_volume.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include "kew/util/wildcard.hpp"

namespace kew::volume {

namespace {

constexpr std::array<std::string_view, 7> kDays{"mon", "tue", "wed", "thu", "fri", "sat", "sun"};

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::optional<int> day_index(std::string_view name) {
  const auto it = std::find(kDays.begin(), kDays.end(), lower(name));
  if (it == kDays.end()) return std::nullopt;
  return static_cast<int>(it - kDays.begin());
}

/// "Mon-Fri", "Sat,Sun", "Mon", "daily" as a day mask.
std::optional<std::uint8_t> parse_days(std::string_view text) {
  if (lower(text) == "daily") return std::uint8_t{0x7f};
  std::uint8_t mask = 0;
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    const std::string_view part = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    const std::size_t dash = part.find('-');
    const auto first = day_index(part.substr(0, dash));
    const auto last = dash == std::string_view::npos ? first : day_index(part.substr(dash + 1));
    if (!first || !last) return std::nullopt;
    // A range wraps round the week: "Sat-Mon" is Saturday, Sunday and Monday.
    for (int d = *first;; d = (d + 1) % 7) {
      mask = static_cast<std::uint8_t>(mask | (1u << d));
      if (d == *last) break;
    }
  }
  return mask == 0 ? std::nullopt : std::optional(mask);
}

/// "0600" or "06:00" as minutes after midnight; 2400 allowed (`end`).
std::optional<int> parse_time(std::string_view text, bool end) {
  std::string digits;
  for (const char c : text)
    if (c != ':') digits.push_back(c);
  if (digits.size() != 4 || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  const int hours = std::stoi(digits.substr(0, 2)), minutes = std::stoi(digits.substr(2));
  if (minutes > 59 || hours > 24 || (hours == 24 && (minutes != 0 || !end))) return std::nullopt;
  return hours * 60 + minutes;
}

}  // namespace

std::optional<WeeklySchedule> WeeklySchedule::parse(const std::vector<std::string>& entries, std::string& error) {
  WeeklySchedule schedule;
  for (const std::string& entry : entries) {
    const std::size_t space = entry.find(' ');
    const std::string_view days = std::string_view(entry).substr(0, space);
    const std::string_view times = space == std::string::npos ? std::string_view() : std::string_view(entry).substr(space + 1);
    const std::size_t dash = times.find('-');
    const auto mask = parse_days(days);
    const auto start = dash == std::string_view::npos ? std::nullopt : parse_time(times.substr(0, dash), false);
    const auto end = dash == std::string_view::npos ? std::nullopt : parse_time(times.substr(dash + 1), true);
    if (!mask || !start || !end) {
      error = "\"" + entry + "\" is not DAYS HHMM-HHMM (days Mon … Sun, ranges \"Mon-Fri\", lists \"Sat,Sun\" or "
              "\"daily\"; times UTC)";
      return std::nullopt;
    }
    schedule.windows_.push_back({*mask, *start, *end});
  }
  return schedule;
}

bool WeeklySchedule::active_at(double utc_s) const {
  if (windows_.empty()) return true;
  const double days_since_epoch = std::floor(utc_s / 86400.0);
  // 1970-01-01 was a Thursday (index 3, Monday = 0).
  const int today = static_cast<int>(std::fmod(days_since_epoch + 3.0, 7.0) + 7.0) % 7;
  const int yesterday = (today + 6) % 7;
  const double minute = (utc_s - days_since_epoch * 86400.0) / 60.0;
  for (const WeeklyWindow& w : windows_) {
    const bool overnight = w.end_min <= w.start_min;
    if ((w.days >> today & 1u) && minute >= w.start_min && (overnight || minute < w.end_min)) return true;
    if (overnight && (w.days >> yesterday & 1u) && minute < w.end_min) return true;
  }
  return false;
}

bool TrafficFilter::concerns(std::string_view id, std::string_view callsign, std::optional<std::uint16_t> squawk) const {
  if (everyone()) return true;
  for (const std::string& pattern : callsigns)
    if (!callsign.empty() && util::matches_wildcard(pattern, callsign)) return true;
  for (const std::string& pattern : addresses)
    if (util::matches_wildcard(pattern, id)) return true;
  return squawk && std::find(squawks.begin(), squawks.end(), *squawk) != squawks.end();
}

}  // namespace kew::volume
