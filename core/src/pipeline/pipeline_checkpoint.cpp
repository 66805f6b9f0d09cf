// The pipeline's checkpoint (design §5.9): the track stage's and the alert stage's state
// between batches, each stage writing its own part; the zones are not written but made
// again from the tracks in the engines. Every exact decision (which pairs conflict) comes
// from the tracks, not from an engine's history, so a restored pipeline continues the
// saved one event for event; only the engines' own counters start again.
#include <stdexcept>

#include "alert_stage.hpp"
#include "batch.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "track_stage.hpp"
#include "zone_set.hpp"

namespace kew {

namespace pipeline {

namespace {

constexpr std::uint32_t kPipelineVersion = 1;
constexpr std::uint32_t kTrackStageVersion = 1;
constexpr std::uint32_t kAlertStageVersion = 2;  // 2: the area stage

template <class Io, class S>
void statistics_fields(Io& io, S& s) {
  io.field(s.records);
  io.field(s.accepted);
  io.field(s.awaiting_velocity);
  io.field(s.tracks_dropped);
  io.field(s.tracks_ended);
  io.field(s.runs_restarted);
  io.field(s.tracks_restarted);
  io.field(s.probes);
  io.field(s.candidates);
  io.field(s.zones_created);
  io.field(s.zones_retired);
  io.field(s.last_data_time);
}

// The plane-free part of a snapshot (TrackStage::apply makes it).
template <class Io, class P>
void base_fields(Io& io, P& base) {
  probe::checkpoint_fields(io, base.kinematics);
  io.field(base.t);
  io.field(base.scale);
  io.field(base.level_off_until_t);
  io.field(base.lat_deg);
  io.field(base.lon_deg);
  io.field(base.slot);
}

}  // namespace

void TrackStage::save(util::CheckpointWriter& out) const {
  if (!checkpointable()) throw std::logic_error("a track stage holding records cannot be checkpointed");
  out.section("track_stage", kTrackStageVersion);
  tracks_.save(out);
  out.boolean(started_);
  out.f64(epoch_);
  out.f64(clock_);
  out.boolean(late_since_accepted_);
  out.f64(newest_late_t_);
  out.u64(accepted_in_run_);
  out.boolean(coverage_centre_.has_value());
  if (coverage_centre_) {
    out.f64(coverage_centre_->lat_deg);
    out.f64(coverage_centre_->lon_deg);
  }
  out.u64(live_tracks_);
  statistics_fields(out, stats_);
}

void TrackStage::restore(util::CheckpointReader& in) {
  in.section("track_stage", kTrackStageVersion);
  tracks_.restore(in);
  started_ = in.boolean();
  epoch_ = in.f64();
  clock_ = in.f64();
  late_since_accepted_ = in.boolean();
  newest_late_t_ = in.f64();
  accepted_in_run_ = in.u64();
  coverage_centre_.reset();
  if (in.boolean()) {
    const double lat = in.f64();
    coverage_centre_ = geo::GeodeticPosition{lat, in.f64()};
  }
  live_tracks_ = in.u64();
  statistics_fields(in, stats_);
  zones_.set_epoch(epoch_);
  // The one plane is the coverage centre's, opened by the run's first record.
  if (started_ && config_.zone_mode == ZoneMode::Single && coverage_centre_)
    zones_.open_single_plane(*coverage_centre_, config_.coverage_radius_m.value_or(PipelineConfig::kSingleCoverage_m),
                             clock_);
}

void AlertStage::save(util::CheckpointWriter& out) const {
  out.section("alert_stage", kAlertStageVersion);
  alerts_.save(out);
  suppressed_.save(out);
  out.u64(probes_);
  out.u64(candidates_);
  out.f64(judged_at_);
  areas_.save(out);
  out.u64(view_.size());
  for (const Snapshot& s : view_) {
    out.boolean(s.track.in_use);
    track::TrackTable::write_track(out, s.track);
    base_fields(out, s.base);
    out.u64(s.base.region);
  }
}

void AlertStage::restore(util::CheckpointReader& in) {
  in.section("alert_stage", kAlertStageVersion);
  alerts_.restore(in);
  suppressed_.restore(in);
  probes_ = in.u64();
  candidates_ = in.u64();
  judged_at_ = in.f64();
  areas_.restore(in);
  const std::uint64_t slots = in.u64();
  view_.clear();
  for (std::uint64_t i = 0; i < slots; ++i) {
    Snapshot& s = view_.emplace_back();
    s.track.in_use = in.boolean();
    track::TrackTable::read_track(in, s.track);
    base_fields(in, s.base);
    s.base.region = static_cast<std::size_t>(in.u64());
  }
}

void ZoneSet::refill(const std::vector<Snapshot>& snapshots, double clock, std::uint64_t zones_created,
                     std::uint64_t zones_retired) {
  std::vector<zone::ZoneKey> step_zones;
  for (std::uint32_t i = 0; i < snapshots.size(); ++i) {
    const Snapshot& s = snapshots[i];
    place(s.base.slot, i, s.track.lat_deg, s.track.lon_deg, clock, step_zones, /*probe=*/false);
  }
  PhaseTimes unused;
  run(snapshots, clock, nullptr, unused);
  end_batch();
  zones_created_ = zones_created;
  zones_retired_ = zones_retired;
}

}  // namespace pipeline

std::optional<std::string> Pipeline::checkpoint() {
  flush();
  if (!track_->checkpointable()) return std::nullopt;
  util::CheckpointWriter out;
  out.section("pipeline", pipeline::kPipelineVersion);
  out.u8(static_cast<std::uint8_t>(config_.zone_mode));
  track_->save(out);
  alert_->save(out);
  out.u64(zones_->zones_created());
  out.u64(zones_->zones_retired());
  return out.take();
}

void Pipeline::restore(std::string_view checkpoint) {
  if (!track_->fresh() || batch_waiting()) throw std::logic_error("a checkpoint is restored into a fresh pipeline");
  util::CheckpointReader in(checkpoint);
  in.section("pipeline", pipeline::kPipelineVersion);
  const std::size_t mode_at = in.offset();
  if (in.u8() != static_cast<std::uint8_t>(config_.zone_mode)) in.fail(mode_at, "a pipeline of another zone mode");
  track_->restore(in);
  alert_->restore(in);
  const std::uint64_t created = in.u64();
  const std::uint64_t retired = in.u64();
  if (!in.at_end()) in.fail(in.offset(), "bytes after the checkpoint's end");
  // The tracks in the engines, as the alert stage last judged them, make the zones again.
  std::vector<pipeline::Snapshot> engine_tracks;
  const track::TrackTable& table = track_->tracks();
  const std::vector<pipeline::Snapshot>& view = alert_->view();
  for (track::TrackSlot slot = 0; slot < table.slot_end(); ++slot) {
    if (!table[slot].in_use || !table[slot].in_engine) continue;
    if (slot >= view.size() || view[slot].base.slot != slot) in.fail(in.offset(), "a track in the engines never judged");
    engine_tracks.push_back(view[slot]);
  }
  zones_->refill(engine_tracks, track_->now(), created, retired);
  prompt_left_ = config_.prompt_records;
}

}  // namespace kew
