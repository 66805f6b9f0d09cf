#include "text_fields.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace kew::protocol::text {

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

bool parse_double(std::string_view s, double& out) {
  s = trim(s);
  if (s.empty()) return false;
  // from_chars refuses a leading '+', which some CSV writers emit.
  if (s.front() == '+') s.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size()) return false;
  out = value;
  return true;
}

bool parse_finite_double(std::string_view s, double& out) {
  double value = 0;
  if (!parse_double(s, value) || !std::isfinite(value)) return false;
  out = value;
  return true;
}

namespace {
int hex_digit_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}
}  // namespace

bool parse_address(std::string_view text, std::string& id, std::uint32_t& key) {
  text = trim(text);
  const bool non_icao = !text.empty() && text.front() == '~';
  if (non_icao) text.remove_prefix(1);
  if (text.size() != 6) return false;
  std::uint32_t address = 0;
  char canonical[7];
  std::size_t n = 0;
  if (non_icao) canonical[n++] = '~';
  for (const char c : text) {
    const int v = hex_digit_value(c);
    if (v < 0) return false;
    address = (address << 4) | static_cast<std::uint32_t>(v);
    canonical[n++] = "0123456789ABCDEF"[v];
  }
  id.assign(canonical, n);
  key = address | (non_icao ? (1u << 24) : 0u);
  return true;
}

bool parse_icao_address(std::string_view text, std::uint32_t& address) {
  if (text.size() != 6) return false;
  std::uint32_t value = 0;
  for (const char c : text) {
    const int v = hex_digit_value(c);
    if (v < 0) return false;
    value = (value << 4) | static_cast<std::uint32_t>(v);
  }
  address = value;
  return true;
}

bool parse_mode3a(std::string_view text, std::uint16_t& code) {
  text = trim(text);
  if (text.size() != 4) return false;
  unsigned value = 0;
  for (const char c : text) {
    if (c < '0' || c > '7') return false;
    value = (value << 3) | static_cast<unsigned>(c - '0');
  }
  code = static_cast<std::uint16_t>(value);
  return true;
}

std::int64_t days_from_civil(std::int64_t year, unsigned month, unsigned day) {
  // Shift the year to start in March so the leap day is the last day of the year;
  // then a 400-year era has a fixed 146097 days.
  year -= month <= 2 ? 1 : 0;
  const std::int64_t era = (year >= 0 ? year : year - 399) / 400;
  const auto year_of_era = static_cast<std::int64_t>(year - era * 400);
  const std::int64_t month_from_march = month > 2 ? month - 3 : month + 9;
  const std::int64_t day_of_year = (153 * month_from_march + 2) / 5 + day - 1;
  const std::int64_t day_of_era =
      year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
  return era * 146097 + day_of_era - 719468;
}

void clear_report(TrackReport& report) {
  report.t = report.lat_deg = report.lon_deg = report.alt_ft = 0.0;
  report.id.clear();
  report.source.clear();
  report.position_source.clear();
  report.callsign.clear();
  report.gs_kt.reset();
  report.trk_deg.reset();
  report.vr_fpm.reset();
  report.sel_ft.reset();
  report.sel_src = SelectedAltitudeSource::Mcp;
  report.tar_dps.reset();
  report.mode3a.reset();
  report.address.reset();
  report.on_ground = false;
  report.coasting = false;
  report.track_end = false;
}

namespace {

/// See check_report(): one turn either way is a convention, further is no angle.
void bring_track_angle_into_one_turn(std::optional<double>& track) {
  constexpr double kTurn = 360.0;
  if (!track || !(*track >= -kTurn && *track < 2 * kTurn)) return;
  double angle = *track;
  if (angle < 0.0) angle += kTurn;
  // Also a tiny negative angle, whose sum with 360 rounds to exactly 360.
  if (angle >= kTurn) angle -= kTurn;
  track = angle;
}

}  // namespace

LineResult check_report(TrackReport& report) {
  if (report.id.empty()) return problem("bad_id", "empty id");
  if (!std::isfinite(report.t)) return problem("bad_number", "time is not finite");
  if (!std::isfinite(report.lat_deg) || report.lat_deg < -90.0 || report.lat_deg > 90.0)
    return problem("lat_out_of_range", fmt::format("lat {} outside [-90, 90]", report.lat_deg));
  if (!std::isfinite(report.lon_deg) || report.lon_deg < -180.0 || report.lon_deg > 180.0)
    return problem("lon_out_of_range", fmt::format("lon {} outside [-180, 180]", report.lon_deg));
  if (!std::isfinite(report.alt_ft)) return problem("bad_number", "altitude is not finite");
  bring_track_angle_into_one_turn(report.trk_deg);
  return std::nullopt;
}

}  // namespace kew::protocol::text
