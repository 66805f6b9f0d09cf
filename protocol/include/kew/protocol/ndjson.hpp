#pragma once
// Decoder of the canonical track record, one JSON object per line (design §5.1).
//
//   {"t":1714400000.25,"id":"4CA123","lat":51.47,"lon":-0.45,"alt_ft":35000,
//    "gs_kt":450,"trk_deg":270.0,"vr_fpm":0,"cs":"BAW123","src":"adsb","gnd":false,"sq":"7000",
//    "addr":"4CA123","coast":false,"end":false}
//
// Required: t (UTC s since 1970), id (string), lat, lon (degrees), alt_ft (feet).
// Optional: gs_kt (knots), trk_deg (degrees; one turn either way of [0, 360) is brought
// into it, any other angle is passed on unwrapped), vr_fpm (ft/min),
// sel_ft (selected altitude, feet), sel_src ("mcp" or "fms": where sel_ft comes from,
// meaningful only with sel_ft; absent or null means "mcp"), tar_dps (track angle rate,
// deg/s, positive turning right), cs, src (strings), gnd (bool), sq (Mode 3/A, string of
// 4 octal digits), addr (24-bit ICAO address, an attribute of the track, not its id:
// string of exactly 6 hex digits, either case), coast (bool: the position is
// extrapolated), end (bool: the track's last update). null for an optional member means
// absent (false for the booleans). Unknown keys are ignored (so that producers may add
// members); when a key repeats, the last value wins. Lines starting with '#' and blank
// lines are skipped; CRLF is accepted; the last line needs no newline. An optional
// number out of its range (a negative ground speed, an absurd track angle) is passed on
// as it is: the track table drops that field alone and counts it (design §4.3).
//
// Rejection reasons (each message names the line number): bad_json, wrong_type,
// bad_number, missing_field, bad_id, bad_mode3a, bad_address, bad_sel_src (sel_src is
// neither "mcp" nor "fms"), lat_out_of_range, lon_out_of_range, line_too_long,
// truncated (a refused last line without newline).

#include <cstddef>
#include <memory>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

struct NdjsonOptions {
  /// Longest line accepted, bytes; a longer one is skipped and counted "line_too_long".
  std::size_t max_line_bytes = 4096;
};

std::unique_ptr<Decoder> make_ndjson_decoder(const NdjsonOptions& options = {});

}  // namespace kew::protocol
