#pragma once
// Why a pair did or did not alert (design §4.10): the facts the pipeline reports to an
// observer about a few watched pairs of tracks. At every update of either track of a
// watched pair, the alert stage reports the first stage that kept the pair from alerting
// at that moment, with the figures it decided on; the track stage reports the watched
// tracks' records. Facts only: enums, names and numbers. Words are the observer's
// (kew-eval --explain: kew::replay::PairWatch).
//
// The pipeline reports only what the observer says it watches, from its own view of the
// tracks, and reads nothing back: an observer changes no alert, and none costs nothing.

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "kew/alert/alert_manager.hpp"
#include "kew/eligibility/eligibility.hpp"
#include "kew/pipeline/record_outcome.hpp"
#include "kew/track/track_report.hpp"
#include "kew/track/track_table.hpp"

namespace kew {

/// Where a pair stood at one update, in the order the pipeline decides: the first stage
/// that holds it back (or Alerting).
enum class PairStage : std::uint8_t {
  RecordRefused,     ///< a record of a party was refused (RecordOutcome::refusal)
  NoTrack,           ///< a party has no track: no record yet, or dropped (timeout, ended)
  AwaitingVelocity,  ///< a party is known but has no velocity yet (one record)
  NotCandidate,      ///< the pair is in conflict but the candidate search did not give it,
                     ///< or no zone holds both aircraft
  ProbeClear,        ///< the conflict test finds no conflict within the look-ahead
  SameAddress,       ///< one aircraft: both tracks carry one 24-bit address
  SameCode,          ///< one aircraft: one discrete code on coinciding tracks (design §4.5)
  LevelPair,         ///< two level aircraft at adjacent levels
  AdjacentLevelOff,  ///< a climb or descent presumed to level off beside a level aircraft
  Inhibited,         ///< a party in an inhibition volume
  Excluded,          ///< a party may not open an alert (the rule and its value)
  ConfirmPending,    ///< in conflict, fewer than `confirm` evaluations in a row yet
  Alerting,          ///< the pair's alert is open
};

/// What keeps a pair clear at the conflict test (PairStage::ProbeClear).
enum class ClearReason : std::uint8_t {
  NoHorizontalLoss,        ///< the horizontal distance stays above S_h within T
  BeyondVerticalLookahead, ///< the rates close below S_v less the tolerance only after T_v
  VerticallyApart,         ///< vertically apart where horizontally close
};

/// The conflict test's figures of a pair at the judgement, in the plane of the zone that
/// holds both tracks.
struct PairFigures {
  double sep_v_ft = 0.0;  ///< vertical distance now (ft)
  double cpa_h_m = 0.0;   ///< horizontal distance at the closest point of approach, on the ellipsoid (m)
  double t_cpa_s = 0.0;   ///< time from the judgement to that point (s)
  double cpa_v_ft = 0.0;  ///< vertical distance there (ft)
  double t_los_s = 0.0;   ///< time from the judgement to the loss of separation (s); in conflict only
};

/// The limit an excluded track is beyond (design §4.5), in the unit of the figure of the
/// track the exclusion reads.
struct ExclusionLimit {
  /// Slow: the lowest ground speed (kt); AltitudeBand: the band's bottom (ft);
  /// BelowLowerLimit: the lower limit at the track's position (ft); PositionStale: the
  /// oldest a last record may be (s); FirstRecords: the fewest records; else 0.
  double low = 0.0;
  double high = 0.0;  ///< AltitudeBand: the band's top (ft); else 0
  /// BelowLowerLimit: the aerodrome whose elevation sets the limit, if one does, and the
  /// height above it that the limit keeps (ft).
  const eligibility::Aerodrome* aerodrome = nullptr;
  double aerodrome_height_ft = 0.0;
};

/// Where a watched pair stood after an update of one of its tracks. Pointers and names
/// point into the pipeline and are valid during the call that reports it.
struct PairObservation {
  double t = 0.0;            ///< data time of the judgement (UTC s)
  alert::PartyName updated;  ///< the track whose update was judged
  alert::PartyName partner;  ///< the other track of the pair
  PairStage stage = PairStage::NoTrack;
  /// NoTrack: how long a silent track lives (s); a track also ends when its source ends it.
  double track_timeout_s = 0.0;
  /// The two tracks as the alert stage judged them, lower slot first (the conflict
  /// test's order); null while a party has no track with a velocity (NoTrack,
  /// AwaitingVelocity: the partner).
  const track::Track* p = nullptr;
  const track::Track* q = nullptr;
  double distance_m = 0.0;  ///< with p and q: their horizontal distance now, on the ellipsoid (m)
  /// With p and q, unless no zone holds both (NotCandidate): the conflict test's figures.
  /// A NotCandidate pair with figures is in conflict, and the candidate search did not
  /// give it.
  std::optional<PairFigures> figures;
  ClearReason clear = ClearReason::NoHorizontalLoss;  ///< ProbeClear
  double vertical_lookahead_s = 0.0;                  ///< with figures: the pair's T_v (s)
  int confirm = 0;  ///< with figures: evaluations in conflict in a row that open an alert
  /// SameAddress … Excluded: the rule of design §4.5 that holds the pair back.
  eligibility::PairVerdict verdict;
  const track::Track* excluded = nullptr;  ///< Excluded: the track that may not alert (p or q)
  ExclusionLimit limit;                    ///< Excluded: the limit it is beyond
};

/// Watches a few pairs of tracks through a pipeline (Pipeline::set_pair_observer). The
/// pipeline calls it synchronously, in record order, only about tracks it watches.
class PairObserver {
 public:
  virtual ~PairObserver() = default;

  /// Whether a watched pair has the track (source, id) as a party: the pipeline reports
  /// nothing about other tracks.
  virtual bool watches(std::string_view source, std::string_view id) const = 0;
  /// The tracks paired with (source, id) whose watch holds data time t (UTC s), each
  /// once: the alert stage judges each such pair after an update of (source, id). The
  /// names must stay valid until those pairs are reported.
  virtual std::vector<alert::PartyName> partners(std::string_view source, std::string_view id,
                                                 double t) const = 0;
  /// A record of a watched track: applied (Accepted, AwaitingVelocity), reported as the
  /// track stage applies it, before the alert stage judges it (records the time guard
  /// released and records a restarted run takes again included); or refused (Refused),
  /// reported when Pipeline::process() returns that outcome for it.
  virtual void record(const TrackReport& report, const RecordOutcome& outcome) = 0;
  /// Where a watched pair stands after an update of one of its tracks (alert stage).
  virtual void pair_judged(const PairObservation& observation) = 0;
};

}  // namespace kew
