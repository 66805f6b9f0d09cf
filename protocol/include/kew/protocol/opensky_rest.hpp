#pragma once
// Decoder of the OpenSky Network REST API's state vectors (format "opensky-rest"): the
// answers of /api/states/all (and /api/states/own), one JSON object each
// (https://openskynetwork.github.io/opensky-api/rest.html):
//   {"time":1458564121,"states":[["3c6444","DLH9LF  ","Germany",1458564120,1458564121,
//     6.1546,50.1964,9639.3,false,232.88,98.26,4.55,null,9547.86,"1000",false,0],...]}
// "states" is null when no aircraft matched. Responses may follow one another in one
// stream (blanks between them), split anywhere between feed() calls.
//
// Each state vector is an array: 0 icao24 (6 hex digits), 1 callsign (8 characters,
// blank-padded, or null), 2 origin country, 3 time_position (UTC s of the position, null
// when OpenSky had none for 15 s), 4 last_contact, 5 longitude (deg), 6 latitude (deg),
// 7 baro_altitude (m), 8 on_ground (bool), 9 velocity (m/s over ground), 10 true_track
// (deg clockwise from north), 11 vertical_rate (m/s, positive climbing), 12 sensors,
// 13 geo_altitude (m), 14 squawk (4 octal digits), 15 spi, 16 position_source (0 ADS-B,
// 1 ASTERIX, 2 MLAT, 3 FLARM), 17 category (with extended=1). null means absent. The
// API's first layout (before 2018) has alert at 15, spi at 16 and position_source at 17:
// a boolean at 16 marks it. A vector needs 0 and 3 to 8; what follows may be missing.
//
// Each aircraft with a position (time_position, latitude and longitude) makes one record
// (source "opensky", id the icao24 upper case, address its number) dated time_position,
// in kew's units: baro_altitude m → ft (geo_altitude when it is null; on the ground
// without either, 0 ft, as aircraft-json's "ground"), velocity m/s → kt, vertical_rate
// m/s → ft/min, by the defining constants (0.3048 m, 1852 m); true_track as the track
// angle, the callsign trimmed, on_ground as the report's ground flag, squawk as Mode 3/A,
// position_source as TrackReport::position_source ("adsb", "asterix", "mlat", "flarm";
// another number is kept as its digits). A position older than max_position_age_s at the
// response's time is not reported, nor one reported before: a position is reported
// again only with a later time_position, so polling every 5 s an aircraft whose position
// is 10 s old makes one record. The records of one response come in data-time order.
// What was reported is remembered across end_message() (one response a datagram or a
// poll) and forgotten at finish() (the end of the stream).
//
// An aircraft without a position is no record and no refusal. Refusals, by reason:
// bad_json (a response, or bytes between responses), object_too_long (a response over
// max_snapshot_bytes, skipped), missing_field (a response without time or states, a
// vector too short), wrong_type (states neither an array nor null, a vector not an array,
// a member of the wrong type), bad_address, bad_mode3a, bad_number, no_altitude (in the
// air without either altitude), *_out_of_range, truncated.

#include <memory>

#include "kew/protocol/aircraft_json.hpp"
#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

/// `options`: the snapshot limits aircraft-json has (max_snapshot_bytes for a response,
/// max_position_age_s at its time).
std::unique_ptr<Decoder> make_opensky_rest_decoder(const AircraftJsonOptions& options = {});

}  // namespace kew::protocol
