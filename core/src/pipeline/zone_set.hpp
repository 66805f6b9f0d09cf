#pragma once
// The zones of a pipeline (design §4.9): the tiling of the sphere (worldwide) or the one
// plane (single), a zone wherever traffic is, one plane per zone key, which zones hold
// each track, and the batch's work on them, run in parallel across zones (design §3.3).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/pipeline/instrumentation.hpp"
#include "kew/pipeline/pipeline_config.hpp"
#include "kew/util/worker_pool.hpp"
#include "kew/zone/zone.hpp"
#include "kew/zone/zone_tiling.hpp"
#include "pair_judge.hpp"
#include "zone_probe.hpp"

namespace kew::pipeline {

class ZoneSet {
 public:
  /// Every argument must outlive the set.
  ZoneSet(const PipelineConfig& config, const PairJudge& judge, const PipelineInstrumentation& instruments);

  // ---- Planes and ownership.
  const std::optional<zone::ZoneTiling>& tiling() const { return tiling_; }
  /// Single mode's plane, empty until open_single_plane().
  const std::optional<geo::Projection>& single_plane() const { return single_plane_; }
  /// Single mode: fixes the plane (centre, radius in m) and opens its zone at `clock`.
  void open_single_plane(const geo::GeodeticPosition& centre, double radius_m, double clock);
  /// The home zone of a position (0 in single mode).
  zone::ZoneKey home_of(double lat_deg, double lon_deg) const {
    return tiling_ ? tiling_->home({lat_deg, lon_deg}) : 0;
  }
  /// The plane of a home zone: its zone's, the zone opened at `clock` when missing, or
  /// for a zone this pipeline does not work (served_longitudes) the same plane without
  /// a zone.
  const geo::Projection& home_plane(zone::ZoneKey key, double clock);
  /// The plane of zone `key`, which need not exist (never opens a zone).
  const geo::Projection& plane(zone::ZoneKey key);
  /// The zone that judges pair (a, b) (design §4.9): the home of the midpoint of their
  /// last reported positions (single mode: zone 0).
  zone::ZoneKey owner_of(const track::Track& a, const track::Track& b) const;
  /// Whether zone `key` holds both tracks (members of it by their last reports).
  bool holds_both(zone::ZoneKey key, const track::Track& a, const track::Track& b);
  /// The largest distance between the last reports of two aircraft that can still come
  /// into conflict, halved (m): the zones' margin. 0 in single mode.
  double margin_m() const { return tiling_ ? tiling_->margin_m() : 0.0; }

  // ---- Membership, in record order (the track stage).
  /// Engine time 0 is data time `epoch` (UTC s) in every zone opened from now on.
  void set_epoch(double epoch) { epoch_ = epoch; }
  /// Places the track in the zones near (lat, lon) at data time t and asks them to probe
  /// it (snapshot: in the batch), taking it out of the zones no longer near; appends the
  /// zones to `step_zones` and returns how many.
  /// `probe` false: placed only (refill()).
  std::uint32_t place(track::TrackSlot slot, std::uint32_t snapshot, double lat_deg, double lon_deg, double t,
                      std::vector<zone::ZoneKey>& step_zones, bool probe = true);
  /// Takes the track out of every zone it is a member of at data time t.
  void remove(track::TrackSlot slot, double t);
  /// Asks the zones due for memory ordering (PipelineConfig::renumber_every_s) to renumber.
  void schedule_renumbering(double clock);
  /// Forgets every zone (a young run restarting, design §4.1); single mode's plane is
  /// kept when `keep_single_plane`. Requires that no track is a member.
  void reset(bool keep_single_plane);
  /// A restored pipeline's zones (design §5.9): every track of `snapshots` (each one in the
  /// engines, as the alert stage last judged it) placed at `clock` without a probe, the
  /// engines run to `clock`; then the creation and retirement counters set to the saved
  /// ones. Requires no zone and no work.
  void refill(const std::vector<Snapshot>& snapshots, double clock, std::uint64_t zones_created,
              std::uint64_t zones_retired);

  // ---- The batch.
  bool has_work() const { return !touched_.empty(); }
  /// Runs every zone's operations (in parallel when `pool` and enough work), each zone's
  /// engine then at `clock`; the CPU time of the parts added to `phases`.
  void run(const std::vector<Snapshot>& snapshots, double clock, util::WorkerPool* pool, PhaseTimes& phases);
  /// The next probe of zone `key`, in the order its probes ran.
  struct Probed {
    std::uint64_t candidates = 0;
    std::span<const FoundPair> found;
  };
  Probed next_probe(zone::ZoneKey key);
  /// Clears the batch's work and retires the zones left empty.
  void end_batch();

  // ---- Readers.
  void for_each_zone(const std::function<void(const zone::Zone&)>& f) const;
  std::size_t zone_count() const { return zone_count_; }
  /// The zone whose plane holds the track's kinematics, null when none.
  const zone::Zone* home_zone(const track::Track& track) const;
  /// Kinetic counters of every zone, summed (retired zones included); queue_max the largest.
  kinetic::KineticStatistics kinetic_statistics() const;
  /// Exact audit of every zone at `clock`, repairing what it finds.
  kinetic::KineticAudit audit(double clock);
  bool is_valid() const;
  std::uint64_t zones_created() const { return zones_created_; }
  std::uint64_t zones_retired() const { return zones_retired_; }

 private:
  /// The zone of `key`, opened (empty, its engine starting at `clock`) when missing.
  zone::Zone& zone_at(zone::ZoneKey key, double clock);
  void touch(zone::ZoneKey key);

  const PipelineConfig& config_;
  std::optional<zone::ZoneTiling> tiling_;     // worldwide mode
  std::optional<geo::Projection> single_plane_;  // single mode
  std::vector<bool> worked_zone_;  // served_longitudes: by key, the zones this pipeline works
  std::vector<std::optional<geo::Projection>> spare_planes_;  // by key: planes of zones not open
  ZoneProbe probe_;
  std::vector<ZoneWork> work_;  // by zone key
  std::vector<zone::ZoneKey> touched_;  // zones with work in the batch, or opened in it
  std::vector<std::vector<zone::ZoneKey>> members_;  // by slot: the zones holding the track
  zone::ZoneKeys scratch_;
  std::size_t zone_count_ = 0;
  kinetic::KineticStatistics retired_kinetic_;  // counters of zones no longer there
  std::uint64_t zones_created_ = 0, zones_retired_ = 0;
  double epoch_ = 0.0;
};

}  // namespace kew::pipeline
