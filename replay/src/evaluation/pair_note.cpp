#include "evaluation/pair_note.hpp"

#include <string>

#include <fmt/format.h>

#include "kew/util/units.hpp"

namespace kew::replay {

namespace {

std::string label(const alert::PartyName& party) { return party_label(party.source, party.id); }
std::string label(const track::Track& t) { return party_label(t.source, t.id); }

/// Distances now and at the CPA, and both tracks' altitudes and rates.
std::string figures_of(const PairObservation& o) {
  const PairFigures& f = *o.figures;
  return fmt::format(
      "{:.2f} NM and {:.0f} ft apart; CPA {:.2f} NM in {:.0f} s, {:.0f} ft there; {} {:.0f} ft {:+.0f} fpm, "
      "{} {:.0f} ft {:+.0f} fpm",
      o.distance_m / units::kMetresPerNauticalMile, f.sep_v_ft, f.cpa_h_m / units::kMetresPerNauticalMile, f.t_cpa_s,
      f.cpa_v_ft, label(*o.p), o.p->alt_ft, o.p->vr_fpm, label(*o.q), o.q->alt_ft, o.q->vr_fpm);
}

std::string clear_detail(const PairObservation& o) {
  switch (o.clear) {
    case ClearReason::NoHorizontalLoss: return "no horizontal loss within the look-ahead";
    case ClearReason::BeyondVerticalLookahead:
      return fmt::format("vertically apart; the rates close below S_v less the tolerance only after the vertical "
                         "look-ahead, {:.0f} s",
                         o.vertical_lookahead_s);
    case ClearReason::VerticallyApart: break;
  }
  return "vertically apart where horizontally close";
}

/// The excluded track's figure the exclusion read, against its limit.
std::string exclusion_detail(const PairObservation& o) {
  const track::Track& t = *o.excluded;
  const ExclusionLimit& limit = o.limit;
  const std::string who = label(t);
  switch (o.verdict.exclusion) {
    case eligibility::Exclusion::Slow:
      return fmt::format("{} at {:.0f} kt, below {:.0f} kt", who, t.gs_kt, limit.low);
    case eligibility::Exclusion::AltitudeBand:
      return fmt::format("{} at {:.0f} ft, outside {:.0f}..{:.0f} ft", who, t.alt_ft, limit.low, limit.high);
    case eligibility::Exclusion::BelowLowerLimit:
      return limit.aerodrome
                 ? fmt::format("{} at {:.0f} ft, below the lower limit {:.0f} ft ({:.0f} ft above {}, {:.0f} ft)", who,
                               t.alt_ft, limit.low, limit.aerodrome_height_ft, limit.aerodrome->ident,
                               limit.aerodrome->elevation_ft)
                 : fmt::format("{} at {:.0f} ft, below the lower limit {:.0f} ft", who, t.alt_ft, limit.low);
    case eligibility::Exclusion::ExcludedCode:
      return fmt::format("{} squawks {:04o}", who, t.mode3a.value_or(0));
    case eligibility::Exclusion::Coasting:
      return fmt::format("{} coasting (its source extrapolates it)", who);
    case eligibility::Exclusion::PositionStale:
      return fmt::format("{} last record {:.0f} s old, over {:.0f} s", who, o.t - t.t, limit.low);
    case eligibility::Exclusion::FirstRecords:
      return fmt::format("{} seen in {} record(s), fewer than {:.0f}", who, t.records, limit.low);
    case eligibility::Exclusion::None:
      break;
  }
  return who;
}

/// The detail of a pair the conflict test judged (o.figures).
std::string judged_detail(const PairObservation& o) {
  const std::string figures = figures_of(o);
  switch (o.stage) {
    case PairStage::NotCandidate: return fmt::format("{} (the candidate search did not give the pair)", figures);
    case PairStage::ProbeClear: return fmt::format("{} ({})", figures, clear_detail(o));
    case PairStage::SameAddress: return fmt::format("both address {:06X}; {}", o.p->address.value_or(0), figures);
    case PairStage::SameCode:
      return fmt::format("both squawk {:04o}, no two addresses, positions and velocities alike; {}",
                         o.p->mode3a.value_or(0), figures);
    case PairStage::Excluded:
      return fmt::format("{}: {}", eligibility::kExclusionNames.name(o.verdict.exclusion), exclusion_detail(o));
    case PairStage::ConfirmPending:
    case PairStage::Alerting: return fmt::format("t_los {:.0f} s; {}", o.figures->t_los_s, figures);
    default: return figures;  // level_pair, adjacent_level_off, inhibited
  }
}

}  // namespace

PairNote note_of(const PairObservation& o, std::optional<double> partner_last_seen) {
  PairNote note;
  note.t = o.t;
  note.updated = label(o.updated);
  note.stage = o.stage;
  if (o.stage == PairStage::NoTrack || o.stage == PairStage::AwaitingVelocity) {
    const std::string partner = label(o.partner);
    note.subject = partner;
    note.detail = o.stage == PairStage::AwaitingVelocity ? fmt::format("{} has no velocity yet", partner)
                  : partner_last_seen
                      ? fmt::format("{} has no track since its last record {:.0f} s ago (dropped after the {:.0f} s "
                                    "timeout, or ended by its source)",
                                    partner, o.t - *partner_last_seen, o.track_timeout_s)
                      : fmt::format("{} has no track: no record of it yet", partner);
    return note;
  }
  if (!o.figures) {
    note.detail = fmt::format("no zone holds both: {:.1f} NM apart", o.distance_m / units::kMetresPerNauticalMile);
    return note;
  }
  if (o.stage == PairStage::Excluded) note.subject = label(*o.excluded);
  note.detail = judged_detail(o);
  return note;
}

std::optional<PairNote> note_of(const TrackReport& report, const RecordOutcome& outcome) {
  if (outcome.kind != RecordOutcome::Kind::AwaitingVelocity && outcome.kind != RecordOutcome::Kind::Refused)
    return std::nullopt;
  PairNote note;
  note.t = report.t;
  note.updated = note.subject = party_label(report.source, report.id);
  if (outcome.kind == RecordOutcome::Kind::AwaitingVelocity) {
    note.stage = PairStage::AwaitingVelocity;
    note.detail = fmt::format("{} has no velocity yet", note.updated);
  } else {
    note.stage = PairStage::RecordRefused;
    note.detail = fmt::format("{} record refused: {}", note.updated, track::kRefusalNames.name(outcome.refusal));
  }
  return note;
}

}  // namespace kew::replay
