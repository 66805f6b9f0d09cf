#pragma once
// The alert stage (design §3, §4.5–4.7): the batch's steps in record order. It keeps its
// own view of each track as of the step it judges, adds the partners of open and pending
// alerts to the pairs the zones found, applies the eligibility rules, and runs the alert
// manager, whose events go to the sink; then the area proximity warning (AreaStage, design
// §4.11) judges the same track against the volumes, through the same manager.

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "batch.hpp"
#include "kew/alert/alert_manager.hpp"
#include "kew/eligibility/eligibility.hpp"
#include "kew/pipeline/instrumentation.hpp"
#include "kew/pipeline/pair_observer.hpp"
#include "kew/pipeline/pipeline_config.hpp"
#include "kew/util/checkpoint_io.hpp"
#include "kew/util/rejections.hpp"
#include "area_stage.hpp"
#include "pair_judge.hpp"
#include "zone_set.hpp"

namespace kew::pipeline {

class AlertStage {
 public:
  using AlertSink = std::function<void(const AlertEvent&)>;

  /// Every argument must outlive the stage; `tracks` is read only to find an observed
  /// pair's partner by name.
  AlertStage(const PipelineConfig& config, const PairJudge& judge, ZoneSet& zones,
             const PipelineInstrumentation& instruments, const track::TrackTable& tracks);

  /// Judges the batch's steps in order (the zones have run), delivering the events.
  void run(Batch& batch);

  void set_sink(AlertSink sink) { sink_ = std::move(sink); }
  void set_pair_observer(PairObserver* observer) { observer_ = observer; }

  const alert::AlertManager& alerts() const { return alerts_; }
  alert::AlertManager& alerts() { return alerts_; }
  const Rejections& suppressed() const { return suppressed_; }
  /// Each track as the alert stage last judged it, by slot.
  const std::vector<Snapshot>& view() const { return view_; }
  /// The stage's state (design §5.9) between batches; restore() into a fresh stage.
  void save(util::CheckpointWriter& out) const;
  void restore(util::CheckpointReader& in);

  std::uint64_t probes() const { return probes_; }
  std::uint64_t candidates() const { return candidates_; }

 private:
  /// A pair the alert manager must see: the other track, the zone that judges it
  /// (kNoZone: none holds both, too far apart to conflict) and, when a zone's probe or
  /// the brute force found it in conflict, that verdict.
  struct Evaluated {
    track::TrackSlot other;
    zone::ZoneKey zone;
    std::optional<PairKinematics> in_conflict;
  };

  void run_step(Batch& batch, const AlertStep& step);
  /// ProbeMode::Brute in worldwide mode: every track within reach on the sphere, each
  /// pair judged in its owner's plane; the conflicting ones into evaluated_.
  void brute_over_sphere(track::TrackSlot slot);
  /// Evaluates evaluated_ (sorted by slot) through the alert manager.
  void evaluate_pairs(track::TrackSlot slot);
  /// The rules' verdict on a pair in conflict (eligibility::Rules::verdict).
  eligibility::PairVerdict rule_verdict(const PairKinematics& pair) const;
  /// rule_verdict() counted in suppressed_: true when the pair is to be treated as clear.
  bool suppressed_by_rules(const PairKinematics& pair);
  /// The track's probe state in zone `key`, made from this stage's view of it as a zone
  /// makes a member's.
  zone::ProbeState state_in(zone::ZoneKey key, track::TrackSlot slot);
  void fill_event(AlertEvent& event, const geo::Projection& plane, const PairKinematics& pair,
                  const probe::ConflictGeometry& g, bool along_turn) const;
  /// served_longitudes: the event's pair is this pipeline's to report.
  bool serves(const AlertEvent& event) const;
  void deliver();
  /// Reports where every watched pair of the updated track stands (PairObserver).
  void observe_watched_pairs(track::TrackSlot slot);
  /// Where the pair of `slot` and `partner` stands after the update of `slot` (design §4.10).
  PairObservation observe_pair(track::TrackSlot slot, alert::PartyName partner);
  /// The limit of design §4.5 that track `t` is beyond by exclusion `why`.
  ExclusionLimit exclusion_limit(eligibility::Exclusion why, const track::Track& t) const;

  const PipelineConfig& config_;
  const PairJudge& judge_;
  ZoneSet& zones_;
  const PipelineInstrumentation& instruments_;
  const track::TrackTable& tracks_;
  std::vector<Snapshot> view_;  // by slot: each track as of the step being judged
  double judged_at_ = 0.0;      // the clock of that step
  alert::AlertManager alerts_;
  eligibility::Rules rules_;
  AreaStage areas_;
  Rejections suppressed_;
  std::vector<Evaluated> evaluated_;  // in slot order once sorted
  std::vector<track::TrackSlot> partners_scratch_;
  double brute_reach_m_ = 0.0;  // worldwide ProbeMode::Brute: pairs within this (m)
  std::vector<AlertEvent> pending_events_;
  AlertSink sink_;
  PairObserver* observer_ = nullptr;
  std::uint64_t probes_ = 0, candidates_ = 0;
};

}  // namespace kew::pipeline
