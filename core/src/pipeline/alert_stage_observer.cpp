// The pair observer (design §4.10): only for watched pairs, from the alert stage's view.
// Facts only; the observer words them.
#include <algorithm>

#include "alert_stage.hpp"
#include "zone_probe.hpp"
#include "kew/util/units.hpp"

namespace kew::pipeline {

namespace {

PairStage stage_of(eligibility::PairRule rule) {
  switch (rule) {
    case eligibility::PairRule::SameAddress: return PairStage::SameAddress;
    case eligibility::PairRule::LevelPair: return PairStage::LevelPair;
    case eligibility::PairRule::AdjacentLevelOff: return PairStage::AdjacentLevelOff;
    case eligibility::PairRule::Inhibited: return PairStage::Inhibited;
    case eligibility::PairRule::SameCode: return PairStage::SameCode;
    case eligibility::PairRule::Excluded: return PairStage::Excluded;
    case eligibility::PairRule::None: break;
  }
  return PairStage::ConfirmPending;
}

}  // namespace

void AlertStage::observe_watched_pairs(track::TrackSlot slot) {
  const track::Track& self = view_[slot].track;
  if (!observer_->watches(self.source, self.id)) return;
  for (const alert::PartyName& partner : observer_->partners(self.source, self.id, judged_at_))
    observer_->pair_judged(observe_pair(slot, partner));
}

ExclusionLimit AlertStage::exclusion_limit(eligibility::Exclusion why, const track::Track& t) const {
  const eligibility::EligibilityConfig& c = config_.eligibility;
  ExclusionLimit limit;
  switch (why) {
    case eligibility::Exclusion::Slow: limit.low = c.min_ground_speed_kt; break;
    case eligibility::Exclusion::AltitudeBand:
      limit.low = c.min_altitude_ft;
      limit.high = c.max_altitude_ft;
      break;
    case eligibility::Exclusion::BelowLowerLimit:
      limit.low = rules_.lower_limit_at(t.lat_deg, t.lon_deg, &limit.aerodrome);
      limit.aerodrome_height_ft = c.aerodrome_height_ft;
      break;
    case eligibility::Exclusion::PositionStale: limit.low = c.max_position_age_s; break;
    case eligibility::Exclusion::FirstRecords: limit.low = c.min_records; break;
    case eligibility::Exclusion::ExcludedCode:
    case eligibility::Exclusion::Coasting:
    case eligibility::Exclusion::None:
      break;
  }
  return limit;
}

PairObservation AlertStage::observe_pair(track::TrackSlot slot, alert::PartyName partner) {
  const track::Track& self = view_[slot].track;
  PairObservation o;
  o.t = judged_at_;
  o.updated = {self.source, self.id};
  o.partner = partner;
  const track::TrackSlot other = tracks_.find(partner.source, partner.id);
  // The track table may know the partner before the alert stage's view does (a record
  // without velocity), or under a slot this view still gives another track.
  if (other == track::kNoTrack || other >= view_.size() || !view_[other].track.in_use ||
      view_[other].track.source != partner.source || view_[other].track.id != partner.id) {
    o.stage = other == track::kNoTrack ? PairStage::NoTrack : PairStage::AwaitingVelocity;
    o.track_timeout_s = config_.tracks.track_timeout_s;
    return o;
  }
  if (!view_[other].track.in_engine) {
    o.stage = PairStage::AwaitingVelocity;
    return o;
  }
  const track::Track& them = view_[other].track;
  o.p = &view_[std::min(slot, other)].track;
  o.q = &view_[std::max(slot, other)].track;
  o.distance_m = geo::Projection::geodesic_distance_m({self.lat_deg, self.lon_deg}, {them.lat_deg, them.lon_deg});
  const zone::ZoneKey owner = zones_.owner_of(self, them);
  if (!zones_.holds_both(owner, self, them)) {
    o.stage = PairStage::NotCandidate;
    return o;
  }
  const zone::ProbeState state = state_in(owner, slot);
  const PairKinematics pair = judge_.pair(state, state.at(judged_at_), state_in(owner, other), judged_at_);
  const probe::ConflictGeometry g = probe::evaluate_pair(pair.kp, pair.kq, pair.minima);
  PairFigures& figures = o.figures.emplace();
  figures.sep_v_ft = g.sep_v_m / units::kMetresPerFoot;
  figures.cpa_h_m = g.cpa_h_m / pair.scale;
  figures.t_cpa_s = g.t_cpa_s;
  figures.cpa_v_ft = g.cpa_v_m / units::kMetresPerFoot;
  figures.t_los_s = g.t_los_s;
  o.vertical_lookahead_s = pair.minima.vertical_lookahead_s;
  o.confirm = pair.parameters.confirm;
  if (!judge_.in_conflict(pair.kp, pair.kq, pair.minima)) {
    o.stage = PairStage::ProbeClear;
    probe::SeparationMinima whole = pair.minima;  // the vertical prediction for all of T
    whole.vertical_lookahead_s = whole.lookahead_s;
    o.clear = g.cpa_h_m >= pair.minima.horizontal_m            ? ClearReason::NoHorizontalLoss
              : judge_.in_conflict(pair.kp, pair.kq, whole) ? ClearReason::BeyondVerticalLookahead
                                                             : ClearReason::VerticallyApart;
    return o;
  }
  const bool searched = std::any_of(evaluated_.begin(), evaluated_.end(),
                                    [&](const Evaluated& e) { return e.other == other; });
  if (!searched) {
    o.stage = PairStage::NotCandidate;
    return o;
  }
  o.verdict = rule_verdict(pair);
  if (o.verdict.rule != eligibility::PairRule::None) {
    o.stage = stage_of(o.verdict.rule);
    if (o.stage == PairStage::Excluded) {
      o.excluded = o.verdict.second_excluded ? o.q : o.p;
      o.limit = exclusion_limit(o.verdict.exclusion, *o.excluded);
    }
    return o;
  }
  o.stage = alerts_.is_active(pair.p, pair.q) ? PairStage::Alerting : PairStage::ConfirmPending;
  return o;
}

}  // namespace kew::pipeline
