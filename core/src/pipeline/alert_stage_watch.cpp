// The pair watch (design §4.10): only for watched pairs, from the alert stage's view.
#include <algorithm>

#include <fmt/format.h>

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

void AlertStage::note_watched_pairs(track::TrackSlot slot) {
  const track::Track& self = view_[slot].track;
  if (!watch_->watches(self.source, self.id)) return;
  watch_->for_each_partner(self.source, self.id, judged_at_,
                           [&](WatchedPair& pair, std::string_view source, std::string_view id) {
                             pair.notes.push_back(watched_pair_note(slot, source, id));
                           });
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

PairNote AlertStage::watched_pair_note(track::TrackSlot slot, std::string_view partner_source,
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
  const zone::ZoneKey owner = zones_.owner_of(self, them);
  const double apart_m = geo::Projection::geodesic_distance_m({self.lat_deg, self.lon_deg}, {them.lat_deg, them.lon_deg});
  if (!zones_.holds_both(owner, self, them)) {
    note.stage = PairStage::NotCandidate;
    note.detail = fmt::format("no zone holds both: {:.1f} NM apart", apart_m / units::kMetresPerNauticalMile);
    return note;
  }
  const zone::ProbeState state = state_in(owner, slot);
  const PairKinematics pair = judge_.pair(state, state.at(judged_at_), state_in(owner, other), judged_at_);
  const probe::ConflictGeometry g = probe::evaluate_pair(pair.kp, pair.kq, pair.minima);
  const track::Track& tp = view_[pair.p].track;
  const track::Track& tq = view_[pair.q].track;
  const std::string figures = fmt::format(
      "{:.2f} NM and {:.0f} ft apart; CPA {:.2f} NM in {:.0f} s, {:.0f} ft there; {} {:.0f} ft {:+.0f} fpm, "
      "{} {:.0f} ft {:+.0f} fpm",
      apart_m / units::kMetresPerNauticalMile, g.sep_v_m / units::kMetresPerFoot, g.cpa_h_m / pair.scale / units::kMetresPerNauticalMile, g.t_cpa_s, g.cpa_v_m / units::kMetresPerFoot,
      party_label(tp.source, tp.id), tp.alt_ft, tp.vr_fpm, party_label(tq.source, tq.id), tq.alt_ft, tq.vr_fpm);
  if (!judge_.in_conflict(pair.kp, pair.kq, pair.minima)) {
    note.stage = PairStage::ProbeClear;
    const bool horizontal = g.cpa_h_m >= pair.minima.horizontal_m;
    probe::SeparationMinima whole = pair.minima;  // the vertical prediction for all of T
    whole.vertical_lookahead_s = whole.lookahead_s;
    const bool vertical_lookahead = !horizontal && judge_.in_conflict(pair.kp, pair.kq, whole);
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
  const eligibility::PairVerdict v = rule_verdict(pair);
  if (v.rule != eligibility::PairRule::None) {
    note.stage = stage_of(v.rule);
    switch (note.stage) {
      case PairStage::SameAddress:
        note.detail = fmt::format("both address {:06X}; {}", tp.address.value_or(0), figures);
        break;
      case PairStage::SameCode:
        note.detail = fmt::format("both squawk {:04o}, no two addresses, positions and velocities alike; {}",
                                  tp.mode3a.value_or(0), figures);
        break;
      case PairStage::Excluded:
      {
        const track::Track& excluded = view_[v.second_excluded ? pair.q : pair.p].track;
        note.subject = party_label(excluded.source, excluded.id);
        note.detail = fmt::format("{}: {}", eligibility::kExclusionNames.name(v.exclusion),
                                  exclusion_detail(v.exclusion, excluded, judged_at_, config_.eligibility, rules_));
      }
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

}  // namespace kew::pipeline
