#include "kew/replay/evaluation.hpp"

#include "evaluation/scoring.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kew::replay {

namespace {

using namespace scoring_rules;

std::uint64_t aircraft_pair_key(AircraftId a, AircraftId b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

}  // namespace

void AlertCollector::add(const AlertEvent& event) {
  const auto open = open_.find(event.id);
  if (open == open_.end()) {
    AlertSpan span;
    span.id = event.id;
    span.kind = event.kind;
    span.volume = event.volume;
    span.volume_kind = event.volume_kind;
    span.a_source = event.a.source;
    span.a_id = event.a.id;
    span.a_callsign = event.a.callsign;
    span.b_source = event.b.source;
    span.b_id = event.b.id;
    span.b_callsign = event.b.callsign;
    span.opened_t = event.opened_t;
    span.max_severity = event.severity;
    span.events = 1;
    if (event.state == AlertState::End) {
      span.ended_t = event.t;
      span.end_reason = event.end_reason;
    } else {
      open_.emplace(event.id, alerts_.size());
    }
    alerts_.push_back(std::move(span));
    return;
  }
  AlertSpan& span = alerts_[open->second];
  ++span.events;
  span.max_severity = std::max(span.max_severity, event.severity);
  if (!event.a.callsign.empty()) span.a_callsign = event.a.callsign;
  if (!event.b.callsign.empty()) span.b_callsign = event.b.callsign;
  if (event.state == AlertState::End) {
    span.ended_t = event.t;
    span.end_reason = event.end_reason;
    open_.erase(open);
  }
}

double nearest_rank_percentile(std::span<const double> sorted, double p) {
  // p·n first: 90·10/100 is exactly 9, 0.9·10 need not be.
  const double rank = std::ceil(p * static_cast<double>(sorted.size()) / 100.0);
  const std::size_t index = rank <= 1.0 ? 0 : std::min(sorted.size() - 1, static_cast<std::size_t>(rank) - 1);
  return sorted[index];
}

std::optional<WarningTimes> warning_times(std::vector<double> warnings) {
  if (warnings.empty()) return std::nullopt;
  std::sort(warnings.begin(), warnings.end());
  return WarningTimes{warnings.front(), nearest_rank_percentile(warnings, 10.0),
                      nearest_rank_percentile(warnings, 50.0), nearest_rank_percentile(warnings, 90.0),
                      warnings.back()};
}

Evaluation evaluate(const Truth& truth, std::span<const AlertSpan> alerts, const ScoringParameters& parameters) {
  Evaluation out;
  EvaluationFigures& f = out.figures;
  out.alerts.resize(alerts.size());
  std::map<std::uint64_t, std::vector<std::size_t>> by_pair;  // aircraft pair → alerts, in input order

  for (std::size_t i = 0; i < alerts.size(); ++i) {
    const AlertSpan& alert = alerts[i];
    ScoredAlert& scored = out.alerts[i];
    const auto ta = truth.find_track(alert.a_source, alert.a_id);
    const auto tb = truth.find_track(alert.b_source, alert.b_id);
    const auto from = static_cast<std::int64_t>(std::ceil(alert.opened_t - kHitBefore_s));
    const auto to = static_cast<std::int64_t>(std::floor(alert.opened_t + parameters.lookahead_s + kHitAfter_s));
    std::optional<AircraftId> a, b;
    if (ta && tb) {
      a = truth.aircraft_of(*ta);
      b = truth.aircraft_of(*tb);
      if (*a != *b) by_pair[aircraft_pair_key(*a, *b)].push_back(i);
    }
    const bool two_aircraft = a && *a != *b;
    if (two_aircraft) scored.loss_s = truth.first_loss_second(*a, *b, from, to);
    if (a && !two_aircraft) {
      scored.cls = AlertClass::Ineligible;
      scored.reason = IneligibleReason::OneAircraft;
    } else if (scored.loss_s) {
      scored.cls = AlertClass::Hit;
    } else if (two_aircraft && truth.any_close_second(*a, *b, from, to)) {
      scored.cls = AlertClass::CloseCall;
    } else {
      const auto sa = ta ? truth.nearest_sample(*ta, alert.opened_t, kNearestSample_s) : std::nullopt;
      const auto sb = tb ? truth.nearest_sample(*tb, alert.opened_t, kNearestSample_s) : std::nullopt;
      if (!sa || !sb) {
        scored.cls = AlertClass::Ineligible;
        scored.reason = IneligibleReason::NoTruth;
      } else if (!sa->second.airborne || !sb->second.airborne) {
        scored.cls = AlertClass::Ineligible;
        scored.reason = IneligibleReason::NotAirborne;
      } else {
        scored.cls = AlertClass::Nuisance;
      }
    }
    scoring::count_alert(f, scored.cls, scored.reason);
  }

  std::vector<double> warnings;
  const std::vector<LossEvent>& events = truth.loss_events();
  out.losses.reserve(events.size());
  for (const LossEvent& event : events) {
    const auto pair = by_pair.find(aircraft_pair_key(event.a, event.b));
    const std::int64_t eligible = std::max(truth.airborne_since(event.track_a, event.start_s).value_or(event.start_s),
                                           truth.airborne_since(event.track_b, event.start_s).value_or(event.start_s));
    const double period = scoring::update_period_s(truth.track(event.track_a), &truth.track(event.track_b));
    out.losses.push_back(scoring::score_event(alerts, pair == by_pair.end() ? nullptr : &pair->second, event.start_s,
                                              eligible, parameters.confirm * period, f, warnings));
  }

  f.flight_hours = truth.figures().flight_hours();
  if (f.flight_hours > 0.0) f.alerts_per_100_flight_hours = 100.0 * static_cast<double>(f.alerts) / f.flight_hours;
  f.loss_events = events.size();
  scoring::finish(f, std::move(warnings));
  return out;
}

}  // namespace kew::replay
