#pragma once
// One zone's run over a batch (design §3.3, §4.9): its kinetic maintenance in record
// order and, at each probe, the candidate search and the conflict test of the pairs the
// zone owns, each tested once; the verdicts go to the alert stage.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "batch.hpp"
#include "kew/pipeline/instrumentation.hpp"
#include "kew/pipeline/pipeline_config.hpp"
#include "kew/zone/zone.hpp"
#include "kew/zone/zone_tiling.hpp"
#include "pair_judge.hpp"

namespace kew::pipeline {

/// One operation of a batch on a zone, in record order.
struct ZoneOp {
  enum class Kind : std::uint8_t { Place, Remove, Probe, Renumber };
  Kind kind;
  track::TrackSlot slot;
  std::uint32_t snapshot;  ///< Place, Probe: the track as of the op (Batch::snapshots)
  double t;                ///< data time of the op: the clock of its record (UTC s)
};

/// What one probe of a zone gave.
struct ProbeResult {
  std::uint32_t first = 0, count = 0;  ///< in ZoneWork::found
  std::uint64_t candidates = 0;        ///< points the search returned
};

/// A zone and the work of the batch on it.
struct ZoneWork {
  std::unique_ptr<zone::Zone> zone;
  std::size_t members = 0;  ///< as the track stage placed them
  double next_renumber = 0.0;
  bool touched = false;     ///< in ZoneSet's list of zones with work
  std::vector<ZoneOp> ops;
  std::vector<ProbeResult> probes;  ///< of the Probe ops, in order
  std::vector<FoundPair> found;     ///< conflicting pairs the zone owns
  std::size_t cursor = 0;           ///< the alert stage's next probe
  PhaseTimes phases;
  std::vector<kinetic::PointId> candidates;
};

/// The probe state of a track as of snapshot `s` in the plane of zone `key`: what a zone
/// stores for a member and the alert stage judges with, made in one place.
zone::ProbeState member_state(const Snapshot& s, const geo::Projection& plane, zone::ZoneKey key);

class ZoneProbe {
 public:
  /// `tiling`: the worldwide tiling (null in single mode). Every argument must outlive
  /// the probe.
  ZoneProbe(const PipelineConfig& config, const PairJudge& judge, const PipelineInstrumentation& instruments,
            const zone::ZoneTiling* tiling);

  /// Runs work.ops in order on work.zone, then advances its engine to the clock (UTC s);
  /// `epoch`: data time of engine time 0.
  void run(ZoneWork& work, const std::vector<Snapshot>& snapshots, double epoch, double clock) const;

  /// Search radius R_i of design §2.1 in `zone` for a track moving at plane speed
  /// `speed_mps`, in plane metres: S_h·k_max + T·(|v_i| + v_max) + 2τ (τ as an absolute
  /// bound), with the largest S_h and T of the defaults and every region (design §4.8),
  /// k_max and v_max the zone's.
  double search_radius(const zone::Zone& zone, double speed_mps) const;

 private:
  /// The candidates of the track's point `self` (design §2.1) into work.candidates.
  void collect_candidates(ZoneWork& work, kinetic::PointId self) const;
  /// Tests the candidates and appends the conflicting pairs the zone owns to work.found.
  void test_candidates(ZoneWork& work, kinetic::PointId self, double now) const;
  /// τ as a bound on the lag of a point behind its track in `zone`'s plane (m).
  double tolerance_bound_m(const zone::Zone& zone) const;

  const PipelineConfig& config_;
  const PairJudge& judge_;
  const PipelineInstrumentation& instruments_;
  const zone::ZoneTiling* tiling_;
};

}  // namespace kew::pipeline
