#pragma once
// Scoring one run's area proximity warnings (APW, design §4.11) against the AreaTruth of
// its recording, with the classes and windows of pair alerts (evaluation.hpp; replay/README.md
// "kew-eval"), as docs/alert-quality.md "Area proximity warnings" lists them.
//
// Each APW alert is, in this order:
//   1. ineligible (one_aircraft): a followed volume's alert about the followed aircraft
//      itself (another of its tracks);
//   2. hit: the aircraft was inside the volume at a second of
//      [t_open − kHitBefore_s, t_open + the volume's lookahead_s + kHitAfter_s];
//   3. close call: it was close (within 1 NM of the area, inside the band) in that window;
//   4. ineligible: no sample of the aircraft (or of a followed volume's centre) within
//      kNearestSample_s of t_open, or a volume the truth does not know (no_truth); the
//      aircraft's nearest sample does not fly (not_airborne);
//   5. else nuisance.
// Each entry is unwarnable when it began within `confirm` update periods of becoming
// eligible (AreaEntry::eligible_since_s), detected when an APW alert of that aircraft
// and volume opened at or before its start + kOpenTolerance_s and had not ended more than
// kEndedBefore_s before it (warning time = start − the earliest such opening), else missed.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "kew/replay/area_truth.hpp"
#include "kew/replay/evaluation.hpp"

namespace kew::replay {

struct ScoredAreaAlert {
  AlertClass cls = AlertClass::Nuisance;
  IneligibleReason reason = IneligibleReason::None;
  /// The alert's volume among the truth's, by name; empty when the truth has none of it.
  std::optional<std::uint32_t> volume;
  /// The volume's kind; for an unknown volume the alert's own volume_kind (else watch).
  volume::VolumeKind kind = volume::VolumeKind::Watch;
  /// Hits: the first inside second within the window (UTC s).
  std::optional<std::int64_t> entry_s;
};

/// An entry, scored as a loss is (eligible_for_s: since AreaEntry::eligible_since_s).
using ScoredAreaEntry = ScoredEvent;

/// The figures of one kind of volume.
struct AreaFigures : ScoreFigures {
  std::size_t volumes = 0;  ///< of this kind in the truth
  std::size_t entries = 0;
};

struct AreaEvaluation {
  std::vector<ScoredAreaAlert> alerts;   ///< parallel to the alerts scored
  std::vector<ScoredAreaEntry> entries;  ///< parallel to AreaTruth::entries()
  /// Every kind that has a volume in the truth or an alert, in kVolumeKindNames order.
  std::map<volume::VolumeKind, AreaFigures> by_kind;
};

/// The APW alerts (kind Apw) of `alerts`, in order; the others are pair alerts.
std::vector<AlertSpan> alerts_of_kind(std::span<const AlertSpan> alerts, AlertKind kind);

/// Scores `alerts` (APW alerts of one run over the truth's recording) against `areas`,
/// built on `truth`; `confirm` as in ScoringParameters. Deterministic.
AreaEvaluation evaluate_areas(const Truth& truth, const AreaTruth& areas, std::span<const AlertSpan> alerts,
                              int confirm);

}  // namespace kew::replay
