#pragma once
// Scoring one run's alerts against the truth of its recording (design §2.6; rules in
// replay/README.md, "kew-eval"): each alert is a hit, a close call, a nuisance or
// ineligible, each loss event detected, missed or unwarnable, with warning times.
//
// The alerts come as the alert stream tells them (kew::AlertEvent: New, Update, End),
// from a Pipeline's sink or read back from an alert log, so that an older build's
// alerts are scored by the same code. Only two figures of the configuration under test
// enter: its look-ahead T (the window in which an alert may be proved right) and its
// `confirm` count (how soon a new track can be warned of at all).

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kew/alert/alert_event.hpp"
#include "kew/replay/truth.hpp"
#include "kew/util/name_table.hpp"

namespace kew::replay {

/// The scoring's fixed windows (s).
namespace scoring_rules {
/// A hit's loss may start this long before the alert opened ...
inline constexpr double kHitBefore_s = 10.0;
/// ... or up to T plus this after it.
inline constexpr double kHitAfter_s = 30.0;
/// Eligibility at opening is read from the sample nearest the opening within this.
inline constexpr double kNearestSample_s = 10.0;
/// An alert opened up to this after the loss started still detects it (1 s sampling).
inline constexpr double kOpenTolerance_s = 1.0;
/// An alert that ended at most this long before the loss started still detects it.
inline constexpr double kEndedBefore_s = 30.0;
}  // namespace scoring_rules

/// One alert from its New event to its End, or to the end of the run.
struct AlertSpan {
  std::string id;            ///< the stream's alert id
  AlertKind kind = AlertKind::Stca;        ///< a pair's alert, or an area proximity warning
  std::string volume, volume_kind;         ///< Apw: the volume's name and kind, as in AlertEvent
  std::string a_source, a_id, a_callsign;  ///< party a as in AlertEvent::a
  std::string b_source, b_id, b_callsign;
  double opened_t = 0.0;     ///< UTC s
  /// UTC s of the End event; empty while the alert was still active at the end of the run.
  std::optional<double> ended_t;
  AlertEndReason end_reason = AlertEndReason::None;
  Severity max_severity = Severity::None;  ///< highest severity of its events
  std::uint64_t events = 0;  ///< events seen (New, Updates, End)
};

/// Groups an event stream into alerts. Events of one alert share its id; an Update or
/// End whose New was never seen (a log that starts mid-alert) opens the alert at its
/// `opened_t`. An event after its alert's End starts a new alert.
class AlertCollector {
 public:
  void add(const AlertEvent& event);
  /// The alerts in order of their first event.
  const std::vector<AlertSpan>& alerts() const { return alerts_; }

 private:
  std::vector<AlertSpan> alerts_;
  std::map<std::string, std::size_t, std::less<>> open_;  // id → index of an alert not ended
};

/// What the configuration under test contributes to the scoring.
struct ScoringParameters {
  double lookahead_s = 120.0;  ///< T: PipelineConfig::minima.lookahead_s, s ≥ 0
  int confirm = 2;             ///< AlertConfig::confirm, ≥ 1
};

enum class AlertClass : std::uint8_t { Hit, CloseCall, Nuisance, Ineligible };
inline constexpr util::NameTable<AlertClass, 4> kAlertClassNames({{
    {AlertClass::Hit, "hit"},
    {AlertClass::CloseCall, "close_call"},
    {AlertClass::Nuisance, "nuisance"},
    {AlertClass::Ineligible, "ineligible"},
}});

/// Why an alert is ineligible.
enum class IneligibleReason : std::uint8_t {
  None,         ///< not ineligible
  OneAircraft,  ///< both parties are one aircraft
  NotAirborne,  ///< a party was not airborne at the opening
  NoTruth,      ///< a party has no sample within kNearestSample_s of the opening
};
inline constexpr util::NameTable<IneligibleReason, 4> kIneligibleReasonNames({{
    {IneligibleReason::None, ""},
    {IneligibleReason::OneAircraft, "one_aircraft"},
    {IneligibleReason::NotAirborne, "not_airborne"},
    {IneligibleReason::NoTruth, "no_truth"},
}});

enum class LossOutcome : std::uint8_t { Detected, Missed, Unwarnable };
inline constexpr util::NameTable<LossOutcome, 3> kLossOutcomeNames({{
    {LossOutcome::Detected, "detected"},
    {LossOutcome::Missed, "missed"},
    {LossOutcome::Unwarnable, "unwarnable"},
}});

struct ScoredAlert {
  AlertClass cls = AlertClass::Nuisance;
  IneligibleReason reason = IneligibleReason::None;
  /// Hits: the first loss second of the pair within the window (UTC s).
  std::optional<std::int64_t> loss_s;
};

/// An event of the truth that alerts were to warn of: a loss of separation of a pair, or
/// an aircraft's entry into a volume (area_evaluation.hpp), scored alike.
struct ScoredEvent {
  LossOutcome outcome = LossOutcome::Missed;
  /// Index into the alerts of the earliest alert that detects the event (also given for
  /// an unwarnable event that an alert covered).
  std::optional<std::size_t> alert;
  /// Event start − that alert's opening (s; ≥ −kOpenTolerance_s).
  std::optional<double> warning_s;
  /// Event start − its becoming eligible (s, ≥ 0): for a loss, the later of its two
  /// tracks'.
  std::int64_t eligible_for_s = 0;
};
using ScoredLoss = ScoredEvent;

/// Nearest-rank percentiles of the warning times of detected losses (s).
struct WarningTimes {
  double min = 0.0, p10 = 0.0, p50 = 0.0, p90 = 0.0, max = 0.0;
};

/// The figures of scored alerts and of the events they were to warn of, pair alerts
/// (EvaluationFigures) and area proximity warnings (AreaFigures) alike.
struct ScoreFigures {
  std::size_t alerts = 0;
  std::size_t hits = 0, close_calls = 0, nuisances = 0, ineligible = 0;
  std::size_t ineligible_one_aircraft = 0, ineligible_not_airborne = 0, ineligible_no_truth = 0;
  /// (nuisances + ineligible) / alerts, in [0, 1]; empty (n/a) without alerts.
  std::optional<double> undesirable_share;
  std::size_t detected = 0, missed = 0, unwarnable = 0;
  /// Empty (n/a) when no event was detected.
  std::optional<WarningTimes> warning;
};

struct EvaluationFigures : ScoreFigures {
  double flight_hours = 0.0;
  /// Empty (n/a) without flight hours.
  std::optional<double> alerts_per_100_flight_hours;
  std::size_t loss_events = 0;
};

struct Evaluation {
  std::vector<ScoredAlert> alerts;  ///< parallel to the alerts scored
  std::vector<ScoredLoss> losses;   ///< parallel to Truth::loss_events()
  EvaluationFigures figures;
};

/// Scores `alerts` (the pair alerts of AlertCollector::alerts() of one run over the
/// truth's recording: area proximity warnings are scored by evaluate_areas,
/// area_evaluation.hpp) against `truth`. An alert whose parties are not tracks of the truth is ineligible
/// (no_truth). Deterministic: the result depends only on the arguments' content.
Evaluation evaluate(const Truth& truth, std::span<const AlertSpan> alerts, const ScoringParameters& parameters);

/// Nearest-rank percentile (p in [0, 100]) of `sorted` (ascending, non-empty): the
/// smallest value with at least p % of the values at or below it; p = 0 gives the minimum.
double nearest_rank_percentile(std::span<const double> sorted, double p);

/// The minimum, nearest-rank 10th, 50th and 90th percentiles and maximum of `warnings`
/// (s, any order); empty without any.
std::optional<WarningTimes> warning_times(std::vector<double> warnings);

}  // namespace kew::replay
