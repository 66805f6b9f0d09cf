#include "kew/config/aip_coordinates.hpp"

#include <cctype>
#include <cmath>

#include <fmt/format.h>

namespace kew::config {

namespace {

bool separator(char c) { return c == '-' || c == ',' || std::isspace(static_cast<unsigned char>(c)); }

// One angle "DDMMSS.s" + hemisphere with `degree_digits` digits of degrees, in degrees;
// nullopt with `why` when it is not one.
std::optional<double> angle(std::string_view word, int degree_digits, char positive, char negative, double limit,
                            std::string& why) {
  if (word.empty()) {
    why = "missing";
    return std::nullopt;
  }
  const char hemisphere = static_cast<char>(std::toupper(static_cast<unsigned char>(word.back())));
  if (hemisphere != positive && hemisphere != negative) {
    why = fmt::format("\"{}\" does not end in {} or {}", word, positive, negative);
    return std::nullopt;
  }
  const std::string_view number = word.substr(0, word.size() - 1);
  const std::size_t point = number.find('.');
  const std::string_view whole = number.substr(0, point);
  const std::string_view fraction = point == std::string_view::npos ? std::string_view() : number.substr(point + 1);
  const auto digits = [](std::string_view s) {
    for (const char c : s)
      if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    return true;
  };
  const auto size = static_cast<std::size_t>(degree_digits);
  const bool seconds = whole.size() == size + 4;
  if (!digits(whole) || !digits(fraction) || !(seconds || whole.size() == size + 2) ||
      (point != std::string_view::npos && fraction.empty())) {
    why = fmt::format("\"{}\" is not {}MMSS{} (or {}MM) with {}/{}", word, std::string(size, 'D'),
                      "[.s]", std::string(size, 'D'), positive, negative);
    return std::nullopt;
  }
  const auto value = [](std::string_view s) { return std::stod(std::string(s)); };
  const double degrees = value(whole.substr(0, size));
  const double minutes = value(whole.substr(size, 2));
  double secs = seconds ? value(whole.substr(size + 2, 2)) : 0.0;
  if (!fraction.empty()) {
    if (!seconds) {
      why = fmt::format("\"{}\": a fraction belongs to the seconds", word);
      return std::nullopt;
    }
    secs += value("0." + std::string(fraction));
  }
  if (minutes >= 60.0 || secs >= 60.0) {
    why = fmt::format("\"{}\": minutes and seconds are below 60", word);
    return std::nullopt;
  }
  const double deg = degrees + minutes / 60.0 + secs / 3600.0;
  if (deg > limit) {
    why = fmt::format("\"{}\" is beyond {}°", word, limit);
    return std::nullopt;
  }
  return hemisphere == negative ? -deg : deg;
}

}  // namespace

std::optional<std::vector<geo::GeodeticPosition>> parse_aip_coordinates(std::string_view text, std::string& error) {
  std::vector<std::string_view> words;
  for (std::size_t i = 0; i < text.size();) {
    while (i < text.size() && separator(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !separator(text[i])) ++i;
    if (i > start) words.push_back(text.substr(start, i - start));
  }
  std::vector<geo::GeodeticPosition> out;
  for (std::size_t w = 0; w < words.size(); w += 2) {
    const std::size_t n = out.size() + 1;
    std::string why;
    const std::optional<double> lat = angle(words[w], 2, 'N', 'S', 90.0, why);
    if (!lat) {
      error = fmt::format("position {}: latitude {}", n, why);
      return std::nullopt;
    }
    const std::optional<double> lon = angle(w + 1 < words.size() ? words[w + 1] : std::string_view(), 3, 'E', 'W', 180.0, why);
    if (!lon) {
      error = fmt::format("position {}: longitude {}", n, why);
      return std::nullopt;
    }
    out.push_back({*lat, *lon});
  }
  if (out.size() > 1 && out.front().lat_deg == out.back().lat_deg && out.front().lon_deg == out.back().lon_deg)
    out.pop_back();
  return out;
}

}  // namespace kew::config
