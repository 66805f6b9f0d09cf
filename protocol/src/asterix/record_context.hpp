#pragma once
// What the per-category record decoders share: the stream's clock, rejection counter and
// radar sites, and the conversions every category needs.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "kew/protocol/asterix/day_clock.hpp"
#include "kew/protocol/asterix/radar_projection.hpp"
#include "kew/protocol/asterix/record_walker.hpp"
#include "kew/track/track_report.hpp"
#include "kew/util/rejections.hpp"
#include "kew/util/units.hpp"

namespace kew::protocol::asterix {

inline constexpr double kKnotsPerMetrePerSecond = units::kKnotsPerMps;
using units::kFeetPerFlightLevel;
using units::kMetresPerFoot;
using units::kMetresPerNauticalMile;

struct RecordContext {
  Rejections& rejections;
  DayClock& clock;
  const RadarProjector& radars;
};

/// Clears every field of `report` keeping its strings' capacity (no allocation per record).
void reset_report(TrackReport& report);

/// Sets report.t from a 3-byte time of day (LSB 1/128 s); false (counted
/// "asterix_bad_time_of_day") when it is not within [0, 24 h).
bool set_time_of_day(const std::uint8_t* tod, RecordContext& context, TrackReport& report);

/// Sets report.source to "<category>/SAC.SIC" from a 2-byte data source identifier.
void set_source(std::string_view category, const std::uint8_t* sac_sic, TrackReport& report);

/// Sets report.id to the 24-bit address as 6 upper-case hex digits.
void set_address_id(std::uint32_t address, TrackReport& report);
/// Sets report.id to a track number in decimal.
void set_track_number_id(std::uint32_t track_number, TrackReport& report);

/// Decodes 8 characters of 6 bits (ICAO Annex 10 IA-5 subset: A-Z, 0-9, space) from 6
/// bytes into `out`, trimmed; false and `out` empty when a code is outside the set or the
/// result is blank.
bool decode_icao_characters(const std::uint8_t* six_bytes, std::string& out);
/// Copies printable ASCII `chars` into `out`, trimmed; false and `out` empty otherwise.
bool decode_ascii_characters(std::span<const std::uint8_t> chars, std::string& out);

/// Ground speed (kt) and track angle (degrees [0, 360)) from Cartesian velocity (m/s,
/// x east, y north).
void set_velocity_from_cartesian(double vx_ms, double vy_ms, TrackReport& report);

/// Selected altitude (design §5.2) from a field laid out as I062/380 SAL and I021/146
/// (SAS, SRC(2), ALT: 13-bit two's complement, LSB 25 ft) and one laid out as I062/380 FSS
/// and I021/148 (MV, AH, AM, ALT as above); either may be empty (absent). SAL counts only
/// when SAS = 1 and SRC is 2 (MCP/FCU) or 3 (FMS); otherwise FSS, which is the MCP/FCU
/// value. Neither: sel_ft stays unset.
void set_selected_altitude(std::span<const std::uint8_t> selected,
                           std::span<const std::uint8_t> final_state, TrackReport& report);

/// Track angle rate from a field laid out as I062/380 TAR and the two octets of
/// I021/165 in edition 0.26: TI(2) at the top of the first octet, the rate in the top 7
/// bits of the second (two's complement, LSB 1/4 deg/s, positive turning right). Set only
/// when the field has both octets and TI ≠ 0 (0: not available).
void set_turn_indicator_rate(std::span<const std::uint8_t> field, TrackReport& report);

/// True when lat/lon are finite and in range; otherwise counts
/// "asterix_position_out_of_range".
bool accept_position(RecordContext& context, const TrackReport& report);

/// Category decoders: fill `report` from a walked record; false after counting the reason
/// the record gives no report.
bool decode_cat062(const RecordItems& items, RecordContext& context, TrackReport& report);
bool decode_cat048(const RecordItems& items, RecordContext& context, TrackReport& report);
bool decode_cat021(const RecordItems& items, RecordContext& context, TrackReport& report);
bool decode_cat021_v026(const RecordItems& items, RecordContext& context, TrackReport& report);

}  // namespace kew::protocol::asterix
