#pragma once
// Why a loss was missed or warned late (design §2.6, §4.10; kew-eval --explain): the
// pipeline is run again over the recording with the pairs of those losses watched
// (PairWatch), and what it noted at every update of either aircraft is condensed
// into the stage that kept kew from alerting earlier, with its evidence.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "kew/pipeline/pipeline.hpp"
#include "kew/replay/evaluation.hpp"
#include "kew/replay/pair_watch.hpp"
#include "kew/replay/truth.hpp"

namespace kew::replay {

namespace explanation_rules {
/// A loss detected less than this ahead is late and explained (s): the default of the
/// `late_s` arguments below.
inline constexpr double kLateWarning_s = 20.0;
/// The watch starts this long before the look-ahead could first have seen the loss (s).
inline constexpr double kLeadIn_s = 30.0;
}  // namespace explanation_rules

/// Why a loss is explained.
enum class ExplainedOutcome : std::uint8_t { Missed, Late, Unwarnable };
inline constexpr util::NameTable<ExplainedOutcome, 3> kExplainedOutcomeNames({{
    {ExplainedOutcome::Missed, "missed"},
    {ExplainedOutcome::Late, "late"},
    {ExplainedOutcome::Unwarnable, "unwarnable"},
}});

/// A run of consecutive notes of one stage.
struct StageSpan {
  PairStage stage = PairStage::NoTrack;
  double first_t = 0.0, last_t = 0.0;  ///< UTC s
  std::size_t notes = 0;
  PairNote first, last;
};

struct LossExplanation {
  std::size_t loss = 0;  ///< index into Truth::loss_events()
  ExplainedOutcome outcome = ExplainedOutcome::Missed;
  /// The stage that kept kew from alerting earlier (design §4.10 gives the rule).
  PairStage stage = PairStage::NoTrack;
  /// One sentence with the evidence: the decisive note's figures.
  std::string reason;
  /// The pair's notes from the watch's start to the alert's opening (late) or the loss's
  /// end (missed), as runs of one stage.
  std::vector<StageSpan> spans;
};

/// The losses kew-eval --explain explains: every loss without an alert `late_s` (s, ≥ 0)
/// ahead (missed, detected late, or unwarnable and not warned of in time), in the order
/// of the truth.
std::vector<std::size_t> losses_to_explain(const Evaluation& evaluation,
                                           double late_s = explanation_rules::kLateWarning_s);

/// Runs a pipeline with `config` (batch_records forced to 1: PairWatch) over `records`
/// in their order, watching the pairs of `losses`, and explains each. `alerts` and
/// `evaluation` are the scored run of the same configuration over the same records.
std::vector<LossExplanation> explain_losses(const Truth& truth, const Evaluation& evaluation,
                                            std::span<const AlertSpan> alerts, const PipelineConfig& config,
                                            std::span<const TrackReport> records, std::span<const std::size_t> losses,
                                            double late_s = explanation_rules::kLateWarning_s);

}  // namespace kew::replay
