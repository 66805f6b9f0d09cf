#pragma once
// Field parsing shared by the text decoders (SBS, OpenSky, readsb, NDJSON): numbers,
// addresses, squawks, civil dates, units, and the checks every decoded report passes.
// Internal to kew_protocol.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "kew/track/track_report.hpp"
#include "kew/util/units.hpp"

namespace kew::protocol::text {

/// Why one line (or JSON element) was refused: a stable snake_case reason for
/// Rejections and a human-readable detail (the decoder adds the line number).
struct LineProblem {
  std::string_view reason;
  std::string detail;
};
/// nullopt when the line was used (or had nothing to report and is not an error).
using LineResult = std::optional<LineProblem>;

inline LineProblem problem(std::string_view reason, std::string detail) {
  return LineProblem{reason, std::move(detail)};
}

// Unit conversions by their defining constants (1 ft = 0.3048 m, 1 NM = 1852 m), in the
// order of operations a reader would write, so independent checks get the same bits.
inline double metres_to_feet(double metres) { return metres / units::kMetresPerFoot; }
inline double metres_per_second_to_knots(double mps) { return mps * units::kSecondsPerHour / units::kMetresPerNauticalMile; }
inline double metres_per_second_to_feet_per_minute(double mps) { return mps * units::kSecondsPerMinute / units::kMetresPerFoot; }
inline double unchanged(double value) { return value; }

/// Removes ASCII spaces and tabs (and a CR) at both ends.
std::string_view trim(std::string_view s);

/// Parses the whole of `s` (surrounding blanks allowed) as a decimal number, "nan" and
/// "inf" included. False for empty text and trailing garbage.
bool parse_double(std::string_view s, double& out);

/// parse_double(), and false for NaN and infinities.
bool parse_finite_double(std::string_view s, double& out);

/// A 24-bit ICAO address as 6 hex digits, optionally prefixed by '~' (readsb and
/// dump1090 mark non-ICAO / TIS-B addresses so). `id` receives the canonical form:
/// upper-case digits, '~' kept, so that "~abc123" and "ABC123" stay distinct tracks.
/// `key` receives the address with bit 24 set for '~' addresses (a compact map key).
bool parse_address(std::string_view text, std::string& id, std::uint32_t& key);

/// The 24-bit ICAO address of a parse_address() `key`, or nullopt for a '~' one: a
/// non-ICAO address (TIS-B, anonymous) is not an aircraft's, so it is no TrackReport
/// address attribute.
inline std::optional<std::uint32_t> icao_address(std::uint32_t key) {
  if ((key >> 24) != 0) return std::nullopt;
  return key;
}

/// Exactly 6 hex digits, either case, nothing around them (canonical NDJSON "addr").
bool parse_icao_address(std::string_view text, std::uint32_t& address);

/// A Mode 3/A code as exactly 4 octal digits ("7700" → 0xFC0), surrounding blanks allowed.
bool parse_mode3a(std::string_view text, std::uint16_t& code);

/// Days from 1970-01-01 to the proleptic Gregorian date y-m-d (negative before 1970).
/// Month 1..12, day 1..31 (not checked against the month length).
std::int64_t days_from_civil(std::int64_t year, unsigned month, unsigned day);

/// Resets every field to its default but keeps the strings' capacity, so that a decoder
/// reusing one report allocates nothing per record.
void clear_report(TrackReport& report);

/// The checks every decoded report passes before it leaves a decoder, on its required
/// fields only: non-empty id, finite time and altitude, latitude in [-90, 90], longitude
/// in [-180, 180]. The optional fields are passed on as the source gave them: a negative
/// or non-finite speed, an absurd vertical rate cost only that field, which the track
/// table drops and counts in fields_dropped (design §4.3). A track angle within one turn
/// of [0, 360), that is in [-360, 720) (sources use -180..180, some write 360 for north),
/// is brought into [0, 360); any other one is left as it is, never wrapped, and dropped
/// there as out of range.
LineResult check_report(TrackReport& report);

}  // namespace kew::protocol::text
