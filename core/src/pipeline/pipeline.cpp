#include "kew/pipeline/pipeline.hpp"

#include <algorithm>
#include <ctime>
#include <cmath>

#include "kew/geometry/hilbert.hpp"
#include "kew/util/gentle_growth.hpp"

namespace kew {

namespace {
constexpr double kFootToMetre = 0.3048;
// Widens R_i so that rounding in positions and speeds can never drop a pair whose CPA
// test is positive (metres; far below any separation minimum).
constexpr double kSearchSlack_m = 1.0;

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
      kdt_(std::in_place, config.kinetic, 0.0),
      alerts_(config.alerts, [this](track::TrackSlot slot) {
        const track::Track& track = tracks_[slot];
        return alert::PartyName{track.source, track.id};
      }),
      regions_(config.regions),
      rules_(config.eligibility, config.minima) {
  if (config_.reference) projection_.emplace(*config_.reference, config_.coverage_radius_m);
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

Pipeline::PairParameters Pipeline::parameters_of(track::TrackSlot p, track::TrackSlot q) const {
  return pair_parameters(probe_state_[tracks_[p].point].region, probe_state_[tracks_[q].point].region);
}

bool Pipeline::pair_in_conflict(const probe::Kinematics& kp, const probe::Kinematics& kq,
                                const probe::SeparationMinima& minima) const {
  if (probe::in_conflict(kp, kq, minima)) return true;
  return config_.turn.enabled && (kp.turn_rate_rps != 0.0 || kq.turn_rate_rps != 0.0) &&
         probe::in_turn_conflict(kp, kq, minima);
}

double Pipeline::tolerance_bound_m() const {
  const kinetic::KineticConfig& k = config_.kinetic;
  if (k.tolerance_mode == kinetic::ToleranceMode::Absolute) return k.tolerance;
  // Relative τ bounds the lag by τ·|p|, and |p| is at most the plane radius of coverage.
  const double k_max = projection_ ? projection_->max_scale() : 1.03;
  return k.tolerance * config_.coverage_radius_m * k_max * 1.05;
}

double Pipeline::search_radius(double speed_mps) const {
  const double k_max = projection_ ? projection_->max_scale() : 1.0;
  const double v_max = speeds_.empty() ? 0.0 : speeds_.top_key();
  return largest_horizontal_m_ * k_max + largest_lookahead_s_ * (speed_mps + v_max) + 2.0 * tolerance_bound_m() +
         kSearchSlack_m;
}

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
  if (!config_.reference) projection_.reset();
  kdt_.emplace(config_.kinetic, 0.0);
  next_renumber_ = 0.0;  // its schedule starts with the new run's clock
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
}

void Pipeline::apply_record(const TrackReport& report) {
  if (!projection_) projection_.emplace(rounded_reference(report), config_.coverage_radius_m);
  if (!started_) {
    started_ = true;
    epoch_ = std::floor(report.t);
    clock_ = epoch_;
  }
  // A plausible record that is not too late moves the clock (and may time out other
  // tracks, or this record's own previous track) before it is applied.
  if (report.t >= clock_ - tracks_.config().max_lateness_s) move_clock(std::max(clock_, report.t));
  restart_if_other_aircraft(report);

  const track::AdmitResult admitted = tracks_.admit(report, clock_, *projection_);
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
  track::Track& track = tracks_[admitted.slot];
  if (admitted.admission == track::Admission::AwaitingVelocity) {
    ++stats_.awaiting_velocity;
    if (track.point != kinetic::kNoPoint) {
      // Velocity reset: the track leaves the probe until it has a velocity again.
      leave_engine(admitted.slot);
      alerts_.drop_track(admitted.slot, clock_, pending_events_);
      deliver();
    }
    if (report.track_end) end_track(admitted.slot);
    return;
  }
  apply(admitted.slot);
  if (report.track_end) end_track(admitted.slot);
}

void Pipeline::restart_if_other_aircraft(const TrackReport& report) {
  if (!report.address || report.t < clock_ - tracks_.config().max_lateness_s) return;  // admit() refuses it
  const track::TrackSlot slot = tracks_.find(report.source, report.id);
  if (slot == track::kNoTrack) return;
  const track::Track& track = tracks_[slot];
  // Two 24-bit addresses are never one aircraft: the id was reused (design §4.5).
  if (!track.address || *track.address == *report.address) return;
  // Keep the old track when admit() is going to refuse the record anyway.
  geo::ProjectionError error = geo::ProjectionError::None;
  (void)projection_->project({report.lat_deg, report.lon_deg}, error);
  if (error != geo::ProjectionError::None) return;
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
void Pipeline::timed(double PhaseTimes::*phase, F&& f) {
  if (!config_.time_phases) {
    f();
    return;
  }
  const double start = thread_cpu_s();
  f();
  phases_.*phase += thread_cpu_s() - start;
}

void Pipeline::move_clock(double t) {
  if (t <= clock_) return;
  tracks_.expire(t, [&](track::TrackSlot slot, const track::Track& track) {
    const double at = std::max(clock_, track.t + tracks_.config().track_timeout_s);
    timed(&PhaseTimes::maintenance_s, [&] { kdt_->advance(engine_time(at)); });
    clock_ = at;
    drop_track(slot);
  });
  timed(&PhaseTimes::maintenance_s, [&] { kdt_->advance(engine_time(t)); });
  clock_ = t;
  if (config_.renumber_every_s > 0.0 && clock_ >= next_renumber_) {
    if (next_renumber_ > 0.0) timed(&PhaseTimes::maintenance_s, [&] { renumber(); });
    next_renumber_ = clock_ + config_.renumber_every_s;
  }
}

void Pipeline::renumber() {
  std::vector<track::TrackSlot> slots;
  std::vector<probe::Kinematics> reports;  // each track's latest report, now
  std::vector<geometry::Point2> positions;
  for (const track::TrackSlot slot : slot_of_point_) {
    if (slot == track::kNoTrack) continue;
    slots.push_back(slot);
    reports.push_back(tracks_[slot].at(clock_));
    positions.push_back(reports.back().position);
  }
  const kinetic::KineticStatistics earlier = kdt_->statistics();
  std::vector<ProbeState> old_state = std::move(probe_state_);
  probe_state_.clear();
  slot_of_point_.clear();
  kdt_.emplace(config_.kinetic, engine_time(clock_));
  for (const std::uint32_t i : geometry::hilbert_order(positions)) {
    track::Track& track = tracks_[slots[i]];
    const kinetic::PointId old_point = track.point;
    track.point = kdt_->insert(engine_time(clock_), reports[i].position, reports[i].velocity);
    util::grow_to(slot_of_point_, track.point + 1, track::kNoTrack);
    util::grow_to(probe_state_, track.point + 1);
    slot_of_point_[track.point] = slots[i];
    probe_state_[track.point] = old_state[old_point];
  }
  kdt_->continue_statistics(earlier);
}

void Pipeline::advance_to(double t) {
  if (!started_ || !std::isfinite(t)) return;
  // Records arriving too late since the last accepted one (a feed whose delay grew by
  // more than max_lateness_s) must be able to catch up: the tick may not carry the clock
  // beyond their reach, or they would be refused for ever.
  if (late_since_accepted_) t = std::min(t, newest_late_t_ + tracks_.config().max_lateness_s);
  move_clock(t);
}

void Pipeline::leave_engine(track::TrackSlot slot) {
  track::Track& track = tracks_[slot];
  if (track.point != kinetic::kNoPoint) {
    timed(&PhaseTimes::maintenance_s, [&] { kdt_->remove(track.point, engine_time(clock_)); });
    slot_of_point_[track.point] = track::kNoTrack;
    track.point = kinetic::kNoPoint;
  }
  speeds_.erase(slot);
}

void Pipeline::drop_track(track::TrackSlot slot) {
  leave_engine(slot);
  alerts_.drop_track(slot, clock_, pending_events_);
  ++stats_.tracks_dropped;
  deliver();
}

void Pipeline::drop_all() {
  for (track::TrackSlot slot = 0; slot < tracks_.slot_end(); ++slot) {
    if (!tracks_[slot].in_use) continue;
    drop_track(slot);
    tracks_.drop(slot);
  }
}

kinetic::KineticAudit Pipeline::audit() { return kdt_->audit_and_repair(); }

void Pipeline::apply(track::TrackSlot slot) {
  track::Track& track = tracks_[slot];
  const probe::Kinematics now = track.at(clock_);
  timed(&PhaseTimes::maintenance_s, [&] {
    if (track.point == kinetic::kNoPoint) {
      track.point = kdt_->insert(engine_time(clock_), now.position, now.velocity);
      util::grow_to(slot_of_point_, track.point + 1, track::kNoTrack);
      slot_of_point_[track.point] = slot;
    } else {
      kdt_->update(track.point, engine_time(clock_), now.position, now.velocity);
    }
  });
  speeds_.set(slot, geometry::norm(now.velocity));
  util::grow_to(probe_state_, track.point + 1);
  ProbeState& state = probe_state_[track.point];
  state = {track.kinematics, track.t, track.plane_scale, track.intent.sel_t + config_.tracks.intent.max_age_s,
           regions_.empty() ? region::RegionMap::kNone : regions_.locate(track.lat_deg, track.lon_deg, track.alt_ft),
           slot};
  if (config_.turn.enabled && track.turn_rate_dps && std::abs(*track.turn_rate_dps) >= config_.turn.min_rate_dps)
    state.kinematics.turn_rate_rps = -*track.turn_rate_dps * (M_PI / 180.0);  // clockwise over ground
  probe(slot);
}

void Pipeline::collect_candidates(track::TrackSlot slot) {
  const track::Track& track = tracks_[slot];
  candidates_.clear();
  // Pairs pending confirmation or alerting are always evaluated, so they see their clear
  // evaluations even when the search (edges mode) does not return them: they are marked
  // here, test_candidates() takes those it meets among the candidates, and then the rest.
  if (++candidate_round_ == 0) {  // wrapped: forget every mark
    for (ProbeState& state : probe_state_) state.partner_round = 0;
    candidate_round_ = 1;
  }
  partners_scratch_.clear();
  alerts_.partners_of(slot, partners_scratch_);
  // A pair's state ends when either track leaves the engine: a partner has a point.
  for (const track::TrackSlot other : partners_scratch_) probe_state_[tracks_[other].point].partner_round = candidate_round_;
  // Each point once, never the track's own (within() marks what it visited).
  switch (config_.probe_mode) {
    case probe::ProbeMode::Exact:
      // Straight-line prediction: every j that can come within S_h of i within T is within
      // S_h + v_max·T (+ 2τ) of i's position T ahead (design §2.1), a disk that is smaller
      // the faster i flies; an arc stays only within |v_i|·T of its start.
      if (config_.search_ahead && probe_state_[track.point].kinematics.turn_rate_rps == 0.0) {
        const geometry::Point2 ahead = kdt_->position_now(track.point) + largest_lookahead_s_ * track.kinematics.velocity;
        search_.within_around(*kdt_, track.point, ahead, search_radius(0.0), candidates_);
      } else {
        search_.within(*kdt_, track.point, search_radius(geometry::norm(track.kinematics.velocity)), candidates_);
      }
      break;
    case probe::ProbeMode::Edges:
      search_.neighbours(*kdt_, track.point, candidates_);
      // A few points; within() gives each once by construction, this makes sure here.
      std::sort(candidates_.begin(), candidates_.end());
      candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());
      break;
    case probe::ProbeMode::Brute:
      for (kinetic::PointId other = 0; other < slot_of_point_.size(); ++other)
        if (slot_of_point_[other] != track::kNoTrack && other != track.point) candidates_.push_back(other);
      break;
  }
}

Pipeline::PairKinematics Pipeline::pair_kinematics(track::TrackSlot slot, const probe::Kinematics& k_self,
                                                   track::TrackSlot other_slot) const {
  const ProbeState& self = probe_state_[tracks_[slot].point];
  const ProbeState& other = probe_state_[tracks_[other_slot].point];
  PairKinematics pair;
  pair.scale = geo::Projection::pair_scale(self.scale, other.scale);
  pair.parameters = parameters_of(slot, other_slot);
  pair.minima = pair.parameters.minima;
  pair.minima.horizontal_m *= pair.scale;
  // The lower slot goes first so that a pair's figures do not depend on which of its
  // two tracks was updated.
  const bool self_first = slot < other_slot;
  const probe::Kinematics k_other = other.at(clock_);
  pair.p = self_first ? slot : other_slot;
  pair.q = self_first ? other_slot : slot;
  pair.kp = self_first ? k_self : k_other;
  pair.kq = self_first ? k_other : k_self;
  return pair;
}

void Pipeline::probe(track::TrackSlot slot) {
  timed(&PhaseTimes::search_s, [&] { collect_candidates(slot); });
  timed(&PhaseTimes::tests_s, [&] { test_candidates(slot); });
}

void Pipeline::test_candidates(track::TrackSlot slot) {
  ++stats_.probes;
  stats_.candidates += candidates_.size();
  const ProbeState& self = probe_state_[tracks_[slot].point];
  const probe::Kinematics k_self = self.at(clock_);
  // Most candidates are clear and have no pair state, and for those the alert manager
  // does nothing: only pairs in conflict or with state (the partners, marked above) go
  // on, in slot order, which fixes the order of the events of one probe (design §2.5).
  // Sorting these few rather than every candidate found is the same order.
  evaluated_.clear();
  constexpr std::size_t kPrefetchAhead = 4;  // the candidates are scattered in memory
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    if (i + kPrefetchAhead < candidates_.size()) {
      const ProbeState* ahead = &probe_state_[candidates_[i + kPrefetchAhead]];
      __builtin_prefetch(ahead);
      __builtin_prefetch(reinterpret_cast<const char*>(ahead) + 64);
    }
    // pair_kinematics() without its copies: this loop runs ~100 times per update.
    ProbeState& them = probe_state_[candidates_[i]];
    const track::TrackSlot other = them.slot;
    if (them.partner_round == candidate_round_) {
      them.partner_round = 0;  // met: not added again below
      evaluated_.push_back(other);
      continue;
    }
    const probe::Kinematics k_other = them.at(clock_);
    probe::SeparationMinima minima =
        regions_.empty() ? config_.minima : pair_parameters(self.region, them.region).minima;
    if (probe::vertically_apart_for_ever(k_self, k_other, minima)) continue;
    minima.horizontal_m *= geo::Projection::pair_scale(self.scale, them.scale);
    if (slot < other ? pair_in_conflict(k_self, k_other, minima) : pair_in_conflict(k_other, k_self, minima))
      evaluated_.push_back(other);
  }
  for (const track::TrackSlot other : partners_scratch_) {  // partners the search did not find
    if (probe_state_[tracks_[other].point].partner_round != candidate_round_) continue;
    ++stats_.candidates;
    evaluated_.push_back(other);
  }
  std::sort(evaluated_.begin(), evaluated_.end());
  for (const track::TrackSlot other : evaluated_) {
    const PairKinematics pair = pair_kinematics(slot, k_self, other);
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
    alert::Evaluation e;
    e.in_conflict = g.in_conflict;
    e.confirm = pair.parameters.confirm;
    e.clear = pair.parameters.clear;
    if (g.in_conflict) {
      e.severity = alerts_.classify(g.lost_now, g.t_los_s, pair.parameters.warning_s);
      e.t_los_s = g.t_los_s;
      e.cpa_h_m = g.cpa_h_m / pair.scale;
      e.cpa_v_ft = g.cpa_v_m / kFootToMetre;
    }
    alerts_.evaluate(
        pair.p, pair.q, e, clock_,
        [&](AlertEvent& event) {
          fill_event(event, pair.p, pair.q, g, pair.kp, pair.kq, along_turn);
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

bool Pipeline::suppressed_by_rules(const PairKinematics& pair) {
  const track::Track& tp = tracks_[pair.p];
  const track::Track& tq = tracks_[pair.q];
  if (rules_.same_address(tp, tq)) {
    suppressed_.reject("same_aircraft");
    return true;
  }
  if (rules_.level_pair(tp, tq)) {
    suppressed_.reject("level_pair");
    return true;
  }
  if (alerts_.is_active(pair.p, pair.q)) return false;
  if (pair.parameters.inhibited) {
    suppressed_.reject("inhibited");
    return true;
  }
  // Codes are duplicated: two aircraft with one code that close in on each other must not
  // lose an open alert, so the code rule only keeps one from opening.
  const double distance_m = geometry::norm(pair.kp.position - pair.kq.position) / pair.scale;
  if (rules_.same_code_colocated(tp, tq, distance_m)) {
    suppressed_.reject("same_aircraft");
    return true;
  }
  eligibility::Exclusion why = rules_.exclusion(tp, clock_);
  if (why == eligibility::Exclusion::None) why = rules_.exclusion(tq, clock_);
  if (why == eligibility::Exclusion::None) return false;
  suppressed_.reject(eligibility::kExclusionNames.name(why));
  return true;
}

void Pipeline::fill_event(AlertEvent& event, track::TrackSlot p, track::TrackSlot q, const probe::ConflictGeometry& g,
                          const probe::Kinematics& kp, const probe::Kinematics& kq, bool along_turn) const {
  const track::Track& tp = tracks_[p];
  const track::Track& tq = tracks_[q];
  const bool p_first = ordered_before(tp, tq);
  event.a = party_of(p_first ? tp : tq);
  event.b = party_of(p_first ? tq : tp);
  event.t_los_s = g.t_los_s;
  event.t_cpa_s = g.t_cpa_s;
  event.cpa_v_ft = g.cpa_v_m / kFootToMetre;
  event.sep_v_ft = g.sep_v_m / kFootToMetre;
  // Horizontal figures on the ellipsoid: the plane overstates lengths by the scale k.
  const geo::Projection& projection = *projection_;
  const auto geodesic = [&](geometry::Point2 x, geometry::Point2 y) {
    return geo::Projection::geodesic_distance_m(projection.unproject(x), projection.unproject(y));
  };
  event.sep_h_m = geodesic(kp.position, kq.position);
  event.cpa_h_m = along_turn ? geodesic(probe::position_along_turn(kp, g.t_cpa_s), probe::position_along_turn(kq, g.t_cpa_s))
                             : geodesic(kp.position + g.t_cpa_s * kp.velocity, kq.position + g.t_cpa_s * kq.velocity);
}

void Pipeline::deliver() {
  if (sink_)
    for (const AlertEvent& event : pending_events_) sink_(event);
  pending_events_.clear();
}

}  // namespace kew
