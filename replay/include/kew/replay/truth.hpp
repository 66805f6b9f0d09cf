#pragma once
// What actually happened in a recording, judged in hindsight (design §2.6; the rules are
// listed in replay/README.md, "kew-eval"). kew-eval scores alerts against this.
//
// The truth is built from every decoded record, on-ground ones included, with fixed
// rules that do not depend on the kew configuration under test: only the separation
// standard (S_h, S_v) is a parameter, and it is an option of the evaluation, not read
// from the configuration. So one truth serves every configuration of a comparison.
//
// Per track (source + id) the positions are interpolated linearly between consecutive
// records at most 20 s apart, never extrapolated, and sampled at every whole UTC second.
// A sample is airborne when it flies (≥ 50 kt), has a plausible altitude, is not on the
// ground and is at or above 1,500 ft and 1,000 ft above the nearest aerodrome within
// 5 NM (of the aerodrome table handed to Truth). Two airborne samples of one second lose
// separation when they are closer than S_h horizontally and than S_v − 200 ft
// vertically (the altimetry tolerance: 975 ft apart at adjacent levels is separated).
// Tracks that are one aircraft (the same 24-bit address, or a discrete Mode 3/A code in
// common and within 1 NM and 300 ft for a minute, without two addresses) never lose
// separation against each other; closeness alone is no identity (a formation). A loss event is a run of loss
// seconds of one pair of aircraft.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "kew/eligibility/aerodromes.hpp"
#include "kew/track/track_report.hpp"
#include "kew/util/units.hpp"

namespace kew::replay {

/// The truth's fixed rules. They are constants on purpose: a truth that moved with the
/// configuration under test could not rank configurations.
namespace truth_rules {
inline constexpr double kNauticalMile_m = units::kMetresPerNauticalMile;
/// Records further apart than this are not interpolated between (s).
inline constexpr double kMaxGap_s = 20.0;
/// A derived speed is measured over at least this baseline when the run allows (s):
/// over one radar period the position noise of a stationary target reads as speed.
inline constexpr double kSpeedBaseline_s = 10.0;
/// Airborne: at least this speed (kt)...
inline constexpr double kMinAirborneSpeed_kt = 50.0;
/// ... a plausible altitude (ft) ...
inline constexpr double kMinPlausibleAltitude_ft = -1000.0;
inline constexpr double kMaxPlausibleAltitude_ft = 60000.0;
/// ... and at or above this altitude (ft): aerodrome traffic is separated visually ...
inline constexpr double kLowerLimit_ft = 1500.0;
/// ... and at or above this height (ft) above the nearest aerodrome within
/// kAerodromeRadius_m (of the table handed to Truth: kew-eval's, its first configuration's), the usual
/// circuit height: the traffic of an aerodrome 2,300 ft above the sea flies below 3,300 ft.
inline constexpr double kAerodromeHeight_ft = 1000.0;
inline constexpr double kAerodromeRadius_m = 5.0 * kNauticalMile_m;
/// Vertical separation is lost below S_v minus this (ft).
inline constexpr double kAltimetryTolerance_ft = 200.0;
/// Two tracks with a discrete code in common (and not two addresses) closer than these
/// for kOneAircraft_s consecutive seconds are one aircraft.
inline constexpr double kOneAircraftHorizontal_m = kNauticalMile_m;
inline constexpr double kOneAircraftVertical_ft = 300.0;
inline constexpr std::int64_t kOneAircraft_s = 60;
/// Runs of loss seconds of one pair closer than this (start of the next − last second
/// of the previous, s) are one loss event.
inline constexpr std::int64_t kLossMerge_s = 10;
/// A close call comes within S_h plus this (m).
inline constexpr double kCloseCallMargin_m = kNauticalMile_m;
}  // namespace truth_rules

/// The separation standard losses are judged by: an option of the evaluation.
struct SeparationStandard {
  double horizontal_m = 5.0 * truth_rules::kNauticalMile_m;  ///< S_h, metres in (0, 185,200]
  double vertical_ft = 1000.0;  ///< S_v, feet in (kAltimetryTolerance_ft, 10,000]
  /// Vertical distances below this are a loss (ft): S_v − the altimetry tolerance.
  double vertical_loss_ft() const { return vertical_ft - truth_rules::kAltimetryTolerance_ft; }
};

/// Horizontal distance (metres, ≥ 0) between two nearby WGS84 positions (degrees): the
/// plane tangent at their mean latitude, with the ellipsoid's meridional and
/// prime-vertical radii of curvature there. Within 20 NM it differs from the geodesic
/// (GeographicLib) by less than 0.005 % up to 80° of latitude and 0.02 % at 85°, far
/// inside the 0.5 % the evaluation allows, at a tenth of a geodesic's cost;
/// tests/replay/test_evaluation.cpp checks it. Longitudes are compared across ±180°. Not
/// for long lines.
double local_distance_m(double lat1_deg, double lon1_deg, double lat2_deg, double lon2_deg);

/// Index of a track of the truth, in order of first appearance in the records.
using TruthTrackId = std::uint32_t;
/// Index of an aircraft (one or more tracks), in order of its first track.
using AircraftId = std::uint32_t;

/// One track of the recording, keyed by source + id.
struct TruthTrack {
  std::string source;
  std::string id;
  std::string callsign;  ///< the last non-empty one reported; empty when none
  std::optional<std::uint32_t> address;  ///< the first 24-bit address reported
  std::uint64_t records = 0;              ///< usable records (refused ones not counted)
  /// Median interval between consecutive records at most kMaxGap_s apart (s); NaN when
  /// the track has no such pair.
  double median_interval_s = 0.0;
};

/// The interpolated state of a track at one whole second.
struct TruthSample {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_ft = 0.0;
  double speed_kt = 0.0;  ///< reported ground speed, else derived; NaN when unknown
  bool on_ground = false; ///< the nearer record's flag
  bool airborne = false;  ///< by the rules above
  /// The lower limit there (ft): kLowerLimit_ft, or the nearest aerodrome's elevation
  /// plus kAerodromeHeight_ft where higher (the nearer record's position).
  double lower_limit_ft = truth_rules::kLowerLimit_ft;
};

/// Inclusive range of whole UTC seconds.
struct SecondRange {
  std::int64_t first = 0;
  std::int64_t last = 0;
  std::int64_t length() const { return last - first + 1; }
};

/// A maximal run of loss seconds of one pair of aircraft (runs less than kLossMerge_s
/// apart merged).
struct LossEvent {
  AircraftId a = 0, b = 0;           ///< a < b
  TruthTrackId track_a = 0, track_b = 0;  ///< the tracks that lost separation first
  std::int64_t start_s = 0;          ///< first loss second (UTC s)
  std::int64_t end_s = 0;            ///< last loss second
  std::int64_t loss_seconds = 0;     ///< seconds in loss within [start_s, end_s]
  double min_horizontal_m = 0.0;     ///< smallest horizontal distance in loss (m)
  double vertical_at_min_ft = 0.0;   ///< vertical distance at that second (ft, ≥ 0)
};

/// Counts describing the truth (every figure is the same for every configuration).
struct TruthFigures {
  std::uint64_t records = 0;          ///< records used
  std::uint64_t records_refused = 0;  ///< non-finite or out-of-range time or position
  std::size_t tracks = 0;
  std::size_t aircraft = 0;           ///< tracks after the one-aircraft merges
  std::size_t merged_by_address = 0;  ///< merges (track pairs joined) by a shared address
  std::size_t merged_by_proximity = 0;///< merges by the code and 1 NM / 300 ft / 60 s rule
  std::int64_t airborne_seconds = 0;  ///< Σ over aircraft (tracks of one aircraft once)
  double flight_hours() const { return static_cast<double>(airborne_seconds) / 3600.0; }
};

class Truth {
 public:
  /// Builds the truth from `records` in any order (each track is sorted by time, stable;
  /// a record at the same time as the previous one of its track is ignored, as the
  /// pipeline's duplicate_time would). A record with a non-finite time, latitude,
  /// longitude or altitude, or a latitude outside [−90, 90] or longitude outside
  /// [−180, 180], is counted in records_refused and not used. A record flagged
  /// track_end ends its track's run: the next record of that id starts a new one.
  /// Runs in O(records·log + Σ_s n_s·log n_s + close pairs) for n_s airborne samples in
  /// second s. `aerodromes`: where the lower limit stands above the sea
  /// (truth_rules::kAerodromeHeight_ft), read during construction only.
  Truth(std::span<const TrackReport> records, const eligibility::AerodromeTable& aerodromes,
        SeparationStandard standard = {});

  const SeparationStandard& standard() const { return standard_; }
  const TruthFigures& figures() const { return figures_; }

  std::size_t track_count() const { return tracks_.size(); }
  const TruthTrack& track(TruthTrackId track) const { return tracks_[track].info; }
  /// The track with this source and id, if any record had them.
  std::optional<TruthTrackId> find_track(std::string_view source, std::string_view id) const;
  /// The aircraft the track belongs to.
  AircraftId aircraft_of(TruthTrackId track) const { return tracks_[track].aircraft; }

  /// The track's sample at whole second `second` (UTC s); empty outside its runs.
  std::optional<TruthSample> sample(TruthTrackId track, std::int64_t second) const;
  /// The sample nearest to `t` (UTC s) within `within_s` (s, ≥ 0), earlier on a tie,
  /// with its second; empty when there is none.
  std::optional<std::pair<std::int64_t, TruthSample>> nearest_sample(TruthTrackId track, double t,
                                                                     double within_s) const;
  /// The first second of the run of consecutive airborne samples that holds `second`
  /// (when the track became eligible); empty when the sample there is not airborne.
  std::optional<std::int64_t> airborne_since(TruthTrackId track, std::int64_t second) const;
  /// The track's runs of consecutive airborne seconds, in time order.
  const std::vector<SecondRange>& airborne(TruthTrackId track) const { return tracks_[track].airborne; }
  /// The track's runs of sampled seconds (records at most kMaxGap_s apart), in time order.
  std::vector<SecondRange> sampled(TruthTrackId track) const;

  /// Loss events of every pair of aircraft, ordered by start, then (a, b).
  const std::vector<LossEvent>& loss_events() const { return losses_; }
  /// The first loss second of aircraft pair {a, b} in [from, to] (UTC s), if any.
  std::optional<std::int64_t> first_loss_second(AircraftId a, AircraftId b, std::int64_t from,
                                                std::int64_t to) const;
  /// True when aircraft a and b are both airborne and within S_h + 1 NM and S_v − 200 ft
  /// at some second of [from, to] (UTC s): a close call or a loss.
  bool any_close_second(AircraftId a, AircraftId b, std::int64_t from, std::int64_t to) const;

 private:
  struct Point {  // one usable record, in the units of TrackReport
    double t, lat, lon, alt, speed_kt;  // speed_kt: reported, else derived, else NaN
    double lower_limit_ft;              // at its position: TruthSample::lower_limit_ft
    bool on_ground, track_end;
  };
  struct Run {  // records [begin, end) with gaps ≤ kMaxGap_s; samples [first_s, last_s]
    std::uint32_t begin, end;
    std::int64_t first_s, last_s;
  };
  struct Track {
    TruthTrack info;
    std::vector<Point> points;
    std::vector<Run> runs;
    std::vector<SecondRange> airborne;
    std::vector<std::uint16_t> codes;  // the discrete Mode 3/A codes reported, distinct
    AircraftId aircraft = 0;
  };
  struct PairTrace {  // of a pair of tracks, then of a pair of aircraft
    std::vector<SecondRange> loss, close, near;
    std::vector<double> loss_min_h_m, loss_v_at_min_ft;  // per loss range
    std::vector<std::uint64_t> loss_tracks;               // per loss range: track pair key
  };

  void add_records(std::span<const TrackReport> records, const eligibility::AerodromeTable& aerodromes);
  void prepare_track(Track& track) const;
  void sweep(std::unordered_map<std::uint64_t, PairTrace>& traces);
  void merge_aircraft(const std::vector<std::pair<std::uint64_t, const PairTrace*>>& traces);
  void build_losses(const std::vector<std::pair<std::uint64_t, const PairTrace*>>& traces);
  TruthSample interpolate(const Track& track, const Run& run, std::uint32_t segment, std::int64_t second) const;
  const PairTrace* aircraft_trace(AircraftId a, AircraftId b) const;

  SeparationStandard standard_;
  TruthFigures figures_;
  std::vector<Track> tracks_;
  std::unordered_map<std::string, TruthTrackId> index_;  // source + '\x1f' + id
  std::vector<std::pair<std::uint64_t, PairTrace>> aircraft_traces_;  // sorted by key
  std::vector<LossEvent> losses_;
};

}  // namespace kew::replay
