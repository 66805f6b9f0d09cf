#pragma once
// What actually happened at the volumes of the area proximity warning (design §4.11),
// judged in hindsight: which aircraft entered which volume, and when (the rules are listed
// in docs/alert-quality.md, "Area proximity warnings"). kew-eval scores APW alerts against
// this as it scores pair alerts against the Truth (truth.hpp).
//
// It is built on a Truth (its tracks, aircraft and samples: positions interpolated
// between records at most 20 s apart, at every whole UTC second, never extrapolated) and
// the configuration's volumes, which are the question asked rather than a parameter of
// the detection: their area, band, schedule and traffic filter enter the truth; their
// look-ahead and warning time do not.
//
// A sample *flies* when its speed is at least 50 kt, its altitude plausible and it is not
// on the ground: the truth's airborne rule without the lower limits, whose place a
// volume's band takes (as the pipeline's area rules drop the altitude ones). A track is
// *inside* a volume at a second when it flies, the volume is active then (its weekly
// schedule), concerns the track (its traffic filter, with the track's id, its last
// callsign and its last Mode 3/A code reported at or before that second), and the sample
// is in the area (Volume::contains: boundary inside) and within the band. For a volume
// that follows an aircraft, the centre at each second is the first track of the truth
// whose id or callsign then matches `follow` and has a sample at that second; another
// aircraft is inside when it is within the circle's radius of it (local_distance_m) and
// its altitude minus the centre's is within the relative band; the centre's own aircraft
// never is. *Close* is the same within the area grown by 1 NM (kCloseCallMargin_m).
//
// An entry is a maximal run of inside seconds of one aircraft (its tracks together) in
// one volume, runs less than kLossMerge_s apart merged, as loss events are.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "kew/replay/truth.hpp"
#include "kew/track/track_report.hpp"
#include "kew/volume/watched_volume.hpp"

namespace kew::replay {

namespace area_rules {
/// A close call comes within this of the area (m), inside the band.
inline constexpr double kCloseCallMargin_m = truth_rules::kCloseCallMargin_m;
/// Runs of inside seconds closer than this (s) are one entry.
inline constexpr std::int64_t kEntryMerge_s = truth_rules::kLossMerge_s;
}  // namespace area_rules

/// The sample flies (see above).
bool flies_for_areas(const TruthSample& sample);

/// Horizontal distance (m, ≥ 0) from `p` to the area of `volume`: 0 inside it (holes
/// excluded), else to the circle (geodesic) or to the nearest edge of a ring, measured in
/// the volume's gnomonic plane (exact along lines through the centre, a fraction of a per
/// mille too long elsewhere within 100 km of it).
double distance_to_area_m(const volume::Volume& volume, volume::LatLon p);

/// One entry of an aircraft into a volume.
struct AreaEntry {
  std::uint32_t volume = 0;    ///< index into the volumes
  AircraftId aircraft = 0;
  TruthTrackId track = 0;      ///< the track inside first
  /// Followed volume: the centre's track at start_s; empty for a fixed volume.
  std::optional<TruthTrackId> centre;
  std::int64_t start_s = 0;    ///< first inside second (UTC s)
  std::int64_t end_s = 0;      ///< last inside second
  std::int64_t inside_seconds = 0;
  /// The first second of the run of consecutive seconds, ending at start_s, in which the
  /// track flew, the volume was active and concerned it (and a centre was there): when
  /// the entry became warnable.
  std::int64_t eligible_since_s = 0;
};

class AreaTruth {
 public:
  /// `truth` must outlive the AreaTruth; `records`: those it was built from (for
  /// callsigns and codes over time); `volumes`: the configuration's, copied. Runs in O(Σ samples · (candidate volumes +
  /// log)) for fixed volumes, found by a VolumeIndex per minute of each track, and
  /// O(Σ samples) per followed volume.
  AreaTruth(const Truth& truth, std::span<const TrackReport> records, std::vector<volume::WatchedVolume> volumes);

  const std::vector<volume::WatchedVolume>& volumes() const { return volumes_; }
  /// The volume of this name, if any.
  std::optional<std::uint32_t> find_volume(std::string_view name) const;

  /// Every entry, ordered by start, then volume, then aircraft.
  const std::vector<AreaEntry>& entries() const { return entries_; }
  /// The first inside second of aircraft `a` in volume `v` within [from, to] (UTC s).
  std::optional<std::int64_t> first_inside_second(std::uint32_t v, AircraftId a, std::int64_t from,
                                                  std::int64_t to) const;
  /// True when aircraft `a` was close to volume `v` (or inside) at a second of [from, to].
  bool any_close_second(std::uint32_t v, AircraftId a, std::int64_t from, std::int64_t to) const;
  /// Followed volume `v`: the centre's track at the second nearest `t` (earlier on a tie)
  /// within `within_s`; empty for a fixed volume or when none was seen.
  std::optional<TruthTrackId> nearest_centre(std::uint32_t v, double t, double within_s) const;
  /// The update period of an entry (s): its track's median interval, for a followed
  /// volume the larger of that and the centre's; 0 when unknown.
  double update_period_s(const AreaEntry& entry) const;

 private:
  struct Ident {  // a track's callsign and code from time t on
    double t;
    std::uint32_t callsign;  // index into callsigns_; 0 is ""
    std::optional<std::uint16_t> squawk;
  };
  struct Trace {  // of one (volume, track), then of one (volume, aircraft)
    std::vector<SecondRange> inside, close;
    std::vector<TruthTrackId> inside_tracks;  // per inside range: its track
  };

  void read_idents(std::span<const TrackReport> records);
  const Ident* ident_at(TruthTrackId track, std::int64_t second) const;
  bool concerns(const volume::WatchedVolume& v, TruthTrackId track, std::int64_t second) const;
  bool names(const volume::WatchedVolume& v, TruthTrackId track, std::int64_t second) const;
  std::optional<std::pair<TruthTrackId, TruthSample>> centre_at(std::uint32_t v, std::int64_t second) const;
  bool eligible(std::uint32_t v, TruthTrackId track, std::int64_t second) const;
  void sweep_fixed();
  void sweep_followed(std::uint32_t v);
  void note(std::uint32_t v, TruthTrackId track, std::int64_t second, bool inside, bool close);
  void build_entries();
  const Trace* aircraft_trace(std::uint32_t v, AircraftId a) const;

  const Truth& truth_;
  std::vector<volume::WatchedVolume> volumes_;
  std::vector<std::string> callsigns_;             // interned; [0] = ""
  std::vector<std::vector<Ident>> idents_;         // by track, by time; empty: never reported one
  std::vector<std::vector<TruthTrackId>> centres_; // by volume: the tracks that ever match `follow`
  std::vector<std::pair<std::uint64_t, Trace>> track_traces_;     // key volume << 32 | track, sorted
  std::vector<std::pair<std::uint64_t, Trace>> aircraft_traces_;  // key volume << 32 | aircraft, sorted
  std::vector<AreaEntry> entries_;
};

}  // namespace kew::replay
