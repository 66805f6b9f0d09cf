#include "opensky_state.hpp"

#include <fmt/format.h>

namespace kew::protocol::text {

LineResult fill_opensky_report(const OpenskyState& s, double t, TrackReport& report) {
  if (!s.icao24) return problem("missing_field", "no \"icao24\"");
  if (!s.latitude || !s.longitude) return problem("no_position", "no latitude/longitude");
  if (!s.altitude && !s.geoaltitude) return problem("no_altitude", "no altitude");
  clear_report(report);
  std::uint32_t key = 0;
  if (!parse_address(*s.icao24, report.id, key)) return problem("bad_address", fmt::format("icao24 \"{}\"", *s.icao24));
  report.address = icao_address(key);
  report.source = "opensky";
  report.t = t;
  report.lat_deg = *s.latitude;
  report.lon_deg = *s.longitude;
  report.alt_ft = s.altitude ? *s.altitude : *s.geoaltitude;
  report.gs_kt = s.groundspeed;
  report.trk_deg = s.track;
  report.vr_fpm = s.vertical_rate;
  report.callsign.assign(trim(s.callsign.value_or(std::string_view{})));
  report.on_ground = s.onground.value_or(false);
  report.mode3a = s.squawk;
  return std::nullopt;
}

}  // namespace kew::protocol::text
