#include "evaluation/scoring.hpp"

#include <algorithm>
#include <cmath>

namespace kew::replay::scoring {

using namespace scoring_rules;

void count_alert(ScoreFigures& f, AlertClass cls, IneligibleReason reason) {
  ++f.alerts;
  switch (cls) {
    case AlertClass::Hit: ++f.hits; break;
    case AlertClass::CloseCall: ++f.close_calls; break;
    case AlertClass::Nuisance: ++f.nuisances; break;
    case AlertClass::Ineligible:
      ++f.ineligible;
      if (reason == IneligibleReason::OneAircraft) ++f.ineligible_one_aircraft;
      if (reason == IneligibleReason::NotAirborne) ++f.ineligible_not_airborne;
      if (reason == IneligibleReason::NoTruth) ++f.ineligible_no_truth;
      break;
  }
}

ScoredEvent score_event(std::span<const AlertSpan> alerts, const std::vector<std::size_t>* candidates,
                        std::int64_t start_s, std::int64_t eligible_since_s, double unwarnable_within_s,
                        ScoreFigures& f, std::vector<double>& warnings) {
  ScoredEvent scored;
  const auto start = static_cast<double>(start_s);
  // The warning the controller had: the earliest alert that was open, or had ended only
  // just, when the event began.
  if (candidates) {
    for (const std::size_t i : *candidates) {
      const AlertSpan& alert = alerts[i];
      if (alert.opened_t > start + kOpenTolerance_s) continue;
      if (alert.ended_t && *alert.ended_t < start - kEndedBefore_s) continue;
      if (!scored.alert || alert.opened_t < alerts[*scored.alert].opened_t) scored.alert = i;
    }
  }
  if (scored.alert) scored.warning_s = start - alerts[*scored.alert].opened_t;
  scored.eligible_for_s = start_s - eligible_since_s;
  if (static_cast<double>(scored.eligible_for_s) <= unwarnable_within_s) {
    scored.outcome = LossOutcome::Unwarnable;
    ++f.unwarnable;
  } else if (scored.alert) {
    scored.outcome = LossOutcome::Detected;
    ++f.detected;
    warnings.push_back(*scored.warning_s);
  } else {
    scored.outcome = LossOutcome::Missed;
    ++f.missed;
  }
  return scored;
}

void finish(ScoreFigures& f, std::vector<double> warnings) {
  if (f.alerts > 0)
    f.undesirable_share = static_cast<double>(f.nuisances + f.ineligible) / static_cast<double>(f.alerts);
  f.warning = warning_times(std::move(warnings));
}

double update_period_s(const TruthTrack& a, const TruthTrack* b) {
  double period = 0.0;
  if (std::isfinite(a.median_interval_s)) period = std::max(period, a.median_interval_s);
  if (b && std::isfinite(b->median_interval_s)) period = std::max(period, b->median_interval_s);
  return period;
}

}  // namespace kew::replay::scoring
