#include <array>
#include <charconv>
#include <cmath>
#include <numbers>

#include "bytes.hpp"
#include "record_context.hpp"

namespace kew::protocol::asterix {

namespace {

/// ICAO 6-bit character codes: 1-26 letters, 32 space, 48-57 digits; '\0' marks a code
/// outside the set. Code 0 is read as a space: some encoders pad with it.
constexpr std::array<char, 64> kIcaoCharacters = [] {
  std::array<char, 64> table{};
  table[0] = ' ';
  for (int i = 1; i <= 26; ++i) table[static_cast<std::size_t>(i)] = static_cast<char>('A' + i - 1);
  table[32] = ' ';
  for (int i = 48; i <= 57; ++i) table[static_cast<std::size_t>(i)] = static_cast<char>('0' + i - 48);
  return table;
}();

void trim_spaces(std::string& text) {
  const auto first = text.find_first_not_of(' ');
  if (first == std::string::npos) {
    text.clear();
    return;
  }
  text.erase(text.find_last_not_of(' ') + 1);
  text.erase(0, first);
}

}  // namespace

void reset_report(TrackReport& report) {
  report.t = 0;
  report.id.clear();
  report.source.clear();
  report.lat_deg = 0;
  report.lon_deg = 0;
  report.alt_ft = 0;
  report.gs_kt.reset();
  report.trk_deg.reset();
  report.vr_fpm.reset();
  report.sel_ft.reset();
  report.sel_src = SelectedAltitudeSource::Mcp;
  report.tar_dps.reset();
  report.callsign.clear();
  report.mode3a.reset();
  report.address.reset();
  report.on_ground = false;
  report.coasting = false;
  report.track_end = false;
}

bool set_time_of_day(const std::uint8_t* tod, RecordContext& context, TrackReport& report) {
  const double seconds = be24(tod) / 128.0;
  if (seconds >= kSecondsPerDay) {
    context.rejections.reject("asterix_bad_time_of_day", "time of day at or beyond 24:00:00");
    return false;
  }
  report.t = context.clock.to_utc(seconds);
  return true;
}

void set_source(std::string_view category, const std::uint8_t* sac_sic, TrackReport& report) {
  // "cat062/255.255" fits the small-string buffer: no allocation.
  std::array<char, 8> number{};
  report.source.assign(category);
  report.source.push_back('/');
  report.source.append(number.data(), std::to_chars(number.data(), number.data() + number.size(), sac_sic[0]).ptr);
  report.source.push_back('.');
  report.source.append(number.data(), std::to_chars(number.data(), number.data() + number.size(), sac_sic[1]).ptr);
}

void set_address_id(std::uint32_t address, TrackReport& report) {
  constexpr char kHex[] = "0123456789ABCDEF";
  std::array<char, 6> text{};
  for (int i = 5; i >= 0; --i) {
    text[static_cast<std::size_t>(i)] = kHex[address & 0xF];
    address >>= 4;
  }
  report.id.assign(text.data(), text.size());
}

void set_track_number_id(std::uint32_t track_number, TrackReport& report) {
  std::array<char, 12> text{};
  const auto result = std::to_chars(text.data(), text.data() + text.size(), track_number);
  report.id.assign(text.data(), result.ptr);
}

bool decode_icao_characters(const std::uint8_t* six_bytes, std::string& out) {
  out.clear();
  const std::uint64_t bits = (std::uint64_t{be24(six_bytes)} << 24) | be24(six_bytes + 3);
  for (int shift = 42; shift >= 0; shift -= 6) {
    const char c = kIcaoCharacters[(bits >> shift) & 0x3F];
    if (c == 0) {
      out.clear();
      return false;
    }
    out.push_back(c);
  }
  trim_spaces(out);
  return !out.empty();
}

bool decode_ascii_characters(std::span<const std::uint8_t> chars, std::string& out) {
  out.clear();
  for (const std::uint8_t c : chars) {
    if (c < 0x20 || c > 0x7E) {
      out.clear();
      return false;
    }
    out.push_back(static_cast<char>(c));
  }
  trim_spaces(out);
  return !out.empty();
}

void set_velocity_from_cartesian(double vx_ms, double vy_ms, TrackReport& report) {
  report.gs_kt = std::hypot(vx_ms, vy_ms) * kKnotsPerMetrePerSecond;
  double track = std::atan2(vx_ms, vy_ms) * 180.0 / std::numbers::pi;
  if (track < 0) track += 360.0;
  if (track >= 360.0) track -= 360.0;
  report.trk_deg = track;
}

void set_selected_altitude(std::span<const std::uint8_t> selected,
                           std::span<const std::uint8_t> final_state, TrackReport& report) {
  constexpr double kAltitudeLsbFt = 25.0;
  if (selected.size() == 2) {
    const std::uint32_t word = be16(selected.data());
    const bool source_given = (word & 0x8000) != 0;  // SAS
    const std::uint32_t source = (word >> 13) & 0x3;  // 0 unknown, 1 aircraft altitude
    if (source_given && (source == 2 || source == 3)) {
      report.sel_ft = sign_extend(word, 13) * kAltitudeLsbFt;
      report.sel_src = source == 3 ? SelectedAltitudeSource::Fms : SelectedAltitudeSource::Mcp;
      return;
    }
  }
  if (final_state.size() == 2) {
    report.sel_ft = sign_extend(be16(final_state.data()), 13) * kAltitudeLsbFt;
    report.sel_src = SelectedAltitudeSource::Mcp;
  }
}

void set_turn_indicator_rate(std::span<const std::uint8_t> field, TrackReport& report) {
  constexpr double kRateLsbDps = 0.25;
  if (field.size() < 2 || (field[0] >> 6) == 0) return;
  report.tar_dps = sign_extend(field[1] >> 1, 7) * kRateLsbDps;
}

bool accept_position(RecordContext& context, const TrackReport& report) {
  const bool ok = std::isfinite(report.lat_deg) && std::isfinite(report.lon_deg) &&
                  std::fabs(report.lat_deg) <= 90.0 && std::fabs(report.lon_deg) <= 180.0;
  if (!ok) context.rejections.reject("asterix_position_out_of_range", "latitude/longitude out of range");
  return ok;
}

}  // namespace kew::protocol::asterix
