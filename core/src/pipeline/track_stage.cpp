#include "track_stage.hpp"

#include <algorithm>
#include <cmath>

namespace kew::pipeline {

namespace {
geo::GeodeticPosition rounded_reference(const TrackReport& r) {
  return {std::round(r.lat_deg * 10.0) / 10.0, std::round(r.lon_deg * 10.0) / 10.0};
}

bool same_record(const TrackReport& a, const TrackReport& b) {
  return a.t == b.t && a.id == b.id && a.source == b.source;
}
}  // namespace

TrackStage::TrackStage(const PipelineConfig& config, ZoneSet& zones, Batch& batch, const region::RegionMap& regions)
    : config_(config),
      zones_(zones),
      batch_(batch),
      regions_(regions),
      tracks_(config.tracks),
      time_guard_(config.tracks.max_time_jump_s, config.tracks.max_lateness_s, track::kTimeJumpConfirm) {}

track::Refusal TrackStage::screen(const TrackReport& report) {
  ++stats_.records;
  const track::Refusal problem = tracks_.plausibility_problem(report);
  if (problem != track::Refusal::None) {
    tracks_.rejections().reject(track::kRefusalNames.name(problem), report.id);
    return problem;
  }
  if (report.t > time_ceiling_) {
    refuse_future(report);
    return track::Refusal::FutureTime;
  }
  return track::Refusal::None;
}

std::vector<TrackReport> TrackStage::take_young_refused() {
  std::vector<TrackReport> refused = std::move(young_refused_);
  young_refused_.clear();
  return refused;
}

std::vector<TrackReport> TrackStage::restart(std::vector<TrackReport> refused) {
  // Without a configured reference the first record fixed the plane, and it always
  // started the clock: a stray one (a position at −45°, 170° in a European feed, a date
  // in 2100) would refuse every record after it. The run has shown nothing yet; start it
  // again from the records it refused, which agree with one another, then those held
  // ahead of a clock that is being discarded.
  time_guard_.release(refused);
  if (!config_.reference) coverage_centre_.reset();
  zones_.reset(config_.reference.has_value());
  started_ = false;
  accepted_in_run_ = 0;
  late_since_accepted_ = false;
  ++stats_.runs_restarted;
  return refused;
}

RecordOutcome TrackStage::process(const TrackReport& report) {
  if (!started_) return apply_record(report);
  if (time_guard_.held() != 0) {
    guard_scratch_.clear();
    time_guard_.refuse_contradicted(report.t, guard_scratch_);
    for (const TrackReport& r : guard_scratch_) refuse_future(r);
  }
  if (time_guard_.ahead(report.t, clock_)) {
    RecordOutcome held{RecordOutcome::Kind::Held};
    if (time_guard_.hold(report)) {
      guard_scratch_.clear();
      time_guard_.release(guard_scratch_);
      if (const std::optional<RecordOutcome> own = apply_released(&report)) return *own;
    }
    return held;
  }
  const RecordOutcome outcome = apply_record(report);
  // Held records this record's time has caught up with are no jump any more.
  while (time_guard_.held() != 0) {
    guard_scratch_.clear();
    time_guard_.release_reached(clock_, guard_scratch_);
    if (guard_scratch_.empty()) break;
    apply_released();
  }
  return outcome;
}

void TrackStage::refuse_future(const TrackReport& r) {
  tracks_.rejections().reject(track::kRefusalNames.name(track::Refusal::FutureTime), r.id);
}

std::optional<RecordOutcome> TrackStage::apply_released(const TrackReport* record) {
  // apply_record() never reaches the guard, so the scratch is not reused meanwhile.
  std::optional<RecordOutcome> own;
  for (const TrackReport& r : guard_scratch_) {
    const RecordOutcome outcome = apply_record(r);
    if (record && same_record(r, *record)) own = outcome;
  }
  return own;
}

void TrackStage::end_of_input() {
  // Nothing contradicted them, and at the end of the input they can blind nothing.
  guard_scratch_.clear();
  time_guard_.release(guard_scratch_);
  apply_released();
}

RecordOutcome TrackStage::apply_record(const TrackReport& report) {
  if (!started_) {
    started_ = true;
    epoch_ = std::floor(report.t);
    clock_ = epoch_;
    zones_.set_epoch(epoch_);
  }
  if (!coverage_centre_) coverage_centre_ = config_.reference.value_or(rounded_reference(report));
  if (config_.zone_mode == ZoneMode::Single && !zones_.single_plane())
    zones_.open_single_plane(*coverage_centre_, config_.coverage_radius_m.value_or(PipelineConfig::kSingleCoverage_m),
                             clock_);
  // A plausible record that is not too late moves the clock (and may time out other
  // tracks, or this record's own previous track) before it is applied.
  if (report.t >= clock_ - tracks_.config().max_lateness_s) move_clock(std::max(clock_, report.t));
  // Single mode's one plane: the record is projected once, for the test of another
  // aircraft and for the track table.
  std::optional<track::ProjectedPosition> projected;
  if (const std::optional<geo::Projection>& plane = zones_.single_plane()) {
    projected.emplace();
    projected->at = plane->project({report.lat_deg, report.lon_deg}, projected->error);
  }
  restart_if_other_aircraft(report, projected ? &*projected : nullptr);

  track::AdmitResult admitted;
  if (outside_limit(report)) {
    tracks_.rejections().reject(track::kRefusalNames.name(track::Refusal::OutsideCoverage), report.id);
    admitted.refusal = track::Refusal::OutsideCoverage;
  } else {
    const zone::ZoneKey home = zones_.home_of(report.lat_deg, report.lon_deg);
    admitted = tracks_.admit(report, clock_, zones_.home_plane(home, clock_), home, projected ? &*projected : nullptr);
  }
  if (admitted.admission == track::Admission::Rejected) {
    if (admitted.refusal == track::Refusal::TooLate) {
      newest_late_t_ = late_since_accepted_ ? std::max(newest_late_t_, report.t) : report.t;
      late_since_accepted_ = true;
    }
    // A configured reference cannot move: only a clock set by a stray record can.
    const bool elsewhere = admitted.refusal == track::Refusal::TooLate ||
                           (admitted.refusal == track::Refusal::OutsideCoverage && !config_.reference);
    if (accepted_in_run_ < kYoungRun && elsewhere) young_refused_.push_back(report);
    // The source ended the track: so it is, even when this last record is refused
    // (a repeated time, say); otherwise it would linger until the timeout.
    if (report.track_end) {
      const track::TrackSlot slot = tracks_.find(report.source, report.id);
      if (slot != track::kNoTrack) end_track(slot);
    }
    return {RecordOutcome::Kind::Refused, admitted.refusal};
  }
  ++stats_.accepted;
  ++accepted_in_run_;
  young_refused_.clear();
  late_since_accepted_ = false;
  stats_.last_data_time = clock_;
  const bool awaiting = admitted.admission == track::Admission::AwaitingVelocity;
  const RecordOutcome applied{awaiting ? RecordOutcome::Kind::AwaitingVelocity : RecordOutcome::Kind::Accepted,
                              track::Refusal::None, admitted.slot};
  if (observer_ && observer_->watches(report.source, report.id)) observer_->record(report, applied);
  if (awaiting) {
    ++stats_.awaiting_velocity;
    if (tracks_[admitted.slot].in_engine) {
      // Velocity reset: the track leaves the probe until it has a velocity again.
      leave_engine(admitted.slot);
      batch_.steps.push_back({AlertStep::Kind::DropAlerts, admitted.slot, 0, 0, 0, clock_});
    }
    if (report.track_end) end_track(admitted.slot);
    return applied;
  }
  apply(admitted.slot);
  if (report.track_end) end_track(admitted.slot);
  return applied;
}

bool TrackStage::outside_limit(const TrackReport& report) const {
  // Single mode's plane refuses what lies beyond it (TrackTable::admit).
  if (config_.zone_mode == ZoneMode::Single || !config_.coverage_radius_m) return false;
  return geo::Projection::geodesic_distance_m(*coverage_centre_, {report.lat_deg, report.lon_deg}) >
         *config_.coverage_radius_m;
}

void TrackStage::restart_if_other_aircraft(const TrackReport& report, const track::ProjectedPosition* projected) {
  if (!report.address || report.t < clock_ - tracks_.config().max_lateness_s) return;  // admit() refuses it
  const track::TrackSlot slot = tracks_.find(report.source, report.id);
  if (slot == track::kNoTrack) return;
  const track::Track& track = tracks_[slot];
  // Two 24-bit addresses are never one aircraft: the id was reused (design §4.5).
  if (!track.address || *track.address == *report.address) return;
  // Keep the old track when admit() is going to refuse the record anyway.
  if (outside_limit(report)) return;
  if (projected && projected->error != geo::ProjectionError::None) return;
  ++stats_.tracks_restarted;
  drop_track(slot);
  tracks_.drop(slot);
}

void TrackStage::end_track(track::TrackSlot slot) {
  ++stats_.tracks_ended;
  drop_track(slot);
  tracks_.drop(slot);
}

void TrackStage::move_clock(double t) {
  if (t <= clock_) return;
  // A zone's engine advances to the time of each operation on it (insert, update and
  // remove advance first), and to the clock at the end of a batch.
  tracks_.expire(t, [&](track::TrackSlot slot, const track::Track& track) {
    clock_ = std::max(clock_, track.t + tracks_.config().track_timeout_s);
    drop_track(slot);
  });
  clock_ = t;
  zones_.schedule_renumbering(clock_);
}

bool TrackStage::advance_to(double t) {
  if (!started_ || !std::isfinite(t)) return false;
  // Records arriving too late since the last accepted one (a feed whose delay grew by
  // more than max_lateness_s) must be able to catch up: the tick may not carry the clock
  // beyond their reach, or they would be refused for ever.
  if (late_since_accepted_) t = std::min(t, newest_late_t_ + tracks_.config().max_lateness_s);
  move_clock(t);
  return true;
}

void TrackStage::leave_engine(track::TrackSlot slot) {
  track::Track& track = tracks_[slot];
  if (!track.in_engine) return;
  zones_.remove(slot, clock_);
  track.in_engine = false;
  --live_tracks_;
}

void TrackStage::drop_track(track::TrackSlot slot) {
  const bool in_engine = tracks_[slot].in_engine;
  leave_engine(slot);
  // A track that never had a velocity has no alerts.
  if (in_engine) batch_.steps.push_back({AlertStep::Kind::DropAlerts, slot, 0, 0, 0, clock_});
  ++stats_.tracks_dropped;
}

void TrackStage::drop_all() {
  for (track::TrackSlot slot = 0; slot < tracks_.slot_end(); ++slot) {
    if (!tracks_[slot].in_use) continue;
    drop_track(slot);
    tracks_.drop(slot);
  }
}

void TrackStage::apply(track::TrackSlot slot) {
  track::Track& track = tracks_[slot];
  if (!track.in_engine) ++live_tracks_;
  track.in_engine = true;
  // What every zone's probe state shares, whatever its plane; and the track as the
  // alert stage will judge it.
  const auto snapshot = static_cast<std::uint32_t>(batch_.snapshots.size());
  Snapshot& s = batch_.snapshots.emplace_back();
  s.track = track;
  s.base.t = track.t;
  s.base.level_off_until_t = track.intent.sel_t + config_.tracks.intent.max_age_s;
  s.base.lat_deg = track.lat_deg;
  s.base.lon_deg = track.lon_deg;
  s.base.region = regions_.empty() ? region::RegionMap::kNone : regions_.locate(track.lat_deg, track.lon_deg, track.alt_ft);
  s.base.slot = slot;
  if (config_.turn.enabled && track.turn_rate_dps && std::abs(*track.turn_rate_dps) >= config_.turn.min_rate_dps)
    s.base.kinematics.turn_rate_rps = -*track.turn_rate_dps * (M_PI / 180.0);  // clockwise over ground
  const auto first_zone = static_cast<std::uint32_t>(batch_.step_zones.size());
  const std::uint32_t zone_count = zones_.place(slot, snapshot, track.lat_deg, track.lon_deg, clock_, batch_.step_zones);
  batch_.steps.push_back({AlertStep::Kind::Update, slot, snapshot, first_zone, zone_count, clock_});
}

}  // namespace kew::pipeline
