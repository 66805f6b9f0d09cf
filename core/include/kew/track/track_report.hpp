#pragma once
// One surveillance record as every decoder produces it and the pipeline consumes it
// (design §3, §5.1). Units are those of the canonical record so that a recording
// round-trips without conversion; the core converts to SI on entry.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "kew/util/name_table.hpp"

namespace kew {

/// Which altitude the aircraft's automation was set to level at (design §4.4, vertical
/// intent): the pilot's MCP/FCU selection or the FMS target altitude.
enum class SelectedAltitudeSource : std::uint8_t {
  Mcp,  ///< MCP/FCU selected altitude (also CAT062/021 "final state selected altitude")
  Fms,  ///< FMS selected altitude
};
/// The names of the canonical record's `sel_src`.
inline constexpr util::NameTable<SelectedAltitudeSource, 2> kSelectedAltitudeSourceNames({{
    {SelectedAltitudeSource::Mcp, "mcp"},
    {SelectedAltitudeSource::Fms, "fms"},
}});
constexpr std::string_view to_string(SelectedAltitudeSource s) { return kSelectedAltitudeSourceNames.name(s); }

struct TrackReport {
  /// Data time, UTC seconds since the Unix epoch (fractional).
  double t = 0.0;
  /// Track identity within its source: the system track number in decimal for ASTERIX
  /// tracks (CAT062, CAT048 with I048/161), otherwise the 24-bit address as 6 upper-case
  /// hex digits (ADS-B, SBS, OpenSky, readsb). Never empty in a valid report.
  std::string id;
  /// Where the record came from ("sbs", "cat062/25.100", ...). Tracks are keyed by
  /// source + id, so two radars' track numbers never collide. Empty is a valid source.
  std::string source;
  /// WGS84 geodetic latitude, degrees in [-90, 90].
  double lat_deg = 0.0;
  /// WGS84 longitude, degrees in [-180, 180].
  double lon_deg = 0.0;
  /// Pressure altitude (or geometric when that is all the source has), feet.
  double alt_ft = 0.0;
  /// Ground speed, knots (>= 0). Absent: the track table derives velocity from positions.
  std::optional<double> gs_kt;
  /// True track angle over ground, degrees clockwise from north in [0, 360).
  std::optional<double> trk_deg;
  /// Vertical rate, feet per minute, positive climbing. Absent: treated as 0 (level).
  std::optional<double> vr_fpm;
  /// Selected altitude, feet (the level the aircraft's automation will stop at), only when
  /// the source says it is valid (design §5.1 gives each format's validity rule).
  std::optional<double> sel_ft;
  /// Where sel_ft comes from; meaningful only with sel_ft.
  SelectedAltitudeSource sel_src = SelectedAltitudeSource::Mcp;
  /// Track angle rate, degrees per second, positive turning right (clockwise), when the
  /// source gives one (CAT062 I062/380 TAR, CAT021 I021/165, CAT048 BDS 5,0, readsb
  /// `track_rate`). Absent: the track table derives it from the last track angles.
  std::optional<double> tar_dps;
  /// Callsign / aircraft identification, trimmed; empty when unknown.
  std::string callsign;
  /// 12-bit Mode 3/A code when the source gives one.
  std::optional<std::uint16_t> mode3a;
  /// 24-bit ICAO aircraft address when the source gives one (an attribute: the identity
  /// of the track is `id`). Two tracks with the same address are one aircraft; two
  /// different addresses are never one aircraft (design §4.5).
  std::optional<std::uint32_t> address;
  /// How the source located the aircraft, in its own words, when it says (readsb's and
  /// dump1090's `type`: "adsb_icao", "mlat", "tisb_icao", "adsr_icao", ...); empty when
  /// it does not. An attribute kept with the record, as `source` is, not the identity.
  std::string position_source;
  /// The source says the target is on the ground.
  bool on_ground = false;
  /// The source extrapolated this position without a fresh measurement (CAT062 I062/080
  /// CST). A coasting track opens no alert (design §4.5).
  bool coasting = false;
  /// The source says this is the track's last update (CAT062 I062/080 TSE): the track
  /// ends after this record, and a later record with the same id starts a new track.
  bool track_end = false;
};

}  // namespace kew
