#pragma once
// The heart of kew (design §3): TrackReports in, alert events out. A facade over three
// stages, each the one owner of its state (core/src/pipeline):
//  1. the track stage (TrackStage), in record order: track table (order, plausibility),
//     clock and time guard, projection into the record's home zone, and the work each
//     zone has to do (place, remove, probe, renumber);
//  2. the zones (ZoneSet, ZoneProbe), each on its own (in parallel across zones, design
//     §3.3): kinetic engine, candidate search and the one conflict test of the pairs the
//     zone owns, whose verdicts go on to
//  3. the alert stage (AlertStage), in record order: partners, eligibility rules, alert
//     manager, sink.
// Deterministic: the same records in the same order give the same events, whatever the
// number of threads or the size of a batch. Used by kew-replay and kewd alike.

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "kew/alert/alert_manager.hpp"
#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/pipeline/pipeline_config.hpp"
#include "kew/pipeline/pipeline_statistics.hpp"
#include "kew/pipeline/record_outcome.hpp"
#include "kew/track/track_table.hpp"
#include "kew/util/rejections.hpp"
#include "kew/zone/zone.hpp"
#include "kew/zone/zone_tiling.hpp"

namespace kew {

namespace util {
class WorkerPool;
}
namespace pipeline {
class PairJudge;
class ZoneSet;
class TrackStage;
class AlertStage;
struct Batch;
}  // namespace pipeline
struct PipelineInstrumentation;  // kew/pipeline/instrumentation.hpp
class PairObserver;              // kew/pipeline/pair_observer.hpp
struct PhaseTimes;

class Pipeline {
 public:
  using AlertSink = std::function<void(const AlertEvent&)>;

  explicit Pipeline(const PipelineConfig& config = {});
  ~Pipeline();
  // The stages hold references to one another and to the configuration.
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  /// Receives every alert event, in sequence order, synchronously.
  void set_alert_sink(AlertSink sink);

  /// Benchmarks' and tests' instruments (kew/pipeline/instrumentation.hpp): phase
  /// timing, the search disk, the conflict tap. None of them changes an alert.
  void instrument(const PipelineInstrumentation& instruments);
  /// Zero unless instrumented with time_phases.
  const PhaseTimes& phase_times() const;

  /// Reports to `observer` the records of the tracks it watches and where each pair it
  /// watches stands at every update of either of its tracks (design §4.10); null stops.
  /// The observer must outlive its use. Requires batch_records = 1 (the alert stage then
  /// judges each record as the track stage takes it): throws std::invalid_argument
  /// otherwise. Changes no alert.
  void set_pair_observer(PairObserver* observer);

  /// Processes one record (any data time; see TrackTableConfig for what is refused) and
  /// says what became of it. A record too far ahead of the clock is held, not applied
  /// (track::TimeGuard): it is applied later, in order, when enough records confirm the
  /// jump, or refused.
  RecordOutcome process(const TrackReport& report);

  /// The latest data time a record may carry (UTC s): a later one is refused at once
  /// ("future_time"), held by nothing. kewd sets it to the wall clock plus
  /// `[service] max_future_s` before each record; offline tools leave it unbounded.
  void set_time_ceiling(double utc_s);

  /// The input ended: records still held ahead of the clock, which nothing contradicted,
  /// are applied.
  void end_of_input();

  /// Runs the zones and the alert stage over the records taken so far, delivering their
  /// events; the next prompt_records records are then judged one by one. Readers of the
  /// pipeline's state (tracks, alerts, statistics) call it first when batch_records > 1.
  void flush();
  /// Records taken that wait for their batch to run (none: every event is delivered).
  bool batch_waiting() const;

  /// Moves the clock to t (UTC s) without a record — live mode's periodic tick: drops
  /// tracks that timed out and executes kinetic events up to t. Ignored if t ≤ now().
  /// While records arrive too late (none accepted since), the clock stops within
  /// max_lateness_s of the newest of them, so a feed whose delay grew can catch up.
  void advance_to(double t);

  /// Ends every alert and drops every track at the current time (end of a replay, or a
  /// daemon shutting down), emitting the End events.
  void drop_all();

  /// The computation's whole state after a flush() (design §5.9, a hot-standby pair's
  /// checkpoint): bytes that restore() turns into a pipeline that continues this one
  /// event for event (ids, seq, numbers, severities, figures) and record for record. The
  /// kinetic engines are not in it: they are made again from the tracks, and only their
  /// counters differ. Nullopt while the track stage holds records it has not decided yet
  /// (ahead of the clock in the time guard, or a young run's refused ones): a few records
  /// later it can.
  std::optional<std::string> checkpoint();
  /// Takes the state a pipeline of the same configuration wrote with checkpoint(). This
  /// pipeline must be fresh (no record processed); the sink, observer and instruments
  /// stay. Throws util::CheckpointError (kew/util/checkpoint_io.hpp) when the bytes cannot
  /// be read or were written in another zone mode: the pipeline is then to be discarded.
  void restore(std::string_view checkpoint);

  /// Exact audit of every zone's triangulation at now(), repairing what it finds; the
  /// zones' findings summed.
  kinetic::KineticAudit audit();
  /// Every zone's kinetic engine is a valid Delaunay triangulation (tests).
  bool is_valid() const;

  /// The pipeline clock (UTC s); 0 before any record.
  double now() const;
  PipelineStatistics statistics() const;
  /// The kinetic counters of every zone, summed (zones that were retired included);
  /// queue_max is the largest of any zone.
  kinetic::KineticStatistics kinetic_statistics() const;
  const Rejections& rejections() const;
  Rejections& rejections();
  /// Optional fields dropped from records that passed the record-level checks (design
  /// §4.3), by reason.
  const Rejections& dropped_fields() const;
  Rejections& dropped_fields();
  /// Conflicting evaluations the rules of design §4.5 turned clear, by rule:
  /// "same_aircraft", "level_pair", "adjacent_level_off", "inhibited", or the exclusion of
  /// the first excluded party.
  const Rejections& suppressed() const;
  const track::TrackTable& tracks() const;
  /// Tracks in the kinetic engines (accepted with a velocity), each counted once.
  std::size_t live_tracks() const;
  const alert::AlertManager& alerts() const;
  alert::AlertManager& alerts();
  const PipelineConfig& config() const { return config_; }
  /// Single mode: the plane in use (empty until the first plausible record fixes the
  /// reference). Worldwide mode: always empty; each zone has its own.
  const std::optional<geo::Projection>& projection() const;

  /// Calls f for every zone that exists now, in key order.
  void for_each_zone(const std::function<void(const zone::Zone&)>& f) const;
  std::size_t zone_count() const;
  /// The zone whose plane holds the track's kinematics (its home), null when none.
  const zone::Zone* home_zone(track::TrackSlot slot) const;
  /// The worldwide tiling (empty in single mode).
  const std::optional<zone::ZoneTiling>& tiling() const;
  /// Worldwide mode's zone margin (m, design §4.9): half the largest distance between
  /// the last reports of two aircraft that can still come into conflict. 0 in single mode.
  double zone_margin_m() const;

 private:
  /// Restarts a young run whose records went elsewhere (TrackStage::kYoungRun).
  void restart_young_run();
  /// `refused`, process()'s outcome for `report`, to the observer if it watches the track.
  void observe_refusal(const TrackReport& report, const RecordOutcome& refused);
  /// The zones, then the alert stage, over the batch taken so far.
  void run_batch();

  PipelineConfig config_;
  std::unique_ptr<PipelineInstrumentation> instruments_;
  std::unique_ptr<PhaseTimes> phases_;
  std::unique_ptr<pipeline::PairJudge> judge_;
  std::unique_ptr<pipeline::Batch> batch_;
  std::unique_ptr<pipeline::ZoneSet> zones_;
  std::unique_ptr<pipeline::TrackStage> track_;
  std::unique_ptr<pipeline::AlertStage> alert_;
  std::unique_ptr<util::WorkerPool> pool_;
  std::size_t prompt_left_ = 0;  // records still to judge one by one (prompt_records)
  PairObserver* observer_ = nullptr;
};

}  // namespace kew
