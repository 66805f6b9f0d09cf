#pragma once
// One OpenSky state vector in kew's units, and the report it makes: shared by the
// traffic library's JSON (opensky-json) and the OpenSky REST API's responses
// (opensky-rest), which name and scale the same fields differently (opensky.hpp,
// opensky_rest.hpp). Internal to kew_protocol.

#include <cstdint>
#include <optional>
#include <string_view>

#include "text_fields.hpp"

namespace kew::protocol::text {

struct OpenskyState {
  std::optional<double> latitude, longitude;
  /// Barometric and geometric altitude (ft), ground speed (kt), track (deg), vertical
  /// rate (ft/min).
  std::optional<double> altitude, geoaltitude, groundspeed, track, vertical_rate;
  std::optional<std::string_view> icao24, callsign;
  std::optional<bool> onground;
  std::optional<std::uint16_t> squawk;
};

/// The report of `s` at data time `t` (UTC s) into `report` (cleared first; source
/// "opensky", id the upper-case icao24, address its number). Problems: missing_field (no
/// icao24), no_position, no_altitude (neither altitude), bad_address; the caller still
/// passes the report through check_report().
LineResult fill_opensky_report(const OpenskyState& s, double t, TrackReport& report);

}  // namespace kew::protocol::text
