#include "alert_stage.hpp"

#include <algorithm>
#include <cmath>

#include "alert_party.hpp"
#include "kew/util/gentle_growth.hpp"
#include "zone_probe.hpp"
#include "kew/util/units.hpp"

namespace kew::pipeline {

namespace {
// ProbeMode::Brute in worldwide mode evaluates every pair whose last reports are within
// twice the distance at which two aircraft can still come into conflict, plus this (m).
constexpr double kBruteSlack_m = 50e3;
constexpr double kEarthRadius_m = 6371008.8;  // mean radius, for the brute force's cut only

bool ordered_before(const track::Track& x, const track::Track& y) {
  return x.source != y.source ? x.source < y.source : x.id < y.id;
}
}  // namespace

AlertStage::AlertStage(const PipelineConfig& config, const PairJudge& judge, ZoneSet& zones,
                       const PipelineInstrumentation& instruments, const track::TrackTable& tracks)
    : config_(config),
      judge_(judge),
      zones_(zones),
      instruments_(instruments),
      tracks_(tracks),
      alerts_(config.alerts,
              [this](track::TrackSlot slot) {
                // The alert stage names parties as they were when it judged them.
                const track::Track& track = view_[slot].track;
                return alert::PartyName{track.source, track.id};
              }),
      rules_(config.eligibility, config.minima),
      areas_(config.volumes, rules_, zones) {
  if (zones_.tiling()) {
    const double fastest_mps = config.tracks.max_ground_speed_kt * units::kMpsPerKnot;
    brute_reach_m_ = 2.0 * (judge.largest_horizontal_m() +
                            2.0 * fastest_mps * (judge.largest_lookahead_s() + config.tracks.track_timeout_s)) +
                     kBruteSlack_m;
  }
}

void AlertStage::run(Batch& batch) {
  for (const AlertStep& step : batch.steps) run_step(batch, step);
}

void AlertStage::run_step(Batch& batch, const AlertStep& step) {
  judged_at_ = step.t;
  if (step.kind == AlertStep::Kind::DropAlerts) {
    view_[step.slot].track.in_engine = false;
    alerts_.drop_track(step.slot, step.t, pending_events_);
    areas_.track_left(step.slot, step.t, alerts_, pending_events_);
    deliver();
    return;
  }
  const track::TrackSlot slot = step.slot;
  util::grow_to(view_, static_cast<std::size_t>(slot) + 1);
  view_[slot] = std::move(batch.snapshots[step.snapshot]);
  ++probes_;
  evaluated_.clear();
  for (std::uint32_t i = step.first_zone; i < step.first_zone + step.zone_count; ++i) {
    const zone::ZoneKey key = batch.step_zones[i];
    const ZoneSet::Probed probed = zones_.next_probe(key);
    candidates_ += probed.candidates;
    for (const FoundPair& f : probed.found) evaluated_.push_back({f.other, key, f.pair});
  }
  const bool brute_sphere = zones_.tiling() && config_.probe_mode == probe::ProbeMode::Brute;
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
    ++candidates_;  // the search did not find it in conflict
    // A pair no zone holds whole is too far apart to be in conflict (design §4.9) and
    // is evaluated clear.
    const zone::ZoneKey owner = zones_.owner_of(view_[slot].track, view_[other].track);
    const bool held = brute_sphere || zones_.holds_both(owner, view_[slot].track, view_[other].track);
    evaluated_.push_back({other, held ? owner : zone::kNoZone, std::nullopt});
  }
  evaluate_pairs(slot);
  areas_.judge(slot, view_, judged_at_, alerts_, suppressed_, pending_events_);
  deliver();
  if (observer_) observe_watched_pairs(slot);
}

void AlertStage::brute_over_sphere(track::TrackSlot slot) {
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
    ++candidates_;
    const zone::ZoneKey owner = zones_.owner_of(view_[slot].track, view_[other].track);
    if (owner != self_plane) {
      self = state_in(owner, slot);
      self_plane = owner;
    }
    const PairKinematics pair = judge_.pair(self, self.at(judged_at_), state_in(owner, other), judged_at_);
    if (judge_.in_conflict(pair.kp, pair.kq, pair.minima)) evaluated_.push_back({other, owner, pair});
  }
}

zone::ProbeState AlertStage::state_in(zone::ZoneKey key, track::TrackSlot slot) {
  return member_state(view_[slot], zones_.plane(key), key);
}

void AlertStage::evaluate_pairs(track::TrackSlot slot) {
  std::sort(evaluated_.begin(), evaluated_.end(),
            [](const Evaluated& a, const Evaluated& b) { return a.other < b.other; });
  const double now = judged_at_;
  for (const Evaluated& pick : evaluated_) {
    const track::TrackSlot other = pick.other;
    alert::Evaluation e;
    if (pick.zone == zone::kNoZone) {
      const PairParameters parameters = judge_.parameters(view_[slot].base.region, view_[other].base.region);
      e.confirm = parameters.confirm;
      e.clear = parameters.clear;
      e.observed_t = view_[slot].track.t;
      alerts_.evaluate(std::min(slot, other), std::max(slot, other), e, now, [](AlertEvent&) {}, pending_events_);
      continue;
    }
    // A pair a zone found in conflict comes with its verdict; a partner the search did
    // not give is tested here, once.
    PairKinematics tested;
    if (!pick.in_conflict) {
      const zone::ProbeState self = state_in(pick.zone, slot);
      tested = judge_.pair(self, self.at(now), state_in(pick.zone, other), now);
    }
    const PairKinematics& pair = pick.in_conflict ? *pick.in_conflict : tested;
    const bool found = pick.in_conflict || judge_.in_conflict(pair.kp, pair.kq, pair.minima);
    // Most pairs are clear: decide that without the figures, which only events need.
    probe::ConflictGeometry g;
    bool along_turn = false;
    if (found && instruments_.conflict_tap) instruments_.conflict_tap(pair.p, pair.q);  // before the rules
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
      e.cpa_v_ft = g.cpa_v_m / units::kMetresPerFoot;
    }
    alerts_.evaluate(
        pair.p, pair.q, e, now,
        [&](AlertEvent& event) {
          fill_event(event, zones_.plane(pick.zone), pair, g, along_turn);
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

eligibility::PairVerdict AlertStage::rule_verdict(const PairKinematics& pair) const {
  eligibility::PairContext context;
  context.now = judged_at_;
  context.distance_m = geometry::norm(pair.kp.position - pair.kq.position) / pair.scale;
  context.alert_open = alerts_.is_active(pair.p, pair.q);
  context.inhibited = pair.parameters.inhibited;
  return rules_.verdict(view_[pair.p].track, view_[pair.q].track, context);
}

bool AlertStage::suppressed_by_rules(const PairKinematics& pair) {
  const eligibility::PairVerdict v = rule_verdict(pair);
  switch (v.rule) {
    case eligibility::PairRule::None:
      return false;
    case eligibility::PairRule::SameAddress:
    case eligibility::PairRule::SameCode:
      suppressed_.reject("same_aircraft");
      break;
    case eligibility::PairRule::Excluded:
      suppressed_.reject(eligibility::kExclusionNames.name(v.exclusion));
      break;
    default:
      suppressed_.reject(eligibility::kPairRuleNames.name(v.rule));  // level_pair, adjacent_level_off, inhibited
      break;
  }
  return true;
}

void AlertStage::fill_event(AlertEvent& event, const geo::Projection& projection, const PairKinematics& pair,
                            const probe::ConflictGeometry& g, bool along_turn) const {
  const track::Track& tp = view_[pair.p].track;
  const track::Track& tq = view_[pair.q].track;
  const probe::Kinematics& kp = pair.kp;
  const probe::Kinematics& kq = pair.kq;
  const bool p_first = ordered_before(tp, tq);
  event.a = party_of(p_first ? tp : tq);
  event.b = party_of(p_first ? tq : tp);
  event.t_los_s = g.t_los_s;
  event.t_cpa_s = g.t_cpa_s;
  event.cpa_v_ft = g.cpa_v_m / units::kMetresPerFoot;
  event.sep_v_ft = g.sep_v_m / units::kMetresPerFoot;
  // Horizontal figures on the ellipsoid: the plane overstates lengths by the scale k.
  const auto geodesic = [&](geometry::Point2 x, geometry::Point2 y) {
    return geo::Projection::geodesic_distance_m(projection.unproject(x), projection.unproject(y));
  };
  event.sep_h_m = geodesic(kp.position, kq.position);
  event.cpa_h_m = along_turn ? geodesic(probe::position_along_turn(kp, g.t_cpa_s), probe::position_along_turn(kq, g.t_cpa_s))
                             : geodesic(kp.position + g.t_cpa_s * kp.velocity, kq.position + g.t_cpa_s * kq.velocity);
}

void AlertStage::deliver() {
  if (sink_)
    for (const AlertEvent& event : pending_events_)
      if (serves(event)) sink_(event);
  pending_events_.clear();
}

bool AlertStage::serves(const AlertEvent& event) const {
  if (!config_.served_longitudes || !zones_.tiling()) return true;
  // A pair is its midpoint's; an area proximity warning its aircraft's.
  double lon = event.kind == AlertKind::Apw
                   ? event.a.lon_deg
                   : zone::ZoneTiling::midpoint({event.a.lat_deg, event.a.lon_deg}, {event.b.lat_deg, event.b.lon_deg})
                         .lon_deg;
  if (lon >= 180.0) lon -= 360.0;  // 180 is −180, as in ZoneTiling::home
  return lon >= config_.served_longitudes->west_deg && lon < config_.served_longitudes->east_deg;
}

}  // namespace kew::pipeline
