// TrackTable's state in a checkpoint (design §5.9): every slot's track as admit() left
// it, the free slots in the order they are reused, the deadlines and the counters. The
// index of (source, id) is made again from the tracks in use. One template of field()
// calls writes and reads a track.
#include "kew/track/track_table.hpp"

namespace kew::track {

namespace {

constexpr std::uint32_t kVersion = 1;

// A field added to Track is to be added here and to test_track_checkpoint's contents().
static_assert(sizeof(Track) == 392, "Track changed: checkpoint its new fields (track_fields), then update this size");

template <class Io, class T>
void track_fields(Io& io, T& track) {
  io.field(track.source);
  io.field(track.id);
  io.field(track.callsign);
  io.field(track.mode3a);
  io.field(track.address);
  io.field(track.coasting);
  io.field(track.number);
  io.field(track.has_velocity);
  io.field(track.vertical_rate_known);
  io.field(track.vertical_rate_derived);
  io.field(track.altitude_step_ft);
  io.field(track.altitude_change_ft);
  io.field(track.altitude_moving_one_way);
  io.field(track.records);
  io.field(track.t);
  io.field(track.lat_deg);
  io.field(track.lon_deg);
  io.field(track.alt_ft);
  io.field(track.gs_kt);
  io.field(track.trk_deg);
  io.field(track.vr_fpm);
  io.field(track.plane_scale);
  auto& intent = track.intent;
  io.field(intent.sel_ft);
  io.field(intent.sel_src, SelectedAltitudeSource::Fms);
  io.field(intent.sel_t);
  io.field(intent.approach_sign);
  io.field(intent.busted);
  io.field(intent.band_entry_rate_fpm);
  io.field(track.level_off_ft);
  io.field(track.turn_rate_dps);
  io.field(track.turn_reference_t);
  io.field(track.turn_reference_trk_deg);
  io.field(track.has_turn_reference);
  probe::checkpoint_fields(io, track.kinematics);
  io.field(track.plane);
  io.field(track.in_engine);
}

}  // namespace

void TrackTable::write_track(util::CheckpointWriter& out, const Track& track) { track_fields(out, track); }
void TrackTable::read_track(util::CheckpointReader& in, Track& track) { track_fields(in, track); }

void TrackTable::save(util::CheckpointWriter& out) const {
  out.section("track_table", kVersion);
  out.u32(slot_end());
  for (TrackSlot slot = 0; slot < slot_end(); ++slot) {
    const Track& track = tracks_[slot];
    out.boolean(track.in_use);
    if (track.in_use) track_fields(out, track);
  }
  out.u64(free_slots_.size());
  for (const TrackSlot slot : free_slots_) out.u32(slot);
  out.u64(deadlines_.size());
  deadlines_.for_each([&](TrackSlot slot, double key) {
    out.u32(slot);
    out.f64(key);
  });
  out.u64(max_in_use_);
  out.u64(velocity_resets_);
  out.u64(velocities_derived_);
  rejections_.save(out);
  dropped_fields_.save(out);
}

void TrackTable::restore(util::CheckpointReader& in) {
  const auto empty = [this] {
    tracks_ = {};
    free_slots_.clear();
    index_ = {};
    deadlines_ = {};
    in_use_ = max_in_use_ = 0;
    velocity_resets_ = velocities_derived_ = 0;
  };
  empty();
  try {
    in.section("track_table", kVersion);
    const TrackSlot slots = in.u32();
    for (TrackSlot slot = 0; slot < slots; ++slot) {
      Track& track = tracks_.emplace_back();
      if (!in.boolean()) continue;
      const std::size_t track_at = in.offset();
      track_fields(in, track);
      track.in_use = true;
      if (find(track.source, track.id) != TrackIndex::kAbsent) in.fail(track_at, "a track written twice");
      index_.insert(TrackIndex::hash(track.source, track.id), slot);
      ++in_use_;
    }
    const std::uint64_t free = in.u64();
    for (std::uint64_t i = 0; i < free; ++i) {
      const std::size_t slot_at = in.offset();
      const TrackSlot slot = in.u32();
      if (slot >= slots || tracks_[slot].in_use) in.fail(slot_at, "a free slot that is not free");
      free_slots_.push_back(slot);
    }
    const std::uint64_t deadlines = in.u64();
    for (std::uint64_t i = 0; i < deadlines; ++i) {
      const std::size_t slot_at = in.offset();
      const TrackSlot slot = in.u32();
      if (slot >= slots || !tracks_[slot].in_use) in.fail(slot_at, "a deadline of a slot not in use");
      deadlines_.set(slot, in.f64());
    }
    max_in_use_ = in.u64();
    velocity_resets_ = in.u64();
    velocities_derived_ = in.u64();
    rejections_.restore(in);
    dropped_fields_.restore(in);
  } catch (const util::CheckpointError&) {
    empty();
    throw;
  }
}

}  // namespace kew::track
