#pragma once
// Decoder of aircraft.json snapshots (format "aircraft-json"): the file readsb,
// dump1090-fa and dump1090-mutability write once a second (/run/readsb/aircraft.json,
// /run/dump1090-fa/aircraft.json, tar1090's /data/aircraft.json and history_N.json), and
// the ADS-B aggregators' API answers in readsb's format:
//   {"now":1700000000.1,"messages":123,"aircraft":[
//     {"hex":"3c6586","type":"adsb_icao","flight":"DLH4AB  ","alt_baro":36000,"gs":451.2,
//      "track":92.1,"baro_rate":0,"lat":49.1,"lon":11.2,"seen_pos":0.4,"seen":0.1},...]}
// "ac" may stand for "aircraft", and "now" may be in milliseconds (the aggregators' API;
// a value above 1e11 is). Snapshots may follow one another in one stream (blanks between
// them), split anywhere between feed() calls.
//
// Each aircraft with a position makes one record (source "aircraft-json", id its hex
// upper case with '~' kept for non-ICAO addresses, address the 24-bit hex but for '~'
// ones) dated now − seen_pos (now − seen without seen_pos; now without either), with the
// members of readsb.hpp: alt_baro (ft, or "ground"), alt_geom, gs, track, baro_rate or
// geom_rate, nav_altitude_mcp or nav_altitude_fms, track_rate, squawk, flight, type (kept
// as TrackReport::position_source: adsb_icao, mlat, tisb_*, adsr_*); and
// dump1090-mutability's altitude, speed and vert_rate when those are absent. A position
// older than max_position_age_s is not reported, nor one reported before: an aircraft's
// position is reported again only with a later data time, so a snapshot every second of
// a position 5 s old makes one record, not five. The records of one snapshot come in
// data-time order. What was reported is remembered across end_message() (one snapshot a
// datagram or message) and forgotten at finish() (the end of the stream).
//
// An aircraft without a position is no record and no refusal (most Mode S aircraft have
// none). Refusals, by reason: bad_json (a snapshot, or an aircraft that is not an
// object), object_too_long (a snapshot over max_snapshot_bytes, skipped), missing_field
// (a snapshot without now or aircraft, an aircraft without hex), bad_address,
// no_altitude, wrong_type, bad_number, *_out_of_range, truncated.

#include <cstddef>
#include <memory>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

struct AircraftJsonOptions {
  /// Largest snapshot accepted, bytes (25,000 aircraft take about 12 MB).
  std::size_t max_snapshot_bytes = 64u << 20;
  /// Positions older than this at the snapshot's time are not reported (s, > 0): the
  /// pipeline refuses records older than its max_lateness_s (10 s) anyway.
  double max_position_age_s = 10.0;
};

std::unique_ptr<Decoder> make_aircraft_json_decoder(const AircraftJsonOptions& options = {});

}  // namespace kew::protocol
