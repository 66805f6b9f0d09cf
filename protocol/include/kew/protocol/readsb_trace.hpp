#pragma once
// Decoder of readsb's traces (format "readsb-trace"): the per-aircraft files readsb
// writes with --write-globe-history (globe_history/YYYY/MM/DD/traces/xx/
// trace_full_<hex>.json, one aircraft's whole day) and in its json directory
// (traces/xx/trace_full_<hex>.json and trace_recent_<hex>.json), gzip-compressed although
// named .json, as tar1090 serves them (readsb's README-json.md, "trace jsons"):
//   {"icao":"3c66b0","r":"D-AIUP","t":"A320","dbFlags":0,"desc":"AIRBUS A-320",
//    "timestamp":1663259853.016,"trace":[
//     [7016.59,49.2633,10.614239,25125,446.5,309.0,0,-2176,{"type":"adsb_icao",
//      "flight":"DLH7YA  ","squawk":"1000","nav_altitude_mcp":14016,...},"adsb_icao",
//      25875,-2208,335,-10.7],
//     [7024.85,49.273589,10.593278,24825,446.0,306.6,0,-2176,null,"adsb_icao",25550,
//      -2144,337,-1.6],...]}
// Traces may follow one another in one stream (blanks between them), split anywhere
// between feed() calls; each is parsed whole, so one is at most max_snapshot_bytes.
//
// A trace row is an array: 0 seconds after "timestamp", 1 latitude, 2 longitude (deg),
// 3 altitude (ft, or the string "ground", or null), 4 ground speed (kt), 5 track (deg; on
// the ground the true heading), 6 flags (1: the first position after 15 s or more
// without one, 2: the start of a new leg, 4: the vertical rate is geometric, 8: the
// altitude is geometric), 7 vertical rate (ft/min), 8 an object of aircraft.json members
// or null, 9 the position's source type ("adsb_icao", "mlat", "tisb_icao", ...), 10
// geometric altitude (ft), 11 geometric vertical rate (ft/min), 12 indicated air speed,
// 13 roll; null means absent. Files before 2022 end rows at 8; later readsb versions
// may add fields after 13, which are ignored. A row needs 0 to 3.
//
// Each row makes one record (source "readsb-trace", id the icao upper case with '~'
// kept for non-ICAO addresses, address the 24-bit hex but for '~' ones) dated timestamp
// + row[0], through the member rules of readsb.hpp: altitude 3 (8 set: as alt_geom),
// "ground" on the ground (altitude the geometric one or 0), else geometric 10; track 5;
// vertical rate 7 (4 set: as geom_rate), else 11; position_source 9, else the row's
// object's "type". The callsign ("flight") and squawk are the last ones an object of the
// trace gave (readsb writes the object only when something changed); the selected
// altitude (nav_altitude_mcp, nav_altitude_fms) and track_rate only from the row's own
// object. Flag 1 marks a gap before a fresh position, not a stale one: such a row is a
// record like the others; flags 2, 4 and 8 only say how to read the row. Rows are in
// time order in a trace; a row not later than the last one reported for its address
// (the same point in trace_recent and trace_full, whose timestamps differ) is not
// reported again, and what was reported is remembered across end_message() and forgotten
// at finish().
//
// Refusals, by reason: bad_json (a trace, or bytes between traces), object_too_long (a
// trace over max_snapshot_bytes, skipped), missing_field (a trace without icao,
// timestamp or trace; a row shorter than 4), wrong_type (trace not an array, a row not an
// array, a field of the wrong type), bad_number, bad_address, bad_mode3a, no_position (a
// row whose latitude or longitude is null), no_altitude, *_out_of_range, truncated.

#include <memory>

#include "kew/protocol/aircraft_json.hpp"
#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

/// A row of an address at most this much later than the one last reported for it is
/// that same point (s): trace_full and trace_recent date one point from different
/// timestamps (offsets to 0.01 s, timestamps to 0.001 s).
inline constexpr double kReadsbTraceSamePosition_s = 0.02;

/// `options`: max_snapshot_bytes bounds a trace; max_position_age_s is not used (a trace
/// is history, not a live picture).
std::unique_ptr<Decoder> make_readsb_trace_decoder(const AircraftJsonOptions& options = {});

}  // namespace kew::protocol
