#pragma once
// The track stage (design §3, §4.1–4.3): records in order. It owns the track table, the
// clock and the time guard, the run's reference and young-run restarts; it tells the
// zones where each track is and queues the batch's steps for the alert stage.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "batch.hpp"
#include "kew/pipeline/pair_observer.hpp"
#include "kew/pipeline/pipeline_config.hpp"
#include "kew/pipeline/pipeline_statistics.hpp"
#include "kew/pipeline/record_outcome.hpp"
#include "kew/region/region_map.hpp"
#include "kew/track/time_guard.hpp"
#include "kew/track/track_table.hpp"
#include "kew/util/checkpoint_io.hpp"
#include "zone_set.hpp"

namespace kew::pipeline {

class TrackStage {
 public:
  /// Every argument must outlive the stage.
  TrackStage(const PipelineConfig& config, ZoneSet& zones, Batch& batch, const region::RegionMap& regions);

  /// The refusal of a record on its own or by the time ceiling, counted; None when the
  /// track stage is to take it (process()).
  track::Refusal screen(const TrackReport& report);
  /// Takes a record screen() let through: the time guard, then the track table.
  RecordOutcome process(const TrackReport& report);

  /// A young run (fewer than kYoungRun records accepted) restarts from the records it
  /// refused when this many in a row were too late or outside coverage: its first record
  /// set the clock or the projection for a feed that is elsewhere (design §4.1–4.2).
  static constexpr std::size_t kYoungRun = 5;
  bool young_run_stuck() const { return young_refused_.size() >= kYoungRun; }
  /// The young run's refused records, taken for a restart (drop_all() and a batch run
  /// come next, then restart()).
  std::vector<TrackReport> take_young_refused();
  /// Starts the run again without its clock (and its reference, unless configured):
  /// returns the records to process again, the young run's refused ones then those the
  /// time guard held.
  std::vector<TrackReport> restart(std::vector<TrackReport> refused);

  /// The input ended: records held ahead of the clock are applied.
  void end_of_input();
  /// Moves the clock towards t without a record (design §4.1); false before any record.
  bool advance_to(double t);
  /// Drops every track at the clock (their alerts end when the batch runs).
  void drop_all();

  void set_time_ceiling(double utc_s) { time_ceiling_ = utc_s; }
  void set_pair_observer(PairObserver* observer) { observer_ = observer; }

  /// Whether save() may be called: no record held ahead of the clock or refused by a young
  /// run (they are records, not state, and are not checkpointed).
  bool checkpointable() const { return time_guard_.held() == 0 && young_refused_.empty(); }
  /// No record taken yet.
  bool fresh() const { return !started_ && stats_.records == 0; }
  /// The stage's state (design §5.9), checkpointable() required; restore() into a fresh
  /// stage of the same configuration, which also sets the zones' epoch and single plane.
  void save(util::CheckpointWriter& out) const;
  void restore(util::CheckpointReader& in);

  double now() const { return clock_; }
  const track::TrackTable& tracks() const { return tracks_; }
  track::TrackTable& tracks() { return tracks_; }
  std::size_t live_tracks() const { return live_tracks_; }
  /// The record counters of PipelineStatistics (the rest is the other stages').
  const PipelineStatistics& statistics() const { return stats_; }

 private:
  /// process() for a record the time guard lets through.
  RecordOutcome apply_record(const TrackReport& report);
  /// Applies the records the time guard released into guard_scratch_, in order; the
  /// outcome of the one equal to `record`, if any.
  std::optional<RecordOutcome> apply_released(const TrackReport* record = nullptr);
  void refuse_future(const TrackReport& r);
  void move_clock(double t);
  /// Takes the track out of the zones and ends its alerts (the table keeps it).
  void drop_track(track::TrackSlot slot);
  /// Drops the track of `report`'s id when it carries another 24-bit address;
  /// `projected`: the record in single mode's plane, if it is one.
  void restart_if_other_aircraft(const TrackReport& report, const track::ProjectedPosition* projected);
  /// Drops a track its source ended (TrackReport::track_end).
  void end_track(track::TrackSlot slot);
  void leave_engine(track::TrackSlot slot);
  /// Places an accepted track in the zones and queues its step.
  void apply(track::TrackSlot slot);
  /// A worldwide run's explicit coverage limit refuses the report.
  bool outside_limit(const TrackReport& report) const;

  const PipelineConfig& config_;
  ZoneSet& zones_;
  Batch& batch_;
  const region::RegionMap& regions_;
  track::TrackTable tracks_;
  track::TimeGuard time_guard_;
  std::vector<TrackReport> guard_scratch_;
  std::vector<TrackReport> young_refused_;
  bool late_since_accepted_ = false;  // a record was refused too_late since the last accepted
  double newest_late_t_ = 0.0;        // the newest such record's time
  std::uint64_t accepted_in_run_ = 0;
  double time_ceiling_ = std::numeric_limits<double>::infinity();
  std::optional<geo::GeodeticPosition> coverage_centre_;  // of the reference or first record
  std::size_t live_tracks_ = 0;
  PairObserver* observer_ = nullptr;
  double epoch_ = 0.0;  // engine time = data time − epoch (design §4.1: local time frames)
  bool started_ = false;
  double clock_ = 0.0;
  PipelineStatistics stats_;
};

}  // namespace kew::pipeline
