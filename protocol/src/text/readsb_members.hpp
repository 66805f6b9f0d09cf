#pragma once
// The members of one aircraft as readsb, dump1090-fa and dump1090-mutability name them,
// shared by the readsb JSON-lines decoder (readsb.hpp), the aircraft.json snapshot
// decoder (aircraft_json.hpp) and the trace decoder (readsb_trace.hpp), and the report
// they make. Internal to kew_protocol.

#include <array>
#include <optional>
#include <string_view>

#include "json_object.hpp"

namespace kew::protocol::text {

struct ReadsbMembers {
  std::optional<double> now, lat, lon, alt_baro, alt_geom, gs, gscp, track, baro_rate, geom_rate;
  std::optional<double> nav_altitude_mcp, nav_altitude_fms, track_rate;
  /// Seconds since the position (seen_pos) and since any message (seen) at `now`.
  std::optional<double> seen_pos, seen;
  /// dump1090-mutability's older names: altitude (ft or "ground"), speed (kt), vert_rate
  /// (ft/min); read when the current ones are absent.
  std::optional<double> altitude, speed, vert_rate;
  std::optional<std::string_view> hex, flight, type;
  std::optional<std::uint16_t> squawk;
  bool alt_baro_ground = false;
  bool altitude_ground = false;

  /// Fills what this (top-level) set lacks from `nested` (adsb_actions' "flightdict").
  void complete_from(const ReadsbMembers& nested);
};

/// An altitude in feet, or readsb's string "ground" (`ground` set, `out` untouched), or
/// a number written as a string (adsb_actions' "0"); null → nullopt.
LineResult read_readsb_altitude(simdjson::dom::element value, std::string_view key, std::optional<double>& out,
                                bool& ground);

/// Reads member `key` into `m` when it is one of ReadsbMembers' (unknown keys: nothing).
LineResult read_readsb_member(std::string_view key, simdjson::dom::element value, ReadsbMembers& m);

/// The members a flightdict may supply (ReadsbMembers::complete_from), read from it.
LineResult read_flightdict(simdjson::dom::element value, ReadsbMembers& nested);

/// The report of `m` at data time `t` (UTC s) from `source` into `report` (cleared
/// first); hex, lat and lon must be present. A problem for a bad address or no altitude.
LineResult fill_readsb_report(const ReadsbMembers& m, double t, std::string_view source, TrackReport& report);

}  // namespace kew::protocol::text
