#include "readsb_members.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace kew::protocol::text {

namespace {

constexpr std::array<std::string_view, 7> kNestedKeys{
    "alt_geom", "baro_rate", "geom_rate", "squawk", "nav_altitude_mcp", "nav_altitude_fms", "track_rate"};

}  // namespace

// readsb writes "ground" for targets reporting on-ground; adsb_actions also writes
// numbers as strings ("0") in this member. dump1090-mutability's "altitude" likewise.
LineResult read_readsb_altitude(simdjson::dom::element value, std::string_view key, std::optional<double>& out,
                                bool& ground) {
  if (!value.is_string()) return read_number(value, key, out);
  std::optional<std::string_view> word;
  if (LineResult r = read_string(value, key, word)) return r;
  if (*word == "ground") {
    ground = true;
    return std::nullopt;
  }
  double number = 0;
  if (!parse_finite_double(*word, number))
    return problem("bad_number", fmt::format("\"{}\" is neither a number nor \"ground\"", key));
  out = number;
  return std::nullopt;
}

void ReadsbMembers::complete_from(const ReadsbMembers& nested) {
  if (!alt_geom) alt_geom = nested.alt_geom;
  if (!baro_rate) baro_rate = nested.baro_rate;
  if (!geom_rate) geom_rate = nested.geom_rate;
  if (!squawk) squawk = nested.squawk;
  if (!nav_altitude_mcp) nav_altitude_mcp = nested.nav_altitude_mcp;
  if (!nav_altitude_fms) nav_altitude_fms = nested.nav_altitude_fms;
  if (!track_rate) track_rate = nested.track_rate;
}

LineResult read_readsb_member(std::string_view key, simdjson::dom::element value, ReadsbMembers& m) {
  if (key == "now") return read_number(value, key, m.now);
  if (key == "lat") return read_number(value, key, m.lat);
  if (key == "lon") return read_number(value, key, m.lon);
  if (key == "alt_baro") return read_readsb_altitude(value, key, m.alt_baro, m.alt_baro_ground);
  if (key == "alt_geom") return read_number(value, key, m.alt_geom);
  if (key == "gs") return read_number(value, key, m.gs);
  if (key == "gscp") return read_number(value, key, m.gscp);
  if (key == "track") return read_number(value, key, m.track);
  if (key == "baro_rate") return read_number(value, key, m.baro_rate);
  if (key == "geom_rate") return read_number(value, key, m.geom_rate);
  if (key == "nav_altitude_mcp") return read_number(value, key, m.nav_altitude_mcp);
  if (key == "nav_altitude_fms") return read_number(value, key, m.nav_altitude_fms);
  if (key == "track_rate") return read_number(value, key, m.track_rate);
  if (key == "seen_pos") return read_number(value, key, m.seen_pos);
  if (key == "seen") return read_number(value, key, m.seen);
  if (key == "altitude") return read_readsb_altitude(value, key, m.altitude, m.altitude_ground);
  if (key == "speed") return read_number(value, key, m.speed);
  if (key == "vert_rate") return read_number(value, key, m.vert_rate);
  if (key == "hex") return read_string(value, key, m.hex);
  if (key == "flight") return read_string(value, key, m.flight);
  if (key == "type") return read_string(value, key, m.type);
  if (key == "squawk") return read_mode3a(value, key, m.squawk);
  return std::nullopt;
}

LineResult read_flightdict(simdjson::dom::element value, ReadsbMembers& nested) {
  if (value.is_null()) return std::nullopt;
  simdjson::dom::object object;
  if (value.get_object().get(object) != simdjson::SUCCESS)
    return problem("wrong_type", "\"flightdict\" must be an object");
  for (const simdjson::dom::key_value_pair member : object) {
    const std::string_view key = member.key;
    if (std::ranges::find(kNestedKeys, key) != kNestedKeys.end()) {
      if (LineResult r = read_readsb_member(key, member.value, nested)) return r;
    }
  }
  return std::nullopt;
}

LineResult fill_readsb_report(const ReadsbMembers& m, double t, std::string_view source, TrackReport& report) {
  clear_report(report);
  std::uint32_t key = 0;
  if (!parse_address(*m.hex, report.id, key))
    return problem("bad_address", fmt::format("hex \"{}\" is not 6 hex digits", *m.hex));
  report.address = icao_address(key);  // none for '~' (non-ICAO) addresses
  report.source.assign(source);
  report.t = t;
  report.lat_deg = *m.lat;
  report.lon_deg = *m.lon;
  const bool ground = m.alt_baro_ground || (!m.alt_baro && m.altitude_ground);
  const std::optional<double> pressure = m.alt_baro ? m.alt_baro : m.altitude;
  if (ground) {
    report.on_ground = true;
    report.alt_ft = m.alt_geom.value_or(0.0);
  } else if (pressure || m.alt_geom) {
    report.alt_ft = pressure ? *pressure : *m.alt_geom;
  } else {
    return problem("no_altitude", "no alt_baro, altitude or alt_geom");
  }
  report.gs_kt = m.gs ? m.gs : m.gscp ? m.gscp : m.speed;
  report.trk_deg = m.track;
  report.vr_fpm = m.baro_rate ? m.baro_rate : m.geom_rate ? m.geom_rate : m.vert_rate;
  // The MCP/FCU selected altitude when given, else the FMS one (design §5.2). readsb's
  // nav_modes ("vnav"...) would tell which one the aircraft flies to; kew does not
  // guess from them.
  if (m.nav_altitude_mcp) {
    report.sel_ft = m.nav_altitude_mcp;
  } else if (m.nav_altitude_fms) {
    report.sel_ft = m.nav_altitude_fms;
    report.sel_src = SelectedAltitudeSource::Fms;
  }
  report.tar_dps = m.track_rate;
  report.mode3a = m.squawk;
  if (m.type) report.position_source.assign(*m.type);
  if (m.flight) {
    const std::string_view callsign = trim(*m.flight);
    if (callsign != "N/A") report.callsign.assign(callsign);
  }
  return std::nullopt;
}

}  // namespace kew::protocol::text
