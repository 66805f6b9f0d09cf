#pragma once
// Who may alert (design §4.5): the rules that sit between the candidate list and the
// alert manager. They never touch the candidate search, which stays complete, and the
// brute-force probe goes through the same rules, so exact = brute still holds.
//
// Three kinds of rule, applied to a pair the conflict test found in conflict:
//  - one aircraft: two tracks with one address are never in conflict, and the same
//    discrete code on coinciding tracks opens no alert; closeness alone never makes
//    two tracks one aircraft;
//  - level pairs: two level aircraft reported at adjacent levels are separated;
//  - exclusions: a track that is not an airborne aircraft worth alerting on opens no
//    alert (an alert already open stays open and ends by its own rules).

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "kew/eligibility/aerodromes.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/track/track_table.hpp"
#include "kew/util/name_table.hpp"

namespace kew::eligibility {

struct EligibilityConfig {
  /// Tracks slower than this open no alert (kt, ≥ 0; 0 disables): stationary test
  /// targets and ground clutter at altitude. Airborne aircraft fly well above 50 kt.
  double min_ground_speed_kt = 50.0;
  /// Altitude band of aircraft worth alerting on (ft): 71,900 ft or −1,400 ft is a
  /// bad altitude, not an aircraft.
  double min_altitude_ft = -1000.0;
  double max_altitude_ft = 60000.0;
  /// Below this altitude no alert opens (ft above mean sea level, ≥ 0; 0 disables):
  /// aerodrome traffic, which STCA leaves to the aerodrome controller.
  double lower_limit_ft = 1500.0;
  /// ... nor below this height above the nearest aerodrome within aerodrome_radius_nm
  /// (ft, ≥ 0; 0 disables), where that is higher: the lower limit at an aerodrome 2,300 ft
  /// above the sea is 3,300 ft. 1,000 ft is the usual circuit height, the ceiling of
  /// aerodrome traffic; 1,500 ft above the sea keeps a sea-level aerodrome's.
  double aerodrome_height_ft = 1000.0;
  /// The aerodromes whose elevation counts: within this distance (NM, (0, 50]) of the track.
  double aerodrome_radius_nm = 5.0;
  /// The aerodrome table: kew_config loads [eligibility] aerodromes_file into it (default
  /// data/aerodromes.csv, installed under share/kew); a program or test may hand in its
  /// own. Null: no aerodromes, the lower limit is lower_limit_ft everywhere.
  std::shared_ptr<const AerodromeTable> aerodromes;
  /// Mode 3/A codes whose tracks open no alert (12-bit values; 7777 = a test
  /// transponder). 7500, 7600 and 7700 are never excluded (see may_exclude_mode3a).
  std::vector<std::uint16_t> excluded_mode3a = {07777};
  /// A track the source says is coasting (extrapolated, CAT062 I062/080 CST) opens no alert.
  bool exclude_coasting = true;
  /// A track whose last record is older than this at the evaluation opens no alert (s, > 0):
  /// the prediction is then an extrapolation of an extrapolation.
  double max_position_age_s = 20.0;
  /// A track opens no alert before its min_records-th record (≥ 1; 1 disables): one
  /// record is one look, and a tracker's duplicate may live for just one (design §4.5).
  int min_records = 2;
  /// Level pairs: |vertical rate| below this is level (ft/min, ≥ 0; 0 disables the rule).
  double level_rate_fpm = 300.0;
  /// Levelling off beside a level aircraft: a climb or descent without a selected
  /// altitude towards a level aircraft is presumed to stop at the level S_v short of it
  /// while it can still stop there gently (design §4.5). Needs level_rate_fpm > 0.
  bool adjacent_level_off = true;
  /// ... where the level aircraft is at or above this (ft; FL100 by default: below it
  /// much traffic flies under visual rules, without clearances to levels).
  double adjacent_level_off_above_ft = 10000.0;
  /// One aircraft without addresses: the same discrete Mode 3/A code on two tracks within
  /// this distance (NM) and altitude difference (ft) of each other.
  double same_code_distance_nm = 1.0;
  double same_code_altitude_ft = 500.0;
};

/// Why a track may not open an alert. Names are the statistics' keys.
enum class Exclusion : std::uint8_t {
  None,
  Slow,             ///< below min_ground_speed_kt
  AltitudeBand,     ///< outside [min_altitude_ft, max_altitude_ft]
  BelowLowerLimit,  ///< below Rules::lower_limit_at()
  ExcludedCode,     ///< Mode 3/A in excluded_mode3a
  Coasting,         ///< the source extrapolates the track
  PositionStale,    ///< no record for max_position_age_s
  FirstRecords,     ///< fewer than min_records records yet
};
inline constexpr util::NameTable<Exclusion, 8> kExclusionNames({{
    {Exclusion::None, "none"},
    {Exclusion::Slow, "slow"},
    {Exclusion::AltitudeBand, "altitude_band"},
    {Exclusion::BelowLowerLimit, "below_lower_limit"},
    {Exclusion::ExcludedCode, "excluded_code"},
    {Exclusion::Coasting, "coasting"},
    {Exclusion::PositionStale, "position_stale"},
    {Exclusion::FirstRecords, "first_records"},
}});

/// The rule that turns a pair the conflict test found in conflict clear (design §4.5), in
/// the order Rules::verdict() applies them.
enum class PairRule : std::uint8_t {
  None,              ///< no rule: the pair may alert
  SameAddress,       ///< one aircraft: both tracks carry one 24-bit address
  LevelPair,         ///< two level aircraft at adjacent levels
  AdjacentLevelOff,  ///< a climb or descent presumed to level off beside a level aircraft
  Inhibited,         ///< a party in an inhibition volume
  SameCode,          ///< one aircraft: one discrete code on coinciding tracks
  Excluded,          ///< a party may not open an alert (PairVerdict::exclusion says why)
};
inline constexpr util::NameTable<PairRule, 7> kPairRuleNames({{
    {PairRule::None, "none"},
    {PairRule::SameAddress, "same_address"},
    {PairRule::LevelPair, "level_pair"},
    {PairRule::AdjacentLevelOff, "adjacent_level_off"},
    {PairRule::Inhibited, "inhibited"},
    {PairRule::SameCode, "same_code"},
    {PairRule::Excluded, "excluded"},
}});

/// What the rules make of a pair in conflict (Rules::verdict).
struct PairVerdict {
  PairRule rule = PairRule::None;
  Exclusion exclusion = Exclusion::None;  ///< Excluded: why
  bool second_excluded = false;           ///< Excluded: the second track (b), not the first
};

/// What the rules read of a pair besides its two tracks.
struct PairContext {
  double now = 0.0;          ///< the data time of the judgement (UTC s)
  double distance_m = 0.0;   ///< the tracks' horizontal distance now (m, on the ellipsoid)
  bool alert_open = false;   ///< the pair's alert is open: only facts may clear it
  bool inhibited = false;    ///< either track in an inhibition volume (design §4.8)
};

/// The codes that are never identity (conspicuity codes shared by many aircraft), and
/// 7500/7600/7700, which an aircraft in trouble selects and must never be treated as
/// identity or excluded.
bool is_discrete_mode3a(std::uint16_t code);
/// False for 7500, 7600 and 7700 (hijack, radio failure, emergency).
bool may_exclude_mode3a(std::uint16_t code);

class Rules {
 public:
  /// `minima`: those of the conflict test; level pairs are judged against S_v and its
  /// altimetry tolerance.
  Rules(const EligibilityConfig& config, const probe::SeparationMinima& minima);

  /// The lower limit at (lat, lon) (ft above mean sea level): lower_limit_ft, or the
  /// elevation of the nearest aerodrome of config.aerodromes within aerodrome_radius_nm
  /// plus aerodrome_height_ft where that is higher; the aerodrome, if it sets the limit,
  /// in `aerodrome`.
  double lower_limit_at(double lat_deg, double lon_deg, const Aerodrome** aerodrome = nullptr) const;

  /// The first rule, in the order of design §4.5, that turns the pair (a, b) clear: one
  /// aircraft by address, level pair; then, only when no alert of the pair is open
  /// (presumptions and weak evidence never end one), adjacent level-off, inhibition,
  /// one aircraft by code, and the exclusions of a, then of b.
  PairVerdict verdict(const track::Track& a, const track::Track& b, const PairContext& context) const;

  /// Why track `t` may not open an alert at data time `now` (UTC s), or None.
  Exclusion exclusion(const track::Track& t, double now) const;
  /// Why track `t` may not open an area proximity warning (design §4.11): exclusion()'s
  /// rules but the altitude ones, which a volume's own band replaces.
  Exclusion area_exclusion(const track::Track& t, double now) const;

  /// Whether two tracks carry the same 24-bit address: one aircraft, whatever else.
  bool same_address(const track::Track& a, const track::Track& b) const;
  /// Whether two tracks without two addresses (two different addresses are never one
  /// aircraft) squawk the same discrete Mode 3/A code and coincide: within
  /// same_code_distance_nm and same_code_altitude_ft, ground speeds within
  /// kCoincidentSpeed_kt and track angles within kCoincidentTrack_deg. `distance_m` is
  /// their current horizontal distance (m, on the ellipsoid). Weaker evidence than an
  /// address (codes are duplicated): the pipeline uses it only for pairs without an open
  /// alert. Closeness alone is never evidence: a formation flies close and alike.
  bool one_aircraft_by_code(const track::Track& a, const track::Track& b, double distance_m) const;
  /// Velocities within these are alike (the one-aircraft rules).
  static constexpr double kCoincidentSpeed_kt = 30.0;
  static constexpr double kCoincidentTrack_deg = 15.0;
  /// Whether two tracks are level (|vertical rate| < level_rate_fpm, or a rate derived
  /// from altitudes one 25 ft step apart unless the step before went the same way: a
  /// steady descent of one step a scan is no quantisation; the rate known: reported or derived,
  /// Track::vertical_rate_known) and reported at adjacent levels (|Δaltitude| ≥ S_v −
  /// the altimetry tolerance), still so at the end of T_v with their rates.
  bool level_pair(const track::Track& a, const track::Track& b) const;
  /// Whether one track is level (as level_pair reads it) and the other climbs or
  /// descends towards it without a selected altitude (Track::intent), at no more than
  /// kLevelOffMaxRate_fpm, the level one at or above adjacent_level_off_above_ft, and can
  /// still stop at track::kCaptureDeceleration_g before it is S_v
  /// from the level one, which is then still S_v − the altimetry tolerance away after T_v
  /// at its own rate: the mover is presumed to level off at the adjacent level, as air
  /// traffic control clears it to (design §4.5). Altitudes at data time `now` (UTC s),
  /// extrapolated from the last records.
  bool adjacent_level_off(const track::Track& a, const track::Track& b, double now) const;
  /// ICAO Doc 8168 (PANS-OPS) asks for less than 1,500 ft/min over the last 1,000 ft to a
  /// level when traffic is at or near the adjacent level, to spare ACAS nuisance
  /// advisories: a faster mover is not presumed to stop (ft/min).
  static constexpr double kLevelOffMaxRate_fpm = 1500.0;


 private:
  /// The rate (ft/min) a level track is taken to have: its own below level_rate_fpm, 0
  /// for one altitude quantum between two records; none when it is not level.
  std::optional<double> level_rate(const track::Track& t) const;

  EligibilityConfig config_;
  double adjacent_level_ft_;     // S_v − the altimetry tolerance
  double separation_ft_;         // S_v
  double vertical_lookahead_s_;  // T_v
};

}  // namespace kew::eligibility
