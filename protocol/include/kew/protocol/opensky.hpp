#pragma once
// Decoders of OpenSky Network state vectors (source "opensky", id = upper-case icao24,
// TrackReport::address = icao24 as a 24-bit number).
//
// CSV: the OpenSky historical "states" files. A header line is required and columns
// are found by name (order free, extra columns ignored):
//   time,icao24,lat,lon,velocity,heading,vertrate,callsign,onground,alert,spi,squawk,
//   baroaltitude,geoaltitude,lastposupdate,lastcontact
// Required: time, icao24, lat, lon, and baroaltitude or geoaltitude. Units converted:
// velocity m/s → kt, baroaltitude/geoaltitude m → ft (barometric preferred, geometric
// when it is empty), vertrate m/s → ft/min. Time t = lastposupdate (when the position
// was measured) when present, else time. onground: true/false/1/0 (any case). Fields
// may be quoted ("..." with "" for a quote). A second header line (concatenated files)
// replaces the first. Rejections: bad_header, no_header, malformed_line, bad_address,
// bad_number, bad_value (onground), bad_mode3a, missing_field (empty time), no_position,
// no_altitude, *_out_of_range, line_too_long, truncated.
//
// JSON: the traffic library's state-vector JSON (recordings/traffic-opensky): one JSON
// array of flat objects
//   {"timestamp":1533101250000,"icao24":"3003ae","callsign":"DLH8JW","latitude":45.81,
//    "longitude":9.22,"altitude":34975.0,"groundspeed":443.4,"track":324.2,
//    "vertical_rate":960.0}
// timestamp: ms since 1970 (values above 1e11, i.e. after 1973 in ms) or s (below),
// altitude ft (geoaltitude ft when altitude is null or absent), groundspeed kt, track
// deg, vertical_rate ft/min; optional onground (bool), squawk (octal string). The array
// is scanned incrementally: each element is cut out by a string-aware bracket counter
// and parsed alone, so memory stays bounded by `max_object_bytes` whatever the file
// size. Elements may equally come as JSON lines without the enclosing array.
// Rejections (messages name the element number): bad_json (also bytes between
// elements that are not ',' '[' ']' or blanks; scanning resumes at the next '{'),
// object_too_long (skipped up to the next "}," or "}\n"), wrong_type, missing_field,
// no_position, no_altitude, bad_address, bad_mode3a, *_out_of_range, truncated.

#include <cstddef>
#include <memory>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

struct OpenskyCsvOptions {
  /// Longest line accepted, bytes.
  std::size_t max_line_bytes = 4096;
};

struct OpenskyJsonOptions {
  /// Longest array element accepted, bytes.
  std::size_t max_object_bytes = 4096;
};

std::unique_ptr<Decoder> make_opensky_csv_decoder(const OpenskyCsvOptions& options = {});
std::unique_ptr<Decoder> make_opensky_json_decoder(const OpenskyJsonOptions& options = {});

}  // namespace kew::protocol
