#pragma once
// Writes TrackReports as canonical NDJSON (design §5.1), the exact inverse of the NDJSON
// decoder: reading a written line gives back an equal report, doubles bit for bit.
//
//   {"t":1714400000.25,"id":"4CA123","lat":51.47,"lon":-0.45,"alt_ft":35000,"gs_kt":450,
//    "trk_deg":270,"vr_fpm":0,"cs":"BAW123","src":"sbs","gnd":true,"sq":"7000","addr":"4CA123"}
//
// Numbers are the shortest text that reads back to the same double (fmt "{}"), so 35000.0
// is written 35000. Optional members are written only when present: gs_kt, trk_deg, vr_fpm
// when set, sel_ft with sel_src ("mcp" or "fms") when sel_ft is set, tar_dps when set, cs
// and src when non-empty, gnd only when true, sq (4 octal digits of the low
// 12 bits of mode3a) when set, addr (6 upper-case hex digits of the low 24 bits of
// address) when set, coast and end (coasting, track_end) only when true. JSON has no NaN or infinity: a non-finite number is
// written null, which the decoder refuses for required members and reads as absent for
// optional ones.

#include <string>
#include <string_view>

#include "kew/track/track_report.hpp"

namespace kew::protocol {

/// Appends `text` to `out` as a JSON string literal, quotes included. '"', '\\' and the
/// control characters below 0x20 are escaped; valid UTF-8 is copied as is; a byte that
/// does not start a valid UTF-8 sequence becomes \ufffd (the output is always valid JSON).
void append_json_string(std::string& out, std::string_view text);

/// Appends one canonical record to `out`, without a newline.
void append_ndjson(std::string& out, const TrackReport& report);

/// One canonical record followed by '\n'.
std::string to_ndjson_line(const TrackReport& report);

}  // namespace kew::protocol
