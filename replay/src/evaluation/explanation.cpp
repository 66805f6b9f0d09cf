#include "kew/replay/explanation.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

namespace kew::replay {

using explanation_rules::kLeadIn_s;

std::vector<std::size_t> losses_to_explain(const Evaluation& evaluation, double late_s) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < evaluation.losses.size(); ++k) {
    const ScoredLoss& s = evaluation.losses[k];
    // An unwarnable loss kew warned of in time anyway needs no explanation.
    if (!s.warning_s || *s.warning_s < late_s) out.push_back(k);
  }
  return out;
}

namespace {

bool same_party(const TruthTrack& t, const std::string& source, const std::string& id) {
  return t.source == source && t.id == id;
}

/// Where the pair's notes stop: the opening of the alert that detected the loss late, or
/// of the first alert of its two tracks that opened during the loss (what came after did
/// not delay it), else the loss's end.
double cutoff(const Truth& truth, const LossEvent& loss, const ScoredLoss& scored, std::span<const AlertSpan> alerts) {
  if (scored.alert) return alerts[*scored.alert].opened_t;
  double end = static_cast<double>(loss.end_s) + 1.0;
  const TruthTrack& a = truth.track(loss.track_a);
  const TruthTrack& b = truth.track(loss.track_b);
  for (const AlertSpan& alert : alerts) {
    const bool pair = (same_party(a, alert.a_source, alert.a_id) && same_party(b, alert.b_source, alert.b_id)) ||
                      (same_party(b, alert.a_source, alert.a_id) && same_party(a, alert.b_source, alert.b_id));
    if (pair && alert.opened_t >= static_cast<double>(loss.start_s) && alert.opened_t < end) end = alert.opened_t;
  }
  return end;
}

bool in_conflict_stage(PairStage s) { return s == PairStage::ConfirmPending || s == PairStage::Alerting; }

std::vector<StageSpan> spans_of(const std::vector<PairNote>& notes) {
  std::vector<StageSpan> spans;
  for (const PairNote& n : notes) {
    if (spans.empty() || spans.back().stage != n.stage) {
      spans.push_back(StageSpan{n.stage, n.t, n.t, 0, n, n});
    }
    StageSpan& s = spans.back();
    s.last_t = n.t;
    s.last = n;
    ++s.notes;
  }
  return spans;
}

/// The decisive stage of the notes before the cutoff (design §4.10): the stage before
/// the run of conflicting evaluations that ended in the alert (or held at the end),
/// unless that run began early enough to warn `late_s` ahead: then confirmation
/// delayed the alert. Without such a run, the stage held at most updates from
/// `late_s` before the loss on. Refused records decide where the pair had no
/// track to judge.
void decide(LossExplanation& out, const std::vector<PairNote>& notes, const LossEvent& loss, double end,
            double late_s) {
  const double start = static_cast<double>(loss.start_s);
  std::vector<const PairNote*> judged;  // the alert stage's notes, refusals aside
  std::vector<const PairNote*> refusals;
  for (const PairNote& n : notes) (n.stage == PairStage::RecordRefused ? refusals : judged).push_back(&n);
  const bool refused = !refusals.empty();
  const PairNote* last_refusal = refused ? refusals.back() : nullptr;
  if (judged.empty()) {
    out.stage = refused ? PairStage::RecordRefused : PairStage::NoTrack;
    out.reason = refused ? fmt::format("every record of the window was refused; last: {}", last_refusal->detail)
                         : "neither aircraft was updated in kew within the window";
    return;
  }
  std::size_t streak = judged.size();
  while (streak > 0 && in_conflict_stage(judged[streak - 1]->stage)) --streak;
  const PairNote* decisive = nullptr;
  if (streak < judged.size()) {
    const PairNote& first_conflict = *judged[streak];
    if (first_conflict.t <= start - late_s) {
      out.stage = PairStage::ConfirmPending;
      out.reason = fmt::format("in conflict {:.0f} s before the loss, {:.0f} s and {} evaluations before it opened: {}",
                               start - first_conflict.t, std::min(end, static_cast<double>(loss.end_s)) - first_conflict.t,
                               judged.size() - streak, first_conflict.detail);
      return;
    }
    if (streak == 0) {
      out.stage = PairStage::NoTrack;
      out.reason = fmt::format("the pair was first judged {:.0f} s before the loss, already in conflict: {}",
                               start - first_conflict.t, first_conflict.detail);
      return;
    }
    decisive = judged[streak - 1];
  } else {
    std::map<PairStage, std::size_t> held;
    for (const PairNote* n : judged)
      if (n->t >= start - late_s) ++held[n->stage];
    if (held.empty()) {
      decisive = judged.back();
    } else {
      const auto most = std::max_element(held.begin(), held.end(),
                                         [](const auto& x, const auto& y) { return x.second < y.second; });
      for (auto it = judged.rbegin(); it != judged.rend() && !decisive; ++it)
        if ((*it)->stage == most->first) decisive = *it;
    }
  }
  out.stage = decisive->stage;
  // A party without a track or velocity because its records were refused: the refusal
  // decides (a duplicate of a record already applied takes nothing away).
  if (out.stage == PairStage::NoTrack || out.stage == PairStage::AwaitingVelocity) {
    for (auto it = refusals.rbegin(); it != refusals.rend(); ++it) {
      if ((*it)->subject != decisive->subject || (*it)->t > decisive->t ||
          (*it)->detail.ends_with(": duplicate_time"))
        continue;
      out.stage = PairStage::RecordRefused;
      out.reason = fmt::format("{}; its record at {:+.0f} s was refused: {}", decisive->detail, (*it)->t - start,
                               (*it)->detail);
      return;
    }
  }
  out.reason = fmt::format("at {:+.0f} s ({} updated): {}", decisive->t - start, decisive->updated, decisive->detail);
}

}  // namespace

std::vector<LossExplanation> explain_losses(const Truth& truth, const Evaluation& evaluation,
                                            std::span<const AlertSpan> alerts, const PipelineConfig& config,
                                            std::span<const TrackReport> records, std::span<const std::size_t> losses,
                                            double late_s) {
  PairWatch watch;
  const double lookahead = config.minima.lookahead_s;
  for (const std::size_t k : losses) {
    const LossEvent& loss = truth.loss_events()[k];
    const TruthTrack& a = truth.track(loss.track_a);
    const TruthTrack& b = truth.track(loss.track_b);
    watch.watch(a.source, a.id, b.source, b.id, static_cast<double>(loss.start_s) - lookahead - kLeadIn_s,
                cutoff(truth, loss, evaluation.losses[k], alerts));
  }

  PipelineConfig watched = config;
  watched.batch_records = 1;
  Pipeline pipeline(watched);
  pipeline.set_pair_observer(&watch);
  for (const TrackReport& r : records) pipeline.process(r);
  pipeline.end_of_input();

  std::vector<LossExplanation> out;
  for (std::size_t i = 0; i < losses.size(); ++i) {
    const std::size_t k = losses[i];
    const LossEvent& loss = truth.loss_events()[k];
    const ScoredLoss& scored = evaluation.losses[k];
    LossExplanation e;
    e.loss = k;
    e.outcome = scored.outcome == LossOutcome::Missed       ? ExplainedOutcome::Missed
                : scored.outcome == LossOutcome::Unwarnable ? ExplainedOutcome::Unwarnable
                                                            : ExplainedOutcome::Late;
    // Notes at the cutoff itself (an alert's opening) did not delay the alert.
    std::vector<PairNote> notes;
    const double end = watch.pair(i).to_t;
    for (const PairNote& n : watch.pair(i).notes)
      if (n.t < end) notes.push_back(n);
    e.spans = spans_of(notes);
    decide(e, notes, loss, end, late_s);
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace kew::replay
