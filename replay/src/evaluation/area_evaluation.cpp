#include "kew/replay/area_evaluation.hpp"

#include <algorithm>
#include <cmath>

namespace kew::replay {

namespace {

using namespace scoring_rules;

std::uint64_t volume_aircraft_key(std::uint32_t volume, AircraftId aircraft) {
  return (static_cast<std::uint64_t>(volume) << 32) | aircraft;
}

// Classifies one APW alert (the order of area_evaluation.hpp).
ScoredAreaAlert score(const Truth& truth, const AreaTruth& areas, const AlertSpan& alert) {
  ScoredAreaAlert scored;
  scored.volume = areas.find_volume(alert.volume);
  if (scored.volume)
    scored.kind = areas.volumes()[*scored.volume].kind;
  else if (const auto kind = volume::kVolumeKindNames.parse(alert.volume_kind))
    scored.kind = *kind;
  const auto ineligible = [&](IneligibleReason reason) {
    scored.cls = AlertClass::Ineligible;
    scored.reason = reason;
    return scored;
  };
  const std::optional<TruthTrackId> track = truth.find_track(alert.a_source, alert.a_id);
  if (!scored.volume || !track) return ineligible(IneligibleReason::NoTruth);
  const std::uint32_t v = *scored.volume;
  const volume::WatchedVolume& w = areas.volumes()[v];
  const AircraftId aircraft = truth.aircraft_of(*track);
  const std::optional<TruthTrackId> centre =
      w.area ? std::nullopt : areas.nearest_centre(v, alert.opened_t, kNearestSample_s);
  if (centre && truth.aircraft_of(*centre) == aircraft) return ineligible(IneligibleReason::OneAircraft);

  const auto from = static_cast<std::int64_t>(std::ceil(alert.opened_t - kHitBefore_s));
  const auto to = static_cast<std::int64_t>(std::floor(alert.opened_t + w.lookahead_s + kHitAfter_s));
  scored.entry_s = areas.first_inside_second(v, aircraft, from, to);
  if (scored.entry_s) {
    scored.cls = AlertClass::Hit;
    return scored;
  }
  if (areas.any_close_second(v, aircraft, from, to)) {
    scored.cls = AlertClass::CloseCall;
    return scored;
  }
  const auto sample = truth.nearest_sample(*track, alert.opened_t, kNearestSample_s);
  if (!sample || (!w.area && !centre)) return ineligible(IneligibleReason::NoTruth);
  if (!flies_for_areas(sample->second)) return ineligible(IneligibleReason::NotAirborne);
  scored.cls = AlertClass::Nuisance;
  return scored;
}

void tally(AreaFigures& f, const ScoredAreaAlert& s) {
  ++f.alerts;
  switch (s.cls) {
    case AlertClass::Hit: ++f.hits; break;
    case AlertClass::CloseCall: ++f.close_calls; break;
    case AlertClass::Nuisance: ++f.nuisances; break;
    case AlertClass::Ineligible:
      ++f.ineligible;
      if (s.reason == IneligibleReason::OneAircraft) ++f.ineligible_one_aircraft;
      if (s.reason == IneligibleReason::NotAirborne) ++f.ineligible_not_airborne;
      if (s.reason == IneligibleReason::NoTruth) ++f.ineligible_no_truth;
      break;
  }
}

}  // namespace

std::vector<AlertSpan> alerts_of_kind(std::span<const AlertSpan> alerts, AlertKind kind) {
  std::vector<AlertSpan> out;
  std::copy_if(alerts.begin(), alerts.end(), std::back_inserter(out),
               [kind](const AlertSpan& a) { return a.kind == kind; });
  return out;
}

AreaEvaluation evaluate_areas(const Truth& truth, const AreaTruth& areas, std::span<const AlertSpan> alerts,
                              int confirm) {
  AreaEvaluation out;
  for (const volume::WatchedVolume& w : areas.volumes()) ++out.by_kind[w.kind].volumes;

  std::map<std::uint64_t, std::vector<std::size_t>> by_volume;  // (volume, aircraft) → alerts, in input order
  out.alerts.reserve(alerts.size());
  for (std::size_t i = 0; i < alerts.size(); ++i) {
    out.alerts.push_back(score(truth, areas, alerts[i]));
    const ScoredAreaAlert& s = out.alerts.back();
    tally(out.by_kind[s.kind], s);
    if (!s.volume) continue;
    if (const auto track = truth.find_track(alerts[i].a_source, alerts[i].a_id))
      by_volume[volume_aircraft_key(*s.volume, truth.aircraft_of(*track))].push_back(i);
  }

  std::map<volume::VolumeKind, std::vector<double>> warnings;
  const std::vector<AreaEntry>& entries = areas.entries();
  out.entries.resize(entries.size());
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const AreaEntry& entry = entries[k];
    ScoredAreaEntry& scored = out.entries[k];
    const volume::VolumeKind kind = areas.volumes()[entry.volume].kind;
    AreaFigures& f = out.by_kind[kind];
    ++f.entries;
    const auto start = static_cast<double>(entry.start_s);
    // The earliest alert of the aircraft and volume that was open, or had ended only
    // just, when the aircraft entered.
    if (const auto it = by_volume.find(volume_aircraft_key(entry.volume, entry.aircraft)); it != by_volume.end()) {
      for (const std::size_t i : it->second) {
        const AlertSpan& alert = alerts[i];
        if (alert.opened_t > start + kOpenTolerance_s) continue;
        if (alert.ended_t && *alert.ended_t < start - kEndedBefore_s) continue;
        if (!scored.alert || alert.opened_t < alerts[*scored.alert].opened_t) scored.alert = i;
      }
    }
    if (scored.alert) scored.warning_s = start - alerts[*scored.alert].opened_t;
    scored.eligible_for_s = entry.start_s - entry.eligible_since_s;
    if (static_cast<double>(scored.eligible_for_s) <= confirm * areas.update_period_s(entry)) {
      scored.outcome = LossOutcome::Unwarnable;
      ++f.unwarnable;
    } else if (scored.alert) {
      scored.outcome = LossOutcome::Detected;
      ++f.detected;
      warnings[kind].push_back(*scored.warning_s);
    } else {
      scored.outcome = LossOutcome::Missed;
      ++f.missed;
    }
  }

  for (auto& [kind, f] : out.by_kind) {
    if (f.alerts > 0)
      f.undesirable_share = static_cast<double>(f.nuisances + f.ineligible) / static_cast<double>(f.alerts);
    std::vector<double>& w = warnings[kind];
    if (w.empty()) continue;
    std::sort(w.begin(), w.end());
    f.warning = WarningTimes{w.front(), nearest_rank_percentile(w, 10.0), nearest_rank_percentile(w, 50.0),
                             nearest_rank_percentile(w, 90.0), w.back()};
  }
  return out;
}

}  // namespace kew::replay
