#pragma once
// Decoder of readsb-style JSON lines, one aircraft state per line, as in
// recordings/adsb_actions-readsb (source "readsb", id = upper-case hex, '~' kept for
// non-ICAO addresses; TrackReport::address = the hex as a 24-bit number, none for '~'):
//   {"now":1693383000,"hex":"ab80bc","flight":"N840KB","lat":39.85,"lon":-119.85,
//    "alt_baro":9975,"gscp":240,"track":164.1}
// Members read: now (UTC s), hex, flight (trimmed callsign; "N/A" means none), lat, lon,
// alt_baro (ft, or the string "ground": on ground, altitude alt_geom or 0; a numeric
// string is read as a number), alt_geom (ft, used when alt_baro is absent), gs (kt) or
// gscp (kt, what adsb_actions writes instead of gs), track (deg), baro_rate or
// geom_rate (ft/min), squawk (octal string), nav_altitude_mcp (ft: sel_ft, sel_src mcp)
// or else nav_altitude_fms (ft: sel_ft, sel_src fms), track_rate (deg/s, positive turning
// right: tar_dps); dump1090-mutability's older altitude (ft or "ground"), speed (kt) and
// vert_rate (ft/min) when the current names are absent. A nested "flightdict" object (adsb_actions' copy of the full readsb
// record) supplies alt_geom, baro_rate, geom_rate, squawk, nav_altitude_mcp,
// nav_altitude_fms and track_rate when the top level lacks them. null means absent;
// other keys are ignored.
// Lines without lat/lon (adsb_actions writes {"flight":"N/A","now":...} heartbeats) are
// counted "no_position". Other rejections: bad_json, wrong_type, bad_number,
// missing_field, no_altitude, bad_address, bad_mode3a, *_out_of_range, line_too_long,
// truncated.

#include <cstddef>
#include <memory>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

struct ReadsbOptions {
  /// Longest line accepted, bytes (the grid files' longest line is ~600 bytes).
  std::size_t max_line_bytes = 4096;
};

std::unique_ptr<Decoder> make_readsb_decoder(const ReadsbOptions& options = {});

}  // namespace kew::protocol
