#include "kew/pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <stdexcept>
#include <cmath>

#include <fmt/format.h>

#include "kew/geometry/hilbert.hpp"
#include "kew/util/gentle_growth.hpp"

namespace kew {

namespace {
constexpr double kFootToMetre = 0.3048;
// Widens R_i so that rounding in positions and speeds can never drop a pair whose CPA
// test is positive (metres; far below any separation minimum).
constexpr double kSearchSlack_m = 1.0;
// The largest point scale of a zone's plane (design §4.9: below 1.02) with room to spare,
// and the zone margin's own slack (m).
constexpr double kScaleBound = 1.05;
constexpr double kMarginSlack_m = 1000.0;
// ProbeMode::Brute in worldwide mode evaluates every pair whose last reports are within
// twice the distance at which two aircraft can still come into conflict, plus this (m).
constexpr double kBruteSlack_m = 50e3;
constexpr double kEarthRadius_m = 6371008.8;  // mean radius, for the brute force's cut only
// A batch with fewer zone operations than this runs on the calling thread alone.
constexpr std::size_t kParallelOps = 48;

geo::GeodeticPosition rounded_reference(const TrackReport& r) {
  return {std::round(r.lat_deg * 10.0) / 10.0, std::round(r.lon_deg * 10.0) / 10.0};
}

AlertParty party_of(const track::Track& t) {
  AlertParty p;
  p.id = t.id;
  p.source = t.source;
  p.callsign = t.callsign;
  p.track_number = t.number;
  p.lat_deg = t.lat_deg;
  p.lon_deg = t.lon_deg;
  p.alt_ft = t.alt_ft;
  p.gs_kt = t.gs_kt;
  p.trk_deg = t.trk_deg;
  p.vr_fpm = t.vr_fpm;
  return p;
}

bool ordered_before(const track::Track& x, const track::Track& y) {
  return x.source != y.source ? x.source < y.source : x.id < y.id;
}
}  // namespace

Pipeline::Pipeline(const PipelineConfig& config)
    : config_(config),
      tracks_(config.tracks),
      time_guard_(config.tracks.max_time_jump_s, config.tracks.max_lateness_s, track::kTimeJumpConfirm),
      alerts_(config.alerts, [this](track::TrackSlot slot) {
        // The alert stage names parties as they were when it judged them.
        const track::Track& track = view_[slot].track;
        return alert::PartyName{track.source, track.id};
      }),
      regions_(config.regions),
      rules_(config.eligibility, config.minima) {
  // Each region's parameters resolved against the defaults once; the defaults last.
  PairParameters defaults;
  defaults.minima = config_.minima;
  defaults.warning_s = config_.alerts.warning_s;
  defaults.confirm = config_.alerts.confirm;
  defaults.clear = config_.alerts.clear;
  largest_horizontal_m_ = defaults.minima.horizontal_m;
  largest_lookahead_s_ = defaults.minima.lookahead_s;
  for (const region::Region& r : regions_.regions()) {
    PairParameters p = defaults;
    const region::RegionParameters& set = r.parameters;
    p.minima.horizontal_m = set.horizontal_m.value_or(p.minima.horizontal_m);
    p.minima.vertical_m = set.vertical_m.value_or(p.minima.vertical_m);
    p.minima.lookahead_s = set.lookahead_s.value_or(p.minima.lookahead_s);
    p.warning_s = set.warning_s.value_or(p.warning_s);
    p.confirm = set.confirm.value_or(p.confirm);
    p.clear = set.clear.value_or(p.clear);
    p.region = &r.name;
    p.inhibited = r.inhibit;
    largest_horizontal_m_ = std::max(largest_horizontal_m_, p.minima.horizontal_m);
    largest_lookahead_s_ = std::max(largest_lookahead_s_, p.minima.lookahead_s);
    region_parameters_.push_back(p);
  }
  region_parameters_.push_back(defaults);
  if (config_.zone_mode == ZoneMode::Worldwide) {
    // Two aircraft whose last reports are D apart can come within S_h of each other
    // within T only if D ≤ S_h + (v_i + v_j)·(T + age), each report at most the track
    // timeout old and every speed at most max_ground_speed_kt (faster reports lose the
    // speed, faster derived ones reset the track, design §4.3). The midpoint of such a
    // pair is within D/2 of both, so a margin of D/2 holds both in the midpoint's zone.
    const double fastest_mps = config_.tracks.max_ground_speed_kt * (1852.0 / 3600.0);
    const double margin = 0.5 * largest_horizontal_m_ * kScaleBound +
                          fastest_mps * (largest_lookahead_s_ + config_.tracks.track_timeout_s) + kMarginSlack_m;
    tiling_.emplace(margin);
    if (config_.served_longitudes) {
      // One core width beyond the band: an alert's pair moves far less while it lasts,
      // so the zones that judged it before its midpoint entered the band are worked too.
      const LongitudeBand band = *config_.served_longitudes;
      worked_zone_.assign(zone::ZoneTiling::key_end(), false);
      unworked_planes_.resize(zone::ZoneTiling::key_end());
      for (zone::ZoneKey key = 0; key < zone::ZoneTiling::key_end(); ++key) {
        if (!tiling_->valid(key)) continue;
        const zone::ZoneTiling::Core core = tiling_->core(key);
        const double width = core.east_deg - core.west_deg;
        bool worked = width >= 360.0;  // a cap
        for (const double shift : {-360.0, 0.0, 360.0})
          worked = worked || (core.west_deg - width + shift < band.east_deg && band.west_deg < core.east_deg + width + shift);
        worked_zone_[key] = worked;
      }
    }
    brute_reach_m_ = 2.0 * (largest_horizontal_m_ + 2.0 * fastest_mps * (largest_lookahead_s_ + config_.tracks.track_timeout_s)) +
                     kBruteSlack_m;
    work_.resize(zone::ZoneTiling::key_end());
  } else {
    work_.resize(1);
  }
  if (config_.threads > 1) pool_ = std::make_unique<util::WorkerPool>(config_.threads);
  prompt_left_ = config_.prompt_records;
}

Pipeline::~Pipeline() = default;

double Pipeline::single_coverage_m() const {
  return config_.coverage_radius_m.value_or(PipelineConfig::kSingleCoverage_m);
}

Pipeline::PairParameters Pipeline::pair_parameters(std::size_t ra, std::size_t rb) const {
  const std::size_t none = region_parameters_.size() - 1;
  const PairParameters& a = region_parameters_[ra == region::RegionMap::kNone ? none : ra];
  const PairParameters& b = region_parameters_[rb == region::RegionMap::kNone ? none : rb];
  if (&a == &b) return a;
  // Different regions: the stricter of each parameter (design §4.8).
  PairParameters p = a;
  p.minima.horizontal_m = std::max(a.minima.horizontal_m, b.minima.horizontal_m);
  p.minima.vertical_m = std::max(a.minima.vertical_m, b.minima.vertical_m);
  p.minima.lookahead_s = std::max(a.minima.lookahead_s, b.minima.lookahead_s);
  p.warning_s = std::max(a.warning_s, b.warning_s);
  p.confirm = std::min(a.confirm, b.confirm);
  p.clear = std::max(a.clear, b.clear);
  p.region = a.region ? a.region : b.region;
  if (a.region && b.region) p.region = *a.region < *b.region ? a.region : b.region;
  p.inhibited = a.inhibited || b.inhibited;
  return p;
}

bool Pipeline::pair_in_conflict(const probe::Kinematics& kp, const probe::Kinematics& kq,
                                const probe::SeparationMinima& minima) const {
  if (probe::in_conflict(kp, kq, minima)) return true;
  return config_.turn.enabled && (kp.turn_rate_rps != 0.0 || kq.turn_rate_rps != 0.0) &&
         probe::in_turn_conflict(kp, kq, minima);
}

double Pipeline::tolerance_bound_m(const zone::Zone& zone) const {
  const kinetic::KineticConfig& k = config_.kinetic;
  if (k.tolerance_mode == kinetic::ToleranceMode::Absolute) return k.tolerance;
  // Relative τ bounds the lag by τ·|p|, and |p| is at most the plane radius of coverage.
  const geo::Projection& plane = zone.projection();
  return k.tolerance * plane.coverage_radius_m() * plane.max_scale() * 1.05;
}

double Pipeline::search_radius(const zone::Zone& zone, double speed_mps) const {
  return largest_horizontal_m_ * zone.projection().max_scale() + largest_lookahead_s_ * (speed_mps + zone.fastest_mps()) +
         2.0 * tolerance_bound_m(zone) + kSearchSlack_m;
}

// ---------------------------------------------------------------------------------------
// The track stage.

void Pipeline::process(const TrackReport& report) {
  ++stats_.records;
  const std::string_view problem = tracks_.plausibility_problem(report);
  if (!problem.empty()) {
    tracks_.rejections().reject(problem, report.id);
    return;
  }
  if (report.t > time_ceiling_) {
    refuse_future(report);
    return;
  }
  process_plausible(report);
  if (young_refused_.size() >= kYoungRun) restart_young_run();
  if (prompt_left_ > 0) {
    --prompt_left_;
    run_batch();
  } else if (steps_.size() >= config_.batch_records) {
    run_batch();
  }
}

void Pipeline::restart_young_run() {
  // Without a configured reference the first record fixed the plane, and it always
  // started the clock: a stray one (a position at −45°, 170° in a European feed, a date
  // in 2100) would refuse every record after it. The run has shown nothing yet; start it
  // again from the records it refused, which agree with one another.
  std::vector<TrackReport> refused = std::move(young_refused_);
  young_refused_.clear();
  drop_all();
  // Held ahead of a clock that is being discarded. A local copy: process_plausible()
  // reuses guard_scratch_.
  std::vector<TrackReport> held;
  time_guard_.release(held);
  if (!config_.reference) {
    projection_.reset();
    coverage_centre_.reset();
  }
  // drop_all() emptied every zone: the new run's zones start with its clock, and so do
  // their counters and renumbering schedules.
  for (ZoneWork& w : work_) w = ZoneWork{};
  zone_count_ = 0;
  retired_kinetic_ = {};
  started_ = false;
  accepted_in_run_ = 0;
  late_since_accepted_ = false;
  ++stats_.runs_restarted;
  for (const TrackReport& r : refused) process_plausible(r);
  for (const TrackReport& r : held) process_plausible(r);
}

void Pipeline::process_plausible(const TrackReport& report) {
  if (!started_) {
    apply_record(report);
    return;
  }
  if (time_guard_.held() != 0) {
    guard_scratch_.clear();
    time_guard_.refuse_contradicted(report.t, guard_scratch_);
    for (const TrackReport& r : guard_scratch_) refuse_future(r);
  }
  if (time_guard_.ahead(report.t, clock_)) {
    if (time_guard_.hold(report)) {
      guard_scratch_.clear();
      time_guard_.release(guard_scratch_);
      apply_released();
    }
    return;
  }
  apply_record(report);
  // Held records this record's time has caught up with are no jump any more.
  while (time_guard_.held() != 0) {
    guard_scratch_.clear();
    time_guard_.release_reached(clock_, guard_scratch_);
    if (guard_scratch_.empty()) break;
    apply_released();
  }
}

void Pipeline::refuse_future(const TrackReport& r) {
  tracks_.rejections().reject("future_time", r.id);
}

void Pipeline::apply_released() {
  // apply_record() never reaches the guard, so the scratch is not reused meanwhile.
  for (const TrackReport& r : guard_scratch_) apply_record(r);
}

void Pipeline::end_of_input() {
  // Nothing contradicted them, and at the end of the input they can blind nothing.
  guard_scratch_.clear();
  time_guard_.release(guard_scratch_);
  apply_released();
  flush();
}

void Pipeline::apply_record(const TrackReport& report) {
  if (!started_) {
    started_ = true;
    epoch_ = std::floor(report.t);
    clock_ = epoch_;
  }
  if (!coverage_centre_) coverage_centre_ = config_.reference.value_or(rounded_reference(report));
  if (config_.zone_mode == ZoneMode::Single && !projection_) {
    projection_.emplace(*coverage_centre_, single_coverage_m());
    zone_at(0);
  }
  // A plausible record that is not too late moves the clock (and may time out other
  // tracks, or this record's own previous track) before it is applied.
  if (report.t >= clock_ - tracks_.config().max_lateness_s) move_clock(std::max(clock_, report.t));
  restart_if_other_aircraft(report);

  track::AdmitResult admitted;
  if (outside_limit(report)) {
    tracks_.rejections().reject("outside_coverage", report.id);
    admitted.refusal = "outside_coverage";
  } else {
    const zone::ZoneKey home = tiling_ ? tiling_->home({report.lat_deg, report.lon_deg}) : 0;
    admitted = tracks_.admit(report, clock_, home_projection(home), home);
  }
  if (admitted.admission == track::Admission::Rejected) {
    if (admitted.refusal == "too_late") {
      newest_late_t_ = late_since_accepted_ ? std::max(newest_late_t_, report.t) : report.t;
      late_since_accepted_ = true;
    }
    // A configured reference cannot move: only a clock set by a stray record can.
    const bool elsewhere = admitted.refusal == "too_late" ||
                           (admitted.refusal == "outside_coverage" && !config_.reference);
    if (accepted_in_run_ < kYoungRun && elsewhere) young_refused_.push_back(report);
    // The source ended the track: so it is, even when this last record is refused
    // (a repeated time, say); otherwise it would linger until the timeout.
    if (report.track_end) {
      const track::TrackSlot slot = tracks_.find(report.source, report.id);
      if (slot != track::kNoTrack) end_track(slot);
    }
    return;
  }
  ++stats_.accepted;
  ++accepted_in_run_;
  young_refused_.clear();
  late_since_accepted_ = false;
  stats_.last_data_time = clock_;
  if (watch_) watch_record(report, admitted.admission);
  if (admitted.admission == track::Admission::AwaitingVelocity) {
    ++stats_.awaiting_velocity;
    if (tracks_[admitted.slot].in_engine) {
      // Velocity reset: the track leaves the probe until it has a velocity again.
      leave_engine(admitted.slot);
      steps_.push_back({AlertStep::Kind::DropAlerts, admitted.slot, 0, 0, 0, clock_});
    }
    if (report.track_end) end_track(admitted.slot);
    return;
  }
  apply(admitted.slot);
  if (report.track_end) end_track(admitted.slot);
}

bool Pipeline::outside_limit(const TrackReport& report) const {
  // Single mode's plane refuses what lies beyond it (TrackTable::admit).
  if (config_.zone_mode == ZoneMode::Single || !config_.coverage_radius_m) return false;
  return geo::Projection::geodesic_distance_m(*coverage_centre_, {report.lat_deg, report.lon_deg}) >
         *config_.coverage_radius_m;
}

const geo::Projection& Pipeline::home_projection(zone::ZoneKey key) {
  if (worked_zone_.empty() || worked_zone_[key]) return zone_at(key).projection();
  // A zone this pipeline does not work still gives its tracks their kinematics, on the
  // very plane its zone would have: a track entering the worked zones is the same track
  // as in a pipeline that works them all.
  std::optional<geo::Projection>& plane = unworked_planes_[key];
  if (!plane) plane.emplace(tiling_->centre(key), tiling_->extent_m(key));
  return *plane;
}

void Pipeline::touch(zone::ZoneKey key) {
  ZoneWork& w = work_[key];
  if (w.touched) return;
  w.touched = true;
  touched_.push_back(key);
}

zone::Zone& Pipeline::zone_at(zone::ZoneKey key) {
  ZoneWork& w = work_[key];
  if (!w.zone) {
    if (tiling_) {
      w.zone = std::make_unique<zone::Zone>(key, tiling_->name(key),
                                            geo::Projection(tiling_->centre(key), tiling_->extent_m(key)),
                                            config_.kinetic, engine_time(clock_));
    } else {
      w.zone = std::make_unique<zone::Zone>(key, "single", *projection_, config_.kinetic, engine_time(clock_));
    }
    ++zone_count_;
    ++stats_.zones_created;
    touch(key);  // retired at the end of the batch if nothing joins it
  }
  return *w.zone;
}

void Pipeline::restart_if_other_aircraft(const TrackReport& report) {
  if (!report.address || report.t < clock_ - tracks_.config().max_lateness_s) return;  // admit() refuses it
  const track::TrackSlot slot = tracks_.find(report.source, report.id);
  if (slot == track::kNoTrack) return;
  const track::Track& track = tracks_[slot];
  // Two 24-bit addresses are never one aircraft: the id was reused (design §4.5).
  if (!track.address || *track.address == *report.address) return;
  // Keep the old track when admit() is going to refuse the record anyway.
  if (outside_limit(report)) return;
  if (projection_) {
    geo::ProjectionError error = geo::ProjectionError::None;
    (void)projection_->project({report.lat_deg, report.lon_deg}, error);
    if (error != geo::ProjectionError::None) return;
  }
  ++stats_.tracks_restarted;
  drop_track(slot);
  tracks_.drop(slot);
}

void Pipeline::end_track(track::TrackSlot slot) {
  ++stats_.tracks_ended;
  drop_track(slot);
  tracks_.drop(slot);
}

namespace {
/// CPU time of the calling thread (s): the split must not count time the thread waited.
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

template <class F>
void Pipeline::timed(PhaseTimes& into, double PhaseTimes::*phase, F&& f) const {
  if (!config_.time_phases) {
    f();
    return;
  }
  const double start = thread_cpu_s();
  f();
  into.*phase += thread_cpu_s() - start;
}

void Pipeline::move_clock(double t) {
  if (t <= clock_) return;
  // A zone's engine advances to the time of each operation on it (insert, update and
  // remove advance first), and to the clock at the end of a batch.
  tracks_.expire(t, [&](track::TrackSlot slot, const track::Track& track) {
    clock_ = std::max(clock_, track.t + tracks_.config().track_timeout_s);
    drop_track(slot);
  });
  clock_ = t;
  if (config_.renumber_every_s > 0.0) {
    for (std::size_t key = 0; key < work_.size(); ++key) {
      ZoneWork& w = work_[key];
      if (!w.zone || clock_ < w.next_renumber) continue;
      if (w.next_renumber > 0.0) {
        w.ops.push_back({ZoneOp::Kind::Renumber, track::kNoTrack, 0, clock_});
        touch(static_cast<zone::ZoneKey>(key));
      }
      w.next_renumber = clock_ + config_.renumber_every_s;
    }
  }
}

void Pipeline::advance_to(double t) {
  if (!started_ || !std::isfinite(t)) return;
  // Records arriving too late since the last accepted one (a feed whose delay grew by
  // more than max_lateness_s) must be able to catch up: the tick may not carry the clock
  // beyond their reach, or they would be refused for ever.
  if (late_since_accepted_) t = std::min(t, newest_late_t_ + tracks_.config().max_lateness_s);
  move_clock(t);
  flush();
}

void Pipeline::leave_engine(track::TrackSlot slot) {
  track::Track& track = tracks_[slot];
  if (!track.in_engine) return;
  for (const zone::ZoneKey key : members_[slot]) {
    ZoneWork& w = work_[key];
    w.ops.push_back({ZoneOp::Kind::Remove, slot, 0, clock_});
    --w.members;
    touch(key);
  }
  members_[slot].clear();
  track.in_engine = false;
  --live_tracks_;
}

void Pipeline::drop_track(track::TrackSlot slot) {
  const bool in_engine = tracks_[slot].in_engine;
  leave_engine(slot);
  // A track that never had a velocity has no alerts.
  if (in_engine) steps_.push_back({AlertStep::Kind::DropAlerts, slot, 0, 0, 0, clock_});
  ++stats_.tracks_dropped;
}

void Pipeline::drop_all() {
  for (track::TrackSlot slot = 0; slot < tracks_.slot_end(); ++slot) {
    if (!tracks_[slot].in_use) continue;
    drop_track(slot);
    tracks_.drop(slot);
  }
  flush();
}

void Pipeline::apply(track::TrackSlot slot) {
  track::Track& track = tracks_[slot];
  util::grow_to(members_, static_cast<std::size_t>(slot) + 1);
  std::vector<zone::ZoneKey>& members = members_[slot];
  if (!track.in_engine) ++live_tracks_;
  track.in_engine = true;
  // The zones that hold the track now (design §4.9): it leaves the others first.
  zones_scratch_.clear();
  if (tiling_) tiling_->zones_near({track.lat_deg, track.lon_deg}, zones_scratch_);
  else zones_scratch_.push_back(0);
  if (!worked_zone_.empty())
    std::erase_if(zones_scratch_, [&](zone::ZoneKey key) { return !worked_zone_[key]; });
  for (const zone::ZoneKey key : members) {
    if (std::find(zones_scratch_.begin(), zones_scratch_.end(), key) != zones_scratch_.end()) continue;
    ZoneWork& w = work_[key];
    w.ops.push_back({ZoneOp::Kind::Remove, slot, 0, clock_});
    --w.members;
    touch(key);
  }
  // What every zone's probe state shares, whatever its plane; and the track as the
  // alert stage will judge it.
  const auto snapshot = static_cast<std::uint32_t>(snapshots_.size());
  Snapshot& s = snapshots_.emplace_back();
  s.track = track;
  s.base.t = track.t;
  s.base.level_off_until_t = track.intent.sel_t + config_.tracks.intent.max_age_s;
  s.base.lat_deg = track.lat_deg;
  s.base.lon_deg = track.lon_deg;
  s.base.region = regions_.empty() ? region::RegionMap::kNone : regions_.locate(track.lat_deg, track.lon_deg, track.alt_ft);
  s.base.slot = slot;
  if (config_.turn.enabled && track.turn_rate_dps && std::abs(*track.turn_rate_dps) >= config_.turn.min_rate_dps)
    s.base.kinematics.turn_rate_rps = -*track.turn_rate_dps * (M_PI / 180.0);  // clockwise over ground
  const auto first_zone = static_cast<std::uint32_t>(step_zones_.size());
  for (const zone::ZoneKey key : zones_scratch_) {
    zone_at(key);
    ZoneWork& w = work_[key];
    if (std::find(members.begin(), members.end(), key) == members.end()) ++w.members;
    w.ops.push_back({ZoneOp::Kind::Place, slot, snapshot, clock_});
    w.ops.push_back({ZoneOp::Kind::Probe, slot, snapshot, clock_});
    touch(key);
    step_zones_.push_back(key);
  }
  members.assign(zones_scratch_.begin(), zones_scratch_.end());
  steps_.push_back({AlertStep::Kind::Update, slot, snapshot, first_zone,
                    static_cast<std::uint32_t>(zones_scratch_.size()), clock_});
}

// ---------------------------------------------------------------------------------------
// The batch: zones in parallel, then the alert stage in record order.

void Pipeline::flush() {
  run_batch();
  prompt_left_ = config_.prompt_records;
}

void Pipeline::run_batch() {
  if (touched_.empty() && steps_.empty()) return;
  const auto run_one = [&](std::size_t i) { run_zone(work_[touched_[i]]); };
  std::size_t ops = 0;
  for (const zone::ZoneKey key : touched_) ops += work_[key].ops.size();
  // Waking the workers costs more than a few operations take (a live feed's batch after
  // one read holds a handful of records): those run here.
  if (pool_ && ops >= kParallelOps) {
    // The zones with the most work first, so that the last ones to finish are small.
    std::stable_sort(touched_.begin(), touched_.end(), [&](zone::ZoneKey a, zone::ZoneKey b) {
      return work_[a].ops.size() > work_[b].ops.size();
    });
    pool_->run(touched_.size(), run_one);
  } else {
    for (std::size_t i = 0; i < touched_.size(); ++i) run_one(i);
  }
  for (const zone::ZoneKey key : touched_) {
    PhaseTimes& p = work_[key].phases;
    phases_.maintenance_s += p.maintenance_s;
    phases_.search_s += p.search_s;
    phases_.tests_s += p.tests_s;
    p = {};
  }
  timed(phases_, &PhaseTimes::tests_s, [&] {
    for (const AlertStep& step : steps_) run_step(step);
  });
  for (const zone::ZoneKey key : touched_) {
    ZoneWork& w = work_[key];
    w.touched = false;
    w.ops.clear();
    w.probes.clear();
    w.found.clear();
    w.cursor = 0;
    // The single zone stays: its engine's counters are the run's, as they always were.
    if (w.zone && w.members == 0 && tiling_) {
      add_statistics(retired_kinetic_, w.zone->kinetic_statistics());
      w.zone.reset();
      w.next_renumber = 0.0;
      --zone_count_;
      ++stats_.zones_retired;
    }
  }
  touched_.clear();
  steps_.clear();
  step_zones_.clear();
  snapshots_.clear();
}

void Pipeline::run_zone(ZoneWork& w) {
  zone::Zone& zone = *w.zone;
  const auto started = std::chrono::steady_clock::now();
  for (const ZoneOp& op : w.ops) {
    switch (op.kind) {
      case ZoneOp::Kind::Place: {
        const Snapshot& s = snapshots_[op.snapshot];
        const zone::ProbeState made = state_of(s, zone.projection(), zone.key());
        kinetic::PointId point = kinetic::kNoPoint;
        timed(w.phases, &PhaseTimes::maintenance_s, [&] {
          point = zone.place(op.slot, engine_time(op.t), probe::extrapolated(made.kinematics, op.t - s.track.t));
        });
        zone.state(point) = made;
        break;
      }
      case ZoneOp::Kind::Remove:
        timed(w.phases, &PhaseTimes::maintenance_s, [&] { zone.remove(op.slot, engine_time(op.t)); });
        break;
      case ZoneOp::Kind::Renumber:
        timed(w.phases, &PhaseTimes::maintenance_s, [&] { zone.renumber(engine_time(op.t), op.t); });
        break;
      case ZoneOp::Kind::Probe: {
        ProbeResult result;
        result.first = static_cast<std::uint32_t>(w.found.size());
        // Worldwide brute force is the alert stage's (brute_over_sphere).
        if (!(tiling_ && config_.probe_mode == probe::ProbeMode::Brute)) {
          const kinetic::PointId self = zone.point_of(op.slot);
          timed(w.phases, &PhaseTimes::search_s, [&] { collect_candidates(w, self); });
          timed(w.phases, &PhaseTimes::tests_s, [&] { test_candidates(w, self, op.t); });
          result.candidates = w.candidates.size();
        }
        result.count = static_cast<std::uint32_t>(w.found.size()) - result.first;
        w.probes.push_back(result);
        ++zone.statistics().probes;
        break;
      }
    }
  }
  timed(w.phases, &PhaseTimes::maintenance_s, [&] { zone.advance(engine_time(clock_)); });
  zone.statistics().busy_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void Pipeline::collect_candidates(ZoneWork& w, kinetic::PointId self) {
  zone::Zone& zone = *w.zone;
  const zone::ProbeState& state = zone.state(self);
  w.candidates.clear();
  // Each point once, never the track's own (within() marks what it visited).
  switch (config_.probe_mode) {
    case probe::ProbeMode::Exact:
      // Straight-line prediction: every j that can come within S_h of i within T is within
      // S_h + v_max·T (+ 2τ) of i's position T ahead (design §2.1), a disk that is smaller
      // the faster i flies; an arc stays only within |v_i|·T of its start.
      if (config_.search_ahead && state.kinematics.turn_rate_rps == 0.0) {
        const geometry::Point2 ahead = zone.engine().position_now(self) + largest_lookahead_s_ * state.kinematics.velocity;
        zone.search().within_around(zone.engine(), self, ahead, search_radius(zone, 0.0), w.candidates);
      } else {
        zone.search().within(zone.engine(), self, search_radius(zone, geometry::norm(state.kinematics.velocity)),
                             w.candidates);
      }
      break;
    case probe::ProbeMode::Edges:
      zone.search().neighbours(zone.engine(), self, w.candidates);
      // A few points; within() gives each once by construction, this makes sure here.
      std::sort(w.candidates.begin(), w.candidates.end());
      w.candidates.erase(std::unique(w.candidates.begin(), w.candidates.end()), w.candidates.end());
      break;
    case probe::ProbeMode::Brute:  // one plane; worldwide: brute_over_sphere()
      for (kinetic::PointId other = 0; other < zone.point_end(); ++other)
        if (zone.slot_of(other) != zone::kNoSlot && other != self) w.candidates.push_back(other);
      break;
  }
}

void Pipeline::test_candidates(ZoneWork& w, kinetic::PointId self_point, double now) {
  zone::Zone& zone = *w.zone;
  const zone::ProbeState& self = zone.state(self_point);
  const probe::Kinematics k_self = self.at(now);
  const track::TrackSlot slot = self.slot;
  // Most candidates are clear: only pairs in conflict go on to the alert stage, which
  // adds the partners and sorts the few by slot (design §2.5).
  constexpr std::size_t kPrefetchAhead = 4;  // the candidates are scattered in memory
  const std::vector<kinetic::PointId>& candidates = w.candidates;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i + kPrefetchAhead < candidates.size()) {
      const zone::ProbeState* ahead = &zone.state(candidates[i + kPrefetchAhead]);
      __builtin_prefetch(ahead);
      __builtin_prefetch(reinterpret_cast<const char*>(ahead) + 64);
    }
    const zone::ProbeState& them = zone.state(candidates[i]);
    const track::TrackSlot other = them.slot;
    const probe::Kinematics k_other = them.at(now);
    probe::SeparationMinima minima =
        regions_.empty() ? config_.minima : pair_parameters(self.region, them.region).minima;
    if (probe::vertically_apart_for_ever(k_self, k_other, minima)) continue;
    minima.horizontal_m *= geo::Projection::pair_scale(self.scale, them.scale);
    if (slot < other ? !pair_in_conflict(k_self, k_other, minima) : !pair_in_conflict(k_other, k_self, minima)) continue;
    // In conflict here: judged here only when this zone owns the pair (design §4.9).
    if (tiling_ &&
        tiling_->owner({self.lat_deg, self.lon_deg}, {them.lat_deg, them.lon_deg}) !=
            zone.key())
      continue;
    w.found.push_back(other);
  }
}

// ---------------------------------------------------------------------------------------
// The alert stage.

void Pipeline::run_step(const AlertStep& step) {
  judged_at_ = step.t;
  if (step.kind == AlertStep::Kind::DropAlerts) {
    view_[step.slot].track.in_engine = false;
    alerts_.drop_track(step.slot, step.t, pending_events_);
    deliver();
    return;
  }
  const track::TrackSlot slot = step.slot;
  util::grow_to(view_, static_cast<std::size_t>(slot) + 1);
  view_[slot] = std::move(snapshots_[step.snapshot]);
  ++stats_.probes;
  evaluated_.clear();
  for (std::uint32_t i = step.first_zone; i < step.first_zone + step.zone_count; ++i) {
    ZoneWork& w = work_[step_zones_[i]];
    const ProbeResult& r = w.probes[w.cursor++];
    stats_.candidates += r.candidates;
    for (std::uint32_t f = r.first; f < r.first + r.count; ++f) evaluated_.push_back({w.found[f], step_zones_[i]});
  }
  const bool brute_sphere = tiling_ && config_.probe_mode == probe::ProbeMode::Brute;
  if (brute_sphere) brute_over_sphere(slot);
  // Pairs pending confirmation or alerting are always evaluated, so they see their clear
  // evaluations even when the search (edges mode) does not return them: each once, in
  // the zone that owns it.
  partners_scratch_.clear();
  alerts_.partners_of(slot, partners_scratch_);
  const std::size_t found = evaluated_.size();
  for (const track::TrackSlot other : partners_scratch_) {
    const auto end = evaluated_.begin() + static_cast<std::ptrdiff_t>(found);
    if (std::find_if(evaluated_.begin(), end, [&](const Evaluated& e) { return e.other == other; }) != end) continue;
    ++stats_.candidates;  // the search did not find it in conflict
    // A pair no zone holds whole is too far apart to be in conflict (design §4.9) and
    // is evaluated clear.
    const zone::ZoneKey owner = owner_of(view_[slot].track, view_[other].track);
    const bool held = brute_sphere || holds_both(owner, view_[slot].track, view_[other].track);
    evaluated_.push_back({other, held ? owner : zone::kNoZone});
  }
  evaluate_pairs(slot);
  if (watch_) note_watched_pairs(slot);
}

zone::ZoneKey Pipeline::owner_of(const track::Track& a, const track::Track& b) const {
  if (!tiling_) return 0;
  return tiling_->owner({a.lat_deg, a.lon_deg}, {b.lat_deg, b.lon_deg});
}

bool Pipeline::holds_both(zone::ZoneKey key, const track::Track& a, const track::Track& b) {
  if (!tiling_) return true;
  for (const track::Track* t : {&a, &b}) {
    tiling_->zones_near({t->lat_deg, t->lon_deg}, zones_scratch_);
    if (std::find(zones_scratch_.begin(), zones_scratch_.end(), key) == zones_scratch_.end()) return false;
  }
  return true;
}

void Pipeline::brute_over_sphere(track::TrackSlot slot) {
  // The oracle of the zoned search: every pair within reach on the sphere is judged in
  // its owner's plane, each track projected there as a zone projects a member, whatever
  // the memberships: a margin too narrow shows as a difference from the exact search.
  const auto unit = [](const track::Track& t, double v[3]) {
    const double lat = t.lat_deg * (M_PI / 180.0), lon = t.lon_deg * (M_PI / 180.0);
    v[0] = std::cos(lat) * std::cos(lon);
    v[1] = std::cos(lat) * std::sin(lon);
    v[2] = std::sin(lat);
  };
  double u[3];
  unit(view_[slot].track, u);
  const double min_cos = std::cos(brute_reach_m_ / kEarthRadius_m);
  zone::ZoneKey self_plane = zone::kNoZone;  // the owner `self` was made for
  zone::ProbeState self;
  for (track::TrackSlot other = 0; other < view_.size(); ++other) {
    if (other == slot || !view_[other].track.in_engine) continue;
    double w[3];
    unit(view_[other].track, w);
    if (u[0] * w[0] + u[1] * w[1] + u[2] * w[2] < min_cos) continue;
    ++stats_.candidates;
    const zone::ZoneKey owner = owner_of(view_[slot].track, view_[other].track);
    if (owner != self_plane) {
      self = state_in(owner, slot);
      self_plane = owner;
    }
    const PairKinematics pair = pair_kinematics(self, self.at(judged_at_), state_in(owner, other), judged_at_);
    if (pair_in_conflict(pair.kp, pair.kq, pair.minima)) evaluated_.push_back({other, owner});
  }
}

const geo::Projection& Pipeline::plane_of(zone::ZoneKey key) {
  if (work_[key].zone) return work_[key].zone->projection();
  util::grow_to(brute_planes_, work_.size());
  if (!brute_planes_[key]) brute_planes_[key].emplace(tiling_->centre(key), tiling_->extent_m(key));
  return *brute_planes_[key];
}

zone::ProbeState Pipeline::state_in(zone::ZoneKey key, track::TrackSlot slot) {
  return state_of(view_[slot], plane_of(key), key);
}

zone::ProbeState Pipeline::state_of(const Snapshot& s, const geo::Projection& plane, zone::ZoneKey key) {
  zone::ProbeState state = s.base;
  state.kinematics = kinematics_in(plane, key, s.track, state.scale);
  state.kinematics.turn_rate_rps = s.base.kinematics.turn_rate_rps;
  return state;
}

probe::Kinematics Pipeline::kinematics_in(const geo::Projection& plane, zone::ZoneKey key, const track::Track& track,
                                          double& scale) {
  if (track.plane == key) {
    scale = track.plane_scale;
    return track.kinematics;
  }
  // Another zone's plane: the reported position projected there, the ground velocity
  // the track's own plane gave, turned and scaled for this one (both are conformal).
  geo::ProjectionError ignored = geo::ProjectionError::None;
  const geo::PlanePosition at = plane.project({track.lat_deg, track.lon_deg}, ignored);
  probe::Kinematics k = track.kinematics;
  k.position = at.p;
  k.velocity = plane.velocity_to_plane(at, track.gs_kt * (1852.0 / 3600.0), track.trk_deg);
  scale = at.scale;
  return k;
}

Pipeline::PairKinematics Pipeline::pair_kinematics(const zone::ProbeState& self, const probe::Kinematics& k_self,
                                                   const zone::ProbeState& other, double now) const {
  PairKinematics pair;
  pair.scale = geo::Projection::pair_scale(self.scale, other.scale);
  pair.parameters = pair_parameters(self.region, other.region);
  pair.minima = pair.parameters.minima;
  pair.minima.horizontal_m *= pair.scale;
  // The lower slot goes first so that a pair's figures do not depend on which of its
  // two tracks was updated.
  const bool self_first = self.slot < other.slot;
  const probe::Kinematics k_other = other.at(now);
  pair.p = self_first ? self.slot : other.slot;
  pair.q = self_first ? other.slot : self.slot;
  pair.kp = self_first ? k_self : k_other;
  pair.kq = self_first ? k_other : k_self;
  return pair;
}

void Pipeline::evaluate_pairs(track::TrackSlot slot) {
  std::sort(evaluated_.begin(), evaluated_.end(),
            [](const Evaluated& a, const Evaluated& b) { return a.other < b.other; });
  const double now = judged_at_;
  for (const Evaluated& pick : evaluated_) {
    const track::TrackSlot other = pick.other;
    alert::Evaluation e;
    if (pick.zone == zone::kNoZone) {
      const PairParameters parameters = pair_parameters(view_[slot].base.region, view_[other].base.region);
      e.confirm = parameters.confirm;
      e.clear = parameters.clear;
      e.observed_t = view_[slot].track.t;
      alerts_.evaluate(std::min(slot, other), std::max(slot, other), e, now, [](AlertEvent&) {}, pending_events_);
      continue;
    }
    const zone::ProbeState self = state_in(pick.zone, slot);
    const PairKinematics pair = pair_kinematics(self, self.at(now), state_in(pick.zone, other), now);
    // Most pairs are clear: decide that without the figures, which only events need.
    probe::ConflictGeometry g;
    bool along_turn = false;
    const bool found = pair_in_conflict(pair.kp, pair.kq, pair.minima);
    if (found && conflict_tap_) conflict_tap_(pair.p, pair.q);  // what the search found, before the rules
    if (found && !suppressed_by_rules(pair)) {
      g = probe::evaluate_pair(pair.kp, pair.kq, pair.minima);
      if (!g.in_conflict) {  // only the turn hypothesis finds it
        g = probe::turn_conflict(pair.kp, pair.kq, pair.minima);
        along_turn = true;
      }
    }
    e.in_conflict = g.in_conflict;
    e.observed_t = view_[slot].track.t;
    e.confirm = pair.parameters.confirm;
    e.clear = pair.parameters.clear;
    if (g.in_conflict) {
      e.severity = alerts_.classify(g.lost_now, g.t_los_s, pair.parameters.warning_s);
      e.t_los_s = g.t_los_s;
      e.cpa_h_m = g.cpa_h_m / pair.scale;
      e.cpa_v_ft = g.cpa_v_m / kFootToMetre;
    }
    alerts_.evaluate(
        pair.p, pair.q, e, now,
        [&](AlertEvent& event) {
          fill_event(event, plane_of(pick.zone), pair.p, pair.q, g, pair.kp, pair.kq, along_turn);
          event.hypothesis = g.lost_now     ? Hypothesis::Proximity
                             : along_turn   ? Hypothesis::Turn
                             : g.level_off  ? Hypothesis::LevelOff
                                            : Hypothesis::Linear;
          event.region = pair.parameters.region ? *pair.parameters.region : std::string();
        },
        pending_events_);
  }
  deliver();
}

Pipeline::RuleVerdict Pipeline::rule_verdict(const PairKinematics& pair) const {
  const track::Track& tp = view_[pair.p].track;
  const track::Track& tq = view_[pair.q].track;
  RuleVerdict v;
  if (rules_.same_address(tp, tq)) {
    v.rule = PairStage::SameAddress;
    return v;
  }
  if (rules_.level_pair(tp, tq)) {
    v.rule = PairStage::LevelPair;
    return v;
  }
  if (alerts_.is_active(pair.p, pair.q)) return v;
  // A presumption, not a fact: it keeps an alert from opening, never ends one, so a
  // level bust that opened one keeps it until the conflict test clears.
  if (rules_.adjacent_level_off(tp, tq, judged_at_)) {
    v.rule = PairStage::AdjacentLevelOff;
    return v;
  }
  if (pair.parameters.inhibited) {
    v.rule = PairStage::Inhibited;
    return v;
  }
  // Codes are duplicated: two aircraft with one code that close in on each other must not
  // lose an open alert, so the code rule only keeps one from opening.
  const double distance_m = geometry::norm(pair.kp.position - pair.kq.position) / pair.scale;
  if (rules_.one_aircraft_by_code(tp, tq, distance_m)) {
    v.rule = PairStage::SameCode;
    return v;
  }
  v.excluded = pair.p;
  v.exclusion = rules_.exclusion(tp, judged_at_);
  if (v.exclusion == eligibility::Exclusion::None) {
    v.excluded = pair.q;
    v.exclusion = rules_.exclusion(tq, judged_at_);
  }
  if (v.exclusion != eligibility::Exclusion::None) v.rule = PairStage::Excluded;
  return v;
}

bool Pipeline::suppressed_by_rules(const PairKinematics& pair) {
  const RuleVerdict v = rule_verdict(pair);
  if (!v.rule) return false;
  switch (*v.rule) {
    case PairStage::SameAddress:
    case PairStage::SameCode:
      suppressed_.reject("same_aircraft");
      break;
    case PairStage::Excluded:
      suppressed_.reject(eligibility::kExclusionNames.name(v.exclusion));
      break;
    default:
      suppressed_.reject(kPairStageNames.name(*v.rule));  // level_pair, adjacent_level_off, inhibited
      break;
  }
  return true;
}

// ---------------------------------------------------------------------------------------
// The pair watch (design §4.10): only for watched pairs, from the alert stage's view.

void Pipeline::set_pair_watch(PairWatch* watch) {
  if (watch && config_.batch_records != 1)
    throw std::invalid_argument("a pair watch needs batch_records = 1");
  watch_ = watch;
}

void Pipeline::note_watched_pairs(track::TrackSlot slot) {
  const track::Track& self = view_[slot].track;
  if (!watch_->watches(self.source, self.id)) return;
  watch_->for_each_partner(self.source, self.id, judged_at_,
                           [&](WatchedPair& pair, std::string_view source, std::string_view id) {
                             pair.notes.push_back(watched_pair_note(slot, source, id));
                           });
}

void Pipeline::watch_record(const TrackReport& report, track::Admission admission) {
  if (!watch_->watches(report.source, report.id)) return;
  watch_->seen(report.source, report.id, report.t);
  if (admission != track::Admission::AwaitingVelocity) return;  // the alert stage notes the rest
  PairNote note;
  note.t = report.t;
  note.updated = note.subject = party_label(report.source, report.id);
  note.stage = PairStage::AwaitingVelocity;
  note.detail = fmt::format("{} has no velocity yet", note.updated);
  watch_->note_track(report.source, report.id, note);
}

namespace {
std::string exclusion_detail(eligibility::Exclusion why, const track::Track& t, double now,
                             const eligibility::EligibilityConfig& c, const eligibility::Rules& rules) {
  const std::string who = party_label(t.source, t.id);
  switch (why) {
    case eligibility::Exclusion::Slow:
      return fmt::format("{} at {:.0f} kt, below {:.0f} kt", who, t.gs_kt, c.min_ground_speed_kt);
    case eligibility::Exclusion::AltitudeBand:
      return fmt::format("{} at {:.0f} ft, outside {:.0f}..{:.0f} ft", who, t.alt_ft, c.min_altitude_ft,
                         c.max_altitude_ft);
    case eligibility::Exclusion::BelowLowerLimit: {
      const eligibility::Aerodrome* aerodrome = nullptr;
      const double limit = rules.lower_limit_at(t.lat_deg, t.lon_deg, &aerodrome);
      return aerodrome ? fmt::format("{} at {:.0f} ft, below the lower limit {:.0f} ft ({:.0f} ft above {}, {:.0f} ft)",
                                     who, t.alt_ft, limit, c.aerodrome_height_ft, aerodrome->ident,
                                     aerodrome->elevation_ft)
                       : fmt::format("{} at {:.0f} ft, below the lower limit {:.0f} ft", who, t.alt_ft, limit);
    }
    case eligibility::Exclusion::ExcludedCode:
      return fmt::format("{} squawks {:04o}", who, t.mode3a.value_or(0));
    case eligibility::Exclusion::Coasting:
      return fmt::format("{} coasting (its source extrapolates it)", who);
    case eligibility::Exclusion::PositionStale:
      return fmt::format("{} last record {:.0f} s old, over {:.0f} s", who, now - t.t, c.max_position_age_s);
    case eligibility::Exclusion::FirstRecords:
      return fmt::format("{} seen in {} record(s), fewer than {}", who, t.records, c.min_records);
    case eligibility::Exclusion::None:
      break;
  }
  return who;
}
}  // namespace

PairNote Pipeline::watched_pair_note(track::TrackSlot slot, std::string_view partner_source,
                                     std::string_view partner_id) {
  const track::Track& self = view_[slot].track;
  PairNote note;
  note.t = judged_at_;
  note.updated = party_label(self.source, self.id);
  const track::TrackSlot other = tracks_.find(partner_source, partner_id);
  if (other == track::kNoTrack || other >= view_.size() || !view_[other].track.in_use ||
      view_[other].track.source != partner_source || view_[other].track.id != partner_id) {
    note.stage = other == track::kNoTrack ? PairStage::NoTrack : PairStage::AwaitingVelocity;
    const std::string partner = party_label(partner_source, partner_id);
    note.subject = partner;
    const std::optional<double> last = watch_->last_seen(partner_source, partner_id);
    note.detail = other != track::kNoTrack ? fmt::format("{} has no velocity yet", partner)
                  : last ? fmt::format("{} has no track since its last record {:.0f} s ago (dropped after the "
                                       "{:.0f} s timeout, or ended by its source)",
                                       partner, judged_at_ - *last, config_.tracks.track_timeout_s)
                         : fmt::format("{} has no track: no record of it yet", partner);
    return note;
  }
  if (!view_[other].track.in_engine) {
    note.stage = PairStage::AwaitingVelocity;
    note.subject = party_label(partner_source, partner_id);
    note.detail = fmt::format("{} has no velocity yet", party_label(partner_source, partner_id));
    return note;
  }
  const track::Track& them = view_[other].track;
  const zone::ZoneKey owner = owner_of(self, them);
  const double apart_m = geo::Projection::geodesic_distance_m({self.lat_deg, self.lon_deg}, {them.lat_deg, them.lon_deg});
  if (!holds_both(owner, self, them)) {
    note.stage = PairStage::NotCandidate;
    note.detail = fmt::format("no zone holds both: {:.1f} NM apart", apart_m / 1852.0);
    return note;
  }
  const zone::ProbeState state = state_in(owner, slot);
  const PairKinematics pair = pair_kinematics(state, state.at(judged_at_), state_in(owner, other), judged_at_);
  const probe::ConflictGeometry g = probe::evaluate_pair(pair.kp, pair.kq, pair.minima);
  const track::Track& tp = view_[pair.p].track;
  const track::Track& tq = view_[pair.q].track;
  const std::string figures = fmt::format(
      "{:.2f} NM and {:.0f} ft apart; CPA {:.2f} NM in {:.0f} s, {:.0f} ft there; {} {:.0f} ft {:+.0f} fpm, "
      "{} {:.0f} ft {:+.0f} fpm",
      apart_m / 1852.0, g.sep_v_m / kFootToMetre, g.cpa_h_m / pair.scale / 1852.0, g.t_cpa_s, g.cpa_v_m / kFootToMetre,
      party_label(tp.source, tp.id), tp.alt_ft, tp.vr_fpm, party_label(tq.source, tq.id), tq.alt_ft, tq.vr_fpm);
  if (!pair_in_conflict(pair.kp, pair.kq, pair.minima)) {
    note.stage = PairStage::ProbeClear;
    const bool horizontal = g.cpa_h_m >= pair.minima.horizontal_m;
    probe::SeparationMinima whole = pair.minima;  // the vertical prediction for all of T
    whole.vertical_lookahead_s = whole.lookahead_s;
    const bool vertical_lookahead = !horizontal && pair_in_conflict(pair.kp, pair.kq, whole);
    note.detail = fmt::format(
        "{} ({})", figures,
        horizontal           ? "no horizontal loss within the look-ahead"
        : vertical_lookahead ? fmt::format("vertically apart; the rates close below S_v less the tolerance only after "
                                           "the vertical look-ahead, {:.0f} s", pair.minima.vertical_lookahead_s)
                             : "vertically apart where horizontally close");
    return note;
  }
  const bool searched = std::any_of(evaluated_.begin(), evaluated_.end(),
                                    [&](const Evaluated& e) { return e.other == other; });
  if (!searched) {
    note.stage = PairStage::NotCandidate;
    note.detail = fmt::format("{} (the candidate search did not give the pair)", figures);
    return note;
  }
  const RuleVerdict v = rule_verdict(pair);
  if (v.rule) {
    note.stage = *v.rule;
    switch (*v.rule) {
      case PairStage::SameAddress:
        note.detail = fmt::format("both address {:06X}; {}", tp.address.value_or(0), figures);
        break;
      case PairStage::SameCode:
        note.detail = fmt::format("both squawk {:04o}, no two addresses, positions and velocities alike; {}",
                                  tp.mode3a.value_or(0), figures);
        break;
      case PairStage::Excluded:
        note.subject = party_label(view_[v.excluded].track.source, view_[v.excluded].track.id);
        note.detail = fmt::format("{}: {}", eligibility::kExclusionNames.name(v.exclusion),
                                  exclusion_detail(v.exclusion, view_[v.excluded].track, judged_at_, config_.eligibility, rules_));
        break;
      default:
        note.detail = figures;
        break;
    }
    return note;
  }
  note.stage = alerts_.is_active(pair.p, pair.q) ? PairStage::Alerting : PairStage::ConfirmPending;
  note.detail = fmt::format("t_los {:.0f} s; {}", g.t_los_s, figures);
  return note;
}

void Pipeline::fill_event(AlertEvent& event, const geo::Projection& projection, track::TrackSlot p, track::TrackSlot q,
                          const probe::ConflictGeometry& g, const probe::Kinematics& kp, const probe::Kinematics& kq,
                          bool along_turn) const {
  const track::Track& tp = view_[p].track;
  const track::Track& tq = view_[q].track;
  const bool p_first = ordered_before(tp, tq);
  event.a = party_of(p_first ? tp : tq);
  event.b = party_of(p_first ? tq : tp);
  event.t_los_s = g.t_los_s;
  event.t_cpa_s = g.t_cpa_s;
  event.cpa_v_ft = g.cpa_v_m / kFootToMetre;
  event.sep_v_ft = g.sep_v_m / kFootToMetre;
  // Horizontal figures on the ellipsoid: the plane overstates lengths by the scale k.
  const auto geodesic = [&](geometry::Point2 x, geometry::Point2 y) {
    return geo::Projection::geodesic_distance_m(projection.unproject(x), projection.unproject(y));
  };
  event.sep_h_m = geodesic(kp.position, kq.position);
  event.cpa_h_m = along_turn ? geodesic(probe::position_along_turn(kp, g.t_cpa_s), probe::position_along_turn(kq, g.t_cpa_s))
                             : geodesic(kp.position + g.t_cpa_s * kp.velocity, kq.position + g.t_cpa_s * kq.velocity);
}

void Pipeline::deliver() {
  if (sink_)
    for (const AlertEvent& event : pending_events_)
      if (serves(event)) sink_(event);
  pending_events_.clear();
}

bool Pipeline::serves(const AlertEvent& event) const {
  if (!config_.served_longitudes || !tiling_) return true;
  double lon = zone::ZoneTiling::midpoint({event.a.lat_deg, event.a.lon_deg}, {event.b.lat_deg, event.b.lon_deg}).lon_deg;
  if (lon >= 180.0) lon -= 360.0;  // 180 is −180, as in ZoneTiling::home
  return lon >= config_.served_longitudes->west_deg && lon < config_.served_longitudes->east_deg;
}

// ---------------------------------------------------------------------------------------
// Readers.

kinetic::KineticAudit Pipeline::audit() {
  flush();
  kinetic::KineticAudit total;
  for (ZoneWork& w : work_) {
    if (!w.zone) continue;
    w.zone->advance(engine_time(clock_));
    const kinetic::KineticAudit a = w.zone->engine().audit_and_repair();
    total.violations_found += a.violations_found;
    total.violations_unrepaired += a.violations_unrepaired;
  }
  return total;
}

bool Pipeline::is_valid() const {
  for (const ZoneWork& w : work_)
    if (w.zone && !w.zone->engine().is_valid()) return false;
  return true;
}

kinetic::KineticStatistics Pipeline::kinetic_statistics() const {
  kinetic::KineticStatistics total = retired_kinetic_;
  for (const ZoneWork& w : work_)
    if (w.zone) add_statistics(total, w.zone->kinetic_statistics());
  return total;
}

const zone::Zone* Pipeline::home_zone(track::TrackSlot slot) const {
  const track::Track& track = tracks_[slot];
  return track.in_use && track.plane < work_.size() ? work_[track.plane].zone.get() : nullptr;
}

}  // namespace kew
