#pragma once
// What scoring pair alerts (evaluation.cpp) and area proximity warnings
// (area_evaluation.cpp) share, so that both keep one set of rules: an alert counted by
// its class, an event (a loss, an entry) judged by the earliest alert of its aircraft
// that was open when it began, and the figures drawn from the counts. Internal to
// kew_replay.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "kew/replay/evaluation.hpp"
#include "kew/replay/truth.hpp"

namespace kew::replay::scoring {

void count_alert(ScoreFigures& f, AlertClass cls, IneligibleReason reason);

/// An event that began at `start_s` and became eligible at `eligible_since_s` (UTC s):
/// unwarnable when that is at most `unwarnable_within_s` before its start; else detected
/// by the earliest of `candidates` (indices into `alerts`, the alerts of its aircraft;
/// null for none) that opened by start + kOpenTolerance_s and had not ended more than
/// kEndedBefore_s before it; else missed. Counted in `f`; a detected event's warning time
/// is appended to `warnings`.
ScoredEvent score_event(std::span<const AlertSpan> alerts, const std::vector<std::size_t>* candidates,
                        std::int64_t start_s, std::int64_t eligible_since_s, double unwarnable_within_s,
                        ScoreFigures& f, std::vector<double>& warnings);

/// The figures drawn from the counts and the detected events' `warnings`: the undesirable
/// share and the warning times.
void finish(ScoreFigures& f, std::vector<double> warnings);

/// The larger of the tracks' median update intervals, ignoring unknown ones (0 when every
/// one is); `b` may be null.
double update_period_s(const TruthTrack& a, const TruthTrack* b);

}  // namespace kew::replay::scoring
