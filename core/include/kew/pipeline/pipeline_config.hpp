#pragma once
// What a Pipeline is configured with (design §3, §4): every part's settings, each
// documented with its unit and range where it is defined.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "kew/alert/alert_manager.hpp"
#include "kew/eligibility/eligibility.hpp"
#include "kew/geo/projection.hpp"
#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/probe/proximity_search.hpp"
#include "kew/region/region_map.hpp"
#include "kew/track/track_table.hpp"
#include "kew/util/name_table.hpp"
#include "kew/volume/watched_volume.hpp"

namespace kew {

/// How the sphere is projected (design §4.9).
enum class ZoneMode : std::uint8_t {
  /// Zones of a worldwide tiling, each with its own plane, created where traffic is.
  Worldwide,
  /// One plane around one reference, records beyond coverage_radius_m refused.
  Single,
};
inline constexpr util::NameTable<ZoneMode, 2> kZoneModeNames({{
    {ZoneMode::Worldwide, "worldwide"},
    {ZoneMode::Single, "single"},
}});

/// A band of longitudes, degrees: [west_deg, east_deg), −180 ≤ west_deg < east_deg ≤ 180.
struct LongitudeBand {
  double west_deg = -180.0;
  double east_deg = 180.0;
};

struct PipelineConfig {
  track::TrackTableConfig tracks;
  ZoneMode zone_mode = ZoneMode::Worldwide;
  /// Single: the plane's centre. Worldwide: the centre of the coverage limit, if one is
  /// set. Default: the first plausible record's position rounded to 0.1°.
  std::optional<geo::GeodeticPosition> reference;
  /// Records farther than this from the reference (geodesic, m) are refused as
  /// outside_coverage. Single: the plane's radius, (0, 3,000 km], 1,500 km when empty.
  /// Worldwide: an explicit limit, (0, 20,040 km]; empty: none.
  std::optional<double> coverage_radius_m;
  /// Single mode's plane radius when coverage_radius_m is empty (m).
  static constexpr double kSingleCoverage_m = 1.5e6;
  /// Zones across machines (worldwide mode, design §4.9): the pairs whose midpoint's
  /// longitude lies in this band are this pipeline's to report; it works only the zones
  /// whose core lies within one core width of the band (the polar caps always), and
  /// delivers only the events of the pairs it serves. Instances whose bands partition
  /// [−180, 180) report, together, exactly one pipeline's events (ids included; seq and
  /// alert numbers are each instance's own). Empty: every pair.
  std::optional<LongitudeBand> served_longitudes;
  kinetic::KineticConfig kinetic = default_kinetic();
  probe::ProbeMode probe_mode = probe::ProbeMode::Exact;
  /// Memory order (design §8.3, s, ≥ 0; 0: off): every this many seconds of data time the
  /// kinetic engine is rebuilt with its points numbered along a Hilbert curve, and the
  /// probe's per-track state, kept by point, with them, so that the candidate search and
  /// the tests read neighbours from nearby memory. Alerts and their order do not change.
  double renumber_every_s = 0.0;
  /// Threads that work on the zones, the calling thread included (≥ 1). Single mode
  /// has one zone: more threads do not help it.
  std::size_t threads = 1;
  /// Records taken before the zones and the alert stage run (≥ 1): 1 delivers each
  /// record's events from process() itself; more lets the zones of a batch work in
  /// parallel, and events come out of flush() (or the process() that fills a batch).
  std::size_t batch_records = 1;
  /// Records judged each on its own, events delivered from its process(), after every
  /// flush() (≥ 0): a live feed's read of a few records then sends each record's alerts
  /// as soon as it is judged, not when the last record of the read is; the records after
  /// them wait for flush() or batch_records, and a batch's zones work in parallel. 0:
  /// every record waits (the batch's zones alone decide when it runs).
  std::size_t prompt_records = 0;
  probe::SeparationMinima minima;
  /// The turn hypothesis (design §4.4); off by default.
  probe::TurnHypothesis turn;
  alert::AlertConfig alerts;
  eligibility::EligibilityConfig eligibility;
  /// Parameter regions and inhibition volumes (design §4.8), in precedence order; each
  /// valid (region::RegionMap::problem), names distinct.
  std::vector<region::Region> regions;
  /// The volumes of the area proximity warning (design §4.11), names distinct; none:
  /// the pairs alone are judged.
  std::vector<volume::WatchedVolume> volumes;

  /// kew's kinetic defaults, each chosen from the curves of design §8.6: absolute
  /// τ = 300 m (above the one-step prediction residual of 90–96 % of recorded reports; the
  /// cost is flat from 100 to 600 m and rises beyond on dense traffic), models kept through
  /// updates while they stay within τ for 4 s (design §2.3), H = 30 s (three lazy windows:
  /// the same cost as 300 s or ∞ with a shorter queue), §8.3 on, certificates proved valid
  /// for 10 s (two to three radar periods) not solved further.
  static kinetic::KineticConfig default_kinetic() {
    kinetic::KineticConfig k;
    k.lazy_window_s = 10.0;
    k.tolerance = 300.0;
    k.keep_model_s = 4.0;
    k.horizon_s = 30.0;
    return k;
  }
};

}  // namespace kew
