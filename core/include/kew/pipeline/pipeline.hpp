#pragma once
// The heart of kew (design §3): TrackReports in, alert events out. Three stages:
//  1. the track stage, in record order: track table (order, plausibility), projection
//     into the record's home zone, and the work each zone has to do (place, remove,
//     probe, renumber);
//  2. the zones, each on its own (in parallel across zones, design §3.3): kinetic engine,
//     candidate search and conflict test of the pairs the zone owns;
//  3. the alert stage, in record order: partners, eligibility rules, alert manager, sink.
// Deterministic: the same records in the same order give the same events, whatever the
// number of threads or the size of a batch. Used by kew-replay and kewd alike.

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "kew/alert/alert_manager.hpp"
#include "kew/eligibility/eligibility.hpp"
#include "kew/geo/projection.hpp"
#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/pipeline/pair_watch.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/probe/proximity_search.hpp"
#include "kew/region/region_map.hpp"
#include "kew/track/time_guard.hpp"
#include "kew/track/track_table.hpp"
#include "kew/util/indexed_heap.hpp"
#include "kew/util/name_table.hpp"
#include "kew/util/worker_pool.hpp"
#include "kew/zone/zone.hpp"
#include "kew/zone/zone_tiling.hpp"

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
  /// Exact mode: search around the predicted position p_i + v_i·T, over the smaller disk
  /// of design §2.1 (a track under a turn hypothesis keeps the disk around p_i). Both
  /// are complete; false measures the difference (kew_peers_bench).
  bool search_ahead = true;
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
  /// Time the three parts of the work on updates (Pipeline::phase_times); off except in
  /// benchmarks (two reads of the thread's CPU clock per part and update, about 1 µs).
  bool time_phases = false;
  probe::SeparationMinima minima;
  /// The turn hypothesis (design §4.4); off by default.
  probe::TurnHypothesis turn;
  alert::AlertConfig alerts;
  eligibility::EligibilityConfig eligibility;
  /// Parameter regions and inhibition volumes (design §4.8), in precedence order; each
  /// valid (region::RegionMap::problem), names distinct.
  std::vector<region::Region> regions;

  /// kew's kinetic defaults: absolute τ = 300 m (above the one-step prediction residual
  /// of 90–96 % of recorded reports, docs/performance.md, measured position noise), models kept
  /// through updates while they stay within τ for 4 s (design §2.3), H = 300 s, §8.3 on,
  /// certificates proved valid for 10 s (two to three radar periods) not solved further.
  static kinetic::KineticConfig default_kinetic() {
    kinetic::KineticConfig k;
    k.lazy_window_s = 10.0;
    k.tolerance = 300.0;
    k.keep_model_s = 4.0;
    k.horizon_s = 300.0;
    return k;
  }
};

/// Where the time of updates goes (PipelineConfig::time_phases): CPU seconds of the
/// calling thread, summed over the run.
struct PhaseTimes {
  double maintenance_s = 0.0;  ///< kinetic maintenance: insert, update, remove, advance (events)
  double search_s = 0.0;       ///< candidate search (ProximitySearch) and partner collection
  double tests_s = 0.0;        ///< CPA tests of the candidates and the alert bookkeeping
};

struct PipelineStatistics {
  std::uint64_t records = 0;            ///< records offered to process()
  std::uint64_t accepted = 0;           ///< records the track table accepted
  std::uint64_t awaiting_velocity = 0;  ///< accepted records of tracks without velocity yet
  std::uint64_t tracks_dropped = 0;     ///< tracks dropped (timeout, end of track, restart)
  std::uint64_t tracks_ended = 0;       ///< tracks the source ended (TrackReport::track_end)
  std::uint64_t runs_restarted = 0;     ///< young runs restarted elsewhere in time or space
  /// Tracks restarted because a record of the same id carried another 24-bit address (a
  /// reused track number: two addresses are never one aircraft).
  std::uint64_t tracks_restarted = 0;
  std::uint64_t probes = 0;             ///< probe runs (one per applied update)
  std::uint64_t candidates = 0;         ///< pairs evaluated, Σ over probes
  std::uint64_t zones_created = 0;      ///< zones that came into existence (traffic arrived)
  std::uint64_t zones_retired = 0;      ///< zones whose last member left
  double last_data_time = 0.0;          ///< the pipeline clock (UTC s); 0 before any record
};

class Pipeline {
 public:
  using AlertSink = std::function<void(const AlertEvent&)>;

  explicit Pipeline(const PipelineConfig& config = {});
  ~Pipeline();
  // The alert manager looks track names up in this object's track table.
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  /// Receives every alert event, in sequence order, synchronously.
  void set_alert_sink(AlertSink sink) { sink_ = std::move(sink); }

  /// Told of every pair evaluation that finds a conflict, before the eligibility rules
  /// and the alert manager see it (a pair the rules then suppress is told too): slots
  /// (p < q) of the pair, at now(). Alerts need `confirm` such evaluations; the tap sees
  /// each one, so benchmarks can check other candidate searches against the probe's.
  /// Empty by default (no cost beyond a test per conflict).
  using ConflictTap = std::function<void(track::TrackSlot p, track::TrackSlot q)>;
  void set_conflict_tap(ConflictTap tap) { conflict_tap_ = std::move(tap); }

  /// Notes where each pair of `watch` stands at every update of either of its tracks
  /// (design §4.10); null stops. The watch must outlive its use. Requires batch_records
  /// = 1 (the alert stage then judges each record as the track stage takes it): throws
  /// std::invalid_argument otherwise. Changes no alert.
  void set_pair_watch(PairWatch* watch);

  /// Processes one record (any data time; see TrackTableConfig for what is refused). A
  /// record too far ahead of the clock is held, not applied (track::TimeGuard): it is
  /// applied later, in order, when enough records confirm the jump, or refused.
  void process(const TrackReport& report);

  /// The latest data time a record may carry (UTC s): a later one is refused at once
  /// ("future_time"), held by nothing. kewd sets it to the wall clock plus
  /// `[service] max_future_s` before each record; offline tools leave it unbounded.
  void set_time_ceiling(double utc_s) { time_ceiling_ = utc_s; }

  /// The input ended: records still held ahead of the clock, which nothing contradicted,
  /// are applied.
  void end_of_input();

  /// Runs the zones and the alert stage over the records taken so far, delivering their
  /// events; the next prompt_records records are then judged one by one. Readers of the
  /// pipeline's state (tracks, alerts, statistics) call it first when batch_records > 1.
  void flush();
  /// Records taken that wait for their batch to run (none: every event is delivered).
  bool batch_waiting() const { return !steps_.empty() || !touched_.empty(); }

  /// Moves the clock to t (UTC s) without a record — live mode's periodic tick: drops
  /// tracks that timed out and executes kinetic events up to t. Ignored if t ≤ now().
  /// While records arrive too late (none accepted since), the clock stops within
  /// max_lateness_s of the newest of them, so a feed whose delay grew can catch up.
  void advance_to(double t);

  /// Ends every alert and drops every track at the current time (end of a replay, or a
  /// daemon shutting down), emitting the End events.
  void drop_all();

  /// Exact audit of every zone's triangulation at now(), repairing what it finds; the
  /// zones' findings summed.
  kinetic::KineticAudit audit();
  /// Every zone's kinetic engine is a valid Delaunay triangulation (tests).
  bool is_valid() const;

  double now() const { return clock_; }
  const PipelineStatistics& statistics() const { return stats_; }
  /// Zero unless PipelineConfig::time_phases.
  const PhaseTimes& phase_times() const { return phases_; }
  /// The kinetic counters of every zone, summed (zones that were retired included);
  /// queue_max is the largest of any zone.
  kinetic::KineticStatistics kinetic_statistics() const;
  const Rejections& rejections() const { return tracks_.rejections(); }
  Rejections& rejections() { return tracks_.rejections(); }
  /// Optional fields dropped from records that passed the record-level checks (design
  /// §4.3), by reason.
  const Rejections& dropped_fields() const { return tracks_.dropped_fields(); }
  Rejections& dropped_fields() { return tracks_.dropped_fields(); }
  /// Conflicting evaluations the rules of design §4.5 turned clear, by rule:
  /// "same_aircraft", "level_pair", "adjacent_level_off", "inhibited", or the exclusion of
  /// the first excluded party.
  const Rejections& suppressed() const { return suppressed_; }
  const track::TrackTable& tracks() const { return tracks_; }
  /// Tracks in the kinetic engines (accepted with a velocity), each counted once.
  std::size_t live_tracks() const { return live_tracks_; }
  const alert::AlertManager& alerts() const { return alerts_; }
  alert::AlertManager& alerts() { return alerts_; }
  const PipelineConfig& config() const { return config_; }
  /// Single mode: the plane in use (empty until the first plausible record fixes the
  /// reference). Worldwide mode: always empty; each zone has its own.
  const std::optional<geo::Projection>& projection() const { return projection_; }

  /// Calls f(const zone::Zone&) for every zone that exists now, in key order.
  template <class F>
  void for_each_zone(F&& f) const {
    for (const ZoneWork& w : work_)
      if (w.zone) f(static_cast<const zone::Zone&>(*w.zone));
  }
  std::size_t zone_count() const { return zone_count_; }
  /// The zone whose plane holds the track's kinematics (its home), null when none.
  const zone::Zone* home_zone(track::TrackSlot slot) const;
  /// The worldwide tiling (empty in single mode).
  const std::optional<zone::ZoneTiling>& tiling() const { return tiling_; }
  /// Worldwide mode's zone margin (m, design §4.9): half the largest distance between
  /// the last reports of two aircraft that can still come into conflict. 0 in single mode.
  double zone_margin_m() const { return tiling_ ? tiling_->margin_m() : 0.0; }

  /// Search radius R_i of design §2.1 in `zone` for a track moving at plane speed
  /// `speed_mps`, in plane metres: S_h·k_max + T·(|v_i| + v_max) + 2τ (τ as an absolute
  /// bound), with the largest S_h and T of the defaults and every region (design §4.8),
  /// k_max and v_max the zone's.
  double search_radius(const zone::Zone& zone, double speed_mps) const;

  /// The parameters that judge a pair whose aircraft are in regions `ra` and `rb`
  /// (region::RegionMap indices, kNone for none), by the rule of design §4.8.
  struct PairParameters {
    probe::SeparationMinima minima;  ///< S_h in metres on the ellipsoid (not yet scaled)
    double warning_s = 0.0;
    int confirm = 0, clear = 0;
    const std::string* region = nullptr;  ///< the judging region's name; null: the defaults
    bool inhibited = false;               ///< either aircraft in an inhibition volume
  };
  PairParameters pair_parameters(std::size_t ra, std::size_t rb) const;

 private:
  /// A young run (fewer than kYoungRun records accepted) restarts from the records it
  /// refused when this many in a row were too late or outside coverage: its first record
  /// set the clock or the projection for a feed that is elsewhere (design §4.1–4.2).
  static constexpr std::size_t kYoungRun = 5;

  // ---- The track stage (1): records in order; writes the track table and the batch.
  void restart_young_run();
  /// process() after the plausibility and wall-clock checks.
  void process_plausible(const TrackReport& report);
  /// process() for a record the time guard lets through.
  void apply_record(const TrackReport& report);
  void refuse_future(const TrackReport& r);
  /// Applies the records the time guard released into guard_scratch_, in order.
  void apply_released();
  void move_clock(double t);
  /// Takes the track out of the zones and ends its alerts (the table keeps it).
  void drop_track(track::TrackSlot slot);
  /// Drops the track of `report`'s id when it carries another 24-bit address.
  void restart_if_other_aircraft(const TrackReport& report);
  /// Drops a track its source ended (TrackReport::track_end).
  void end_track(track::TrackSlot slot);
  /// Removes the track from every zone it is a member of.
  void leave_engine(track::TrackSlot slot);
  /// Places an accepted track in the zones that hold it now and asks them to probe.
  void apply(track::TrackSlot slot);
  /// The zone of `key`, created (empty, its engine starting now) when it does not exist.
  zone::Zone& zone_at(zone::ZoneKey key);
  /// The plane of a home zone (single mode's plane for key 0 there): its zone's, created
  /// when missing, or for a zone this pipeline does not work (served_longitudes) the
  /// same plane without a zone.
  const geo::Projection& home_projection(zone::ZoneKey key);
  /// A worldwide run's explicit coverage limit refuses the report.
  bool outside_limit(const TrackReport& report) const;
  /// Single mode's plane radius (m).
  double single_coverage_m() const;

  // ---- The zones (2): each on its own, in parallel.
  struct ZoneOp {
    enum class Kind : std::uint8_t { Place, Remove, Probe, Renumber };
    Kind kind;
    track::TrackSlot slot;
    std::uint32_t snapshot;  // Place, Probe: the track as of the op
    double t;                // data time of the op (the clock of its record)
  };
  struct ProbeResult {
    std::uint32_t first = 0, count = 0;  // in ZoneWork::found
    std::uint64_t candidates = 0;        // points the search returned
  };
  /// A zone and the work of the batch on it.
  struct ZoneWork {
    std::unique_ptr<zone::Zone> zone;
    std::size_t members = 0;  // as the track stage placed them
    double next_renumber = 0.0;
    bool touched = false;     // in touched_
    std::vector<ZoneOp> ops;
    std::vector<ProbeResult> probes;        // of the Probe ops, in order
    std::vector<track::TrackSlot> found;    // conflicting pairs the zone owns
    std::size_t cursor = 0;                 // the alert stage's next probe
    PhaseTimes phases;
    std::vector<kinetic::PointId> candidates;
  };
  void touch(zone::ZoneKey key);
  /// The zones, then the alert stage, over the batch taken so far.
  void run_batch();
  void run_zone(ZoneWork& work);
  /// The candidates of the track's point `self` in `zone` (design §2.1).
  void collect_candidates(ZoneWork& work, kinetic::PointId self);
  /// Tests the candidates and appends the conflicting pairs the zone owns to `found`.
  void test_candidates(ZoneWork& work, kinetic::PointId self, double now);

  // ---- The alert stage (3): records in order; writes the alert manager.
  /// What the zones and the alert stage know of a track after one of its records.
  struct Snapshot {
    track::Track track;
    zone::ProbeState base;  // everything but the plane: t, region, intent, turn, slot
  };
  struct AlertStep {
    enum class Kind : std::uint8_t { Update, DropAlerts };
    Kind kind;
    track::TrackSlot slot;
    std::uint32_t snapshot = 0;                   // Update
    std::uint32_t first_zone = 0, zone_count = 0;  // Update: in step_zones_
    double t;                                     // the clock of its record
  };
  void run_step(const AlertStep& step);
  /// ProbeMode::Brute in worldwide mode: every track within reach on the sphere, each
  /// pair judged in its owner's plane; the conflicting ones into evaluated_.
  void brute_over_sphere(track::TrackSlot slot);
  /// Evaluates evaluated_ (sorted by slot) through the alert manager.
  void evaluate_pairs(track::TrackSlot slot);
  /// The zone that judges pair (a, b) (design §4.9): the home of the midpoint of their
  /// last reported positions (single mode: zone 0).
  zone::ZoneKey owner_of(const track::Track& a, const track::Track& b) const;
  /// served_longitudes: the event's pair is this pipeline's to report.
  bool serves(const AlertEvent& event) const;
  /// Whether zone `key` holds both tracks (members of it by their last reports).
  bool holds_both(zone::ZoneKey key, const track::Track& a, const track::Track& b);
  /// The track's kinematics and point scale in `key`'s plane, at the track's last
  /// record: its own when that plane is the one it was admitted in, else projected there.
  static probe::Kinematics kinematics_in(const geo::Projection& plane, zone::ZoneKey key, const track::Track& track,
                                         double& scale);
  /// The track's probe state in zone `key`, made from the alert stage's view of it as
  /// a zone makes a member's.
  zone::ProbeState state_in(zone::ZoneKey key, track::TrackSlot slot);
  /// The probe state of a track as of snapshot `s` in the plane of zone `key`: what a
  /// zone stores for a member and the alert stage judges with, made in one place.
  static zone::ProbeState state_of(const Snapshot& s, const geo::Projection& plane, zone::ZoneKey key);
  /// The plane of zone `key`, which need not exist (brute force).
  const geo::Projection& plane_of(zone::ZoneKey key);
  /// Runs f, adding its duration to `phase` of `into` when phases are timed.
  template <class F>
  void timed(PhaseTimes& into, double PhaseTimes::*phase, F&& f) const;
  /// A pair as the probe evaluates it: lower slot first, minima scaled for the pair.
  struct PairKinematics {
    track::TrackSlot p, q;
    probe::Kinematics kp, kq;
    probe::SeparationMinima minima;  // S_h scaled for the pair
    double scale;  // the pair's projection scale
    PairParameters parameters;
  };
  PairKinematics pair_kinematics(const zone::ProbeState& self, const probe::Kinematics& k_self,
                                 const zone::ProbeState& other, double now) const;
  /// The rule of design §4.5 that turns a pair the conflict test found in conflict
  /// clear, if any: rule empty when none does.
  struct RuleVerdict {
    std::optional<PairStage> rule;  // SameAddress, LevelPair, Inhibited, SameCode, Excluded
    eligibility::Exclusion exclusion = eligibility::Exclusion::None;  // Excluded: why
    track::TrackSlot excluded = track::kNoTrack;                      // Excluded: who
  };
  RuleVerdict rule_verdict(const PairKinematics& pair) const;
  /// rule_verdict() counted in suppressed_: true when the pair is to be treated as clear.
  bool suppressed_by_rules(const PairKinematics& pair);
  /// The track stage's part of the pair watch: an accepted record of a watched track is
  /// seen, and one still without a velocity noted (it never reaches the alert stage).
  void watch_record(const TrackReport& report, track::Admission admission);
  /// Notes where every watched pair of the updated track stands (PairWatch).
  void note_watched_pairs(track::TrackSlot slot);
  /// The note of one watched pair after the update of `slot` (design §4.10).
  PairNote watched_pair_note(track::TrackSlot slot, std::string_view partner_source, std::string_view partner_id);
  void fill_event(AlertEvent& event, const geo::Projection& plane, track::TrackSlot p, track::TrackSlot q,
                  const probe::ConflictGeometry& g,
                  const probe::Kinematics& kp, const probe::Kinematics& kq, bool along_turn) const;
  /// The conflict test of one ordered pair: linear (with vertical intent), then, when
  /// the turn hypothesis is on and either aircraft turns, along the arcs.
  bool pair_in_conflict(const probe::Kinematics& kp, const probe::Kinematics& kq,
                        const probe::SeparationMinima& minima) const;
  void deliver();
  double engine_time(double t) const { return t - epoch_; }
  double tolerance_bound_m(const zone::Zone& zone) const;

  PipelineConfig config_;
  // The track stage's state.
  track::TrackTable tracks_;
  track::TimeGuard time_guard_;
  std::vector<TrackReport> guard_scratch_;
  std::vector<TrackReport> young_refused_;
  bool late_since_accepted_ = false;  // a record was refused too_late since the last accepted
  double newest_late_t_ = 0.0;        // the newest such record's time
  std::uint64_t accepted_in_run_ = 0;
  double time_ceiling_ = std::numeric_limits<double>::infinity();
  std::optional<geo::Projection> projection_;  // single mode
  std::optional<zone::ZoneTiling> tiling_;     // worldwide mode
  std::vector<bool> worked_zone_;  // served_longitudes: by key, the zones this pipeline works
  std::vector<std::optional<geo::Projection>> unworked_planes_;  // by key, made on first use
  std::optional<geo::GeodeticPosition> coverage_centre_;  // of the reference or first record
  std::vector<ZoneWork> work_;  // by zone key
  std::size_t zone_count_ = 0;
  kinetic::KineticStatistics retired_kinetic_;  // counters of zones no longer there
  std::vector<std::vector<zone::ZoneKey>> members_;  // by slot: the zones holding the track
  zone::ZoneKeys zones_scratch_;
  std::size_t live_tracks_ = 0;
  // The batch: what the track stage took, for the zones and the alert stage.
  std::vector<Snapshot> snapshots_;
  std::vector<AlertStep> steps_;
  std::vector<zone::ZoneKey> step_zones_;
  std::vector<zone::ZoneKey> touched_;  // zones with work in the batch, or created in it
  std::size_t prompt_left_ = 0;         // records still to judge one by one (prompt_records)
  std::unique_ptr<util::WorkerPool> pool_;
  // The alert stage's state.
  std::vector<Snapshot> view_;  // by slot: each track as of the step being judged
  double judged_at_ = 0.0;      // the clock of that step
  alert::AlertManager alerts_;
  /// A pair the alert manager must see: the other track and the zone that judges it
  /// (kNoZone: none holds both, too far apart to conflict).
  struct Evaluated {
    track::TrackSlot other;
    zone::ZoneKey zone;
  };
  std::vector<Evaluated> evaluated_;  // in slot order once sorted
  std::vector<track::TrackSlot> partners_scratch_;
  std::vector<std::optional<geo::Projection>> brute_planes_;  // planes of zones not there
  double brute_reach_m_ = 0.0;  // worldwide ProbeMode::Brute: pairs within this (m)
  region::RegionMap regions_;
  std::vector<PairParameters> region_parameters_;  // by region index; the defaults last
  double largest_horizontal_m_ = 0.0;              // S_h and T of the search radius
  double largest_lookahead_s_ = 0.0;
  eligibility::Rules rules_;
  Rejections suppressed_;
  ConflictTap conflict_tap_;
  PairWatch* watch_ = nullptr;
  std::vector<AlertEvent> pending_events_;
  AlertSink sink_;
  double epoch_ = 0.0;  // engine time = data time − epoch (design §4.1: local time frames)
  bool started_ = false;
  double clock_ = 0.0;
  PipelineStatistics stats_;
  PhaseTimes phases_;
};

}  // namespace kew
