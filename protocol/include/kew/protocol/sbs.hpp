#pragma once
// Decoder of SBS-1 BaseStation text (dump1090 / readsb port 30003), one message a line:
//   MSG,3,1,1,4CA123,1,2024/04/29,14:13:20.250,2024/04/29,14:13:20.260,,35000,,,51.47,-0.45,,,0,0,0,0
// Fields (1-based): 2 transmission type, 5 hex address, 7/8 date/time generated,
// 9/10 date/time logged, 11 callsign, 12 altitude (ft), 13 ground speed (kt), 14 track
// (deg), 15 lat, 16 lon, 17 vertical rate (ft/min), 18 squawk, 22 is-on-ground.
//
// Messages are merged per address. A report is emitted for each MSG,3 (airborne
// position) and carries: the position and altitude of that message, its on-ground flag
// (-1 or 1 true, 0 or empty false), the latest MSG,4 velocity (ground speed, track,
// vertical rate) of the address if that MSG,4 is at most `velocity_max_age_s` away in
// time (an older velocity would extrapolate the track wrongly, so it is left out and the
// track table derives one from positions), the latest MSG,1 callsign, and the latest
// MSG,6 squawk. MSG,2 (surface), 5, 7, 8 and the other transmission types (SEL, ID,
// AIR, STA, CLK) are counted as "ignored_message_type". id = upper-case hex, source "sbs",
// TrackReport::address = the hex as a 24-bit number (none for a '~' non-ICAO address).
//
// Time: the "generated" date and time (fields 7, 8), or the "logged" ones (9, 10) when
// those are empty. SBS times are the receiver's local time with no zone; the decoder
// reads them as UTC minus `utc_offset_s` (the receiver's offset east of Greenwich,
// seconds: 32400 for Japan).
//
// Rejection reasons: malformed_line, ignored_message_type, bad_address, bad_time,
// bad_number, no_position, no_altitude, lat_out_of_range, lon_out_of_range,
// address_table_full, line_too_long, truncated. Velocity fields out of their range (NaN
// included) are passed on, for the track table to drop (design §4.3).

#include <cstddef>
#include <memory>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

struct SbsOptions {
  /// Offset of the receiver's local clock east of UTC, seconds; t = local − offset.
  double utc_offset_s = 0.0;
  /// A MSG,4 velocity further than this from a MSG,3 position in time, s, is not used.
  double velocity_max_age_s = 10.0;
  /// Longest line accepted, bytes.
  std::size_t max_line_bytes = 4096;
  /// Most addresses whose merge state is kept. When full, addresses silent for
  /// `address_stale_after_s` are forgotten; if that frees nothing, a new address's
  /// messages are counted "address_table_full" (its positions still pass, unmerged).
  std::size_t max_addresses = 100000;
  /// Data-time silence after which an address's merge state may be forgotten, s.
  double address_stale_after_s = 600.0;
};

std::unique_ptr<Decoder> make_sbs_decoder(const SbsOptions& options = {});

}  // namespace kew::protocol
