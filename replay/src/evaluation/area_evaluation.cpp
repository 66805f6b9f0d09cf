#include "kew/replay/area_evaluation.hpp"

#include "evaluation/scoring.hpp"

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
    scoring::count_alert(out.by_kind[s.kind], s.cls, s.reason);
    if (!s.volume) continue;
    if (const auto track = truth.find_track(alerts[i].a_source, alerts[i].a_id))
      by_volume[volume_aircraft_key(*s.volume, truth.aircraft_of(*track))].push_back(i);
  }

  std::map<volume::VolumeKind, std::vector<double>> warnings;
  out.entries.reserve(areas.entries().size());
  for (const AreaEntry& entry : areas.entries()) {
    const volume::VolumeKind kind = areas.volumes()[entry.volume].kind;
    AreaFigures& f = out.by_kind[kind];
    ++f.entries;
    const auto alerts_of = by_volume.find(volume_aircraft_key(entry.volume, entry.aircraft));
    out.entries.push_back(scoring::score_event(alerts, alerts_of == by_volume.end() ? nullptr : &alerts_of->second,
                                               entry.start_s, entry.eligible_since_s,
                                               confirm * areas.update_period_s(entry), f, warnings[kind]));
  }

  for (auto& [kind, f] : out.by_kind) scoring::finish(f, std::move(warnings[kind]));
  return out;
}

}  // namespace kew::replay
