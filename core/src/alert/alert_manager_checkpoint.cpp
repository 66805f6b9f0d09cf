// AlertManager's state in a checkpoint (design §5.9): every pair being judged, active or
// counting towards confirmation, with what decides its next event, the partner lists in
// their order, and the numbering. Pairs are written in key order, so that one state
// always gives the same bytes. One template of field() calls writes and reads each part.
#include <algorithm>
#include <type_traits>

#include "kew/alert/alert_manager.hpp"

namespace kew::alert {

namespace {

constexpr std::uint32_t kVersion = 2;  // 2: areas (Apw alerts)

template <class Io, class Party>
void party_fields(Io& io, Party& p) {
  io.field(p.lat_deg);
  io.field(p.lon_deg);
  io.field(p.alt_ft);
  io.field(p.gs_kt);
  io.field(p.trk_deg);
  io.field(p.vr_fpm);
  io.field(p.callsign);
  io.field(p.track_number);
}

// The pair's slots are its key's; the rest of its state.
template <class Io, class State>
void pair_fields(Io& io, State& s) {
  io.field(s.conflicts_in_row);
  io.field(s.clears_in_row);
  io.field(s.counted_t);
  io.field(s.active);
  io.field(s.opened_seq);
  auto& e = s.last;
  io.field(e.id_hash);
  io.field(e.seq);
  io.field(e.t);
  io.field(e.opened_t);
  io.field(e.t_los_s);
  io.field(e.t_cpa_s);
  io.field(e.cpa_h_m);
  io.field(e.cpa_v_ft);
  io.field(e.sep_h_m);
  io.field(e.sep_v_ft);
  party_fields(io, e.lo);
  party_fields(io, e.hi);
  io.field(e.number);
  io.field(e.state, AlertState::End);
  io.field(e.severity, Severity::Loss);
  io.field(e.hypothesis, Hypothesis::Proximity);
  io.field(e.region);
  io.field(e.volume);
  io.field(e.volume_kind);
  io.field(e.acknowledged);
  io.field(e.lo_is_a);
  io.field(s.decided.t_los_s);
  io.field(s.decided.cpa_h_m);
  io.field(s.decided.cpa_v_ft);
}

template <class Io, class Counters>
void numbering_fields(Io& io, std::uint64_t& seq, std::uint16_t& next_number, Counters& counters) {
  io.field(seq);
  io.field(next_number);
  io.field(counters.opened);
  io.field(counters.updated);
  io.field(counters.ended);
}

}  // namespace

void AlertManager::save(util::CheckpointWriter& out) const {
  out.section("alert_manager", kVersion);
  std::uint64_t seq = seq_;
  std::uint16_t next_number = next_number_;
  Counters counters = counters_;
  numbering_fields(out, seq, next_number, counters);

  std::vector<std::uint64_t> keys;
  keys.reserve(pairs_.size());
  for (const auto& [key, s] : pairs_) keys.push_back(key);
  std::sort(keys.begin(), keys.end());
  out.u64(keys.size());
  for (const std::uint64_t key : keys) {
    out.u64(key);
    pair_fields(out, pairs_.at(key));
  }

  std::vector<Slot> slots;
  slots.reserve(partners_.size());
  for (const auto& [slot, others] : partners_) slots.push_back(slot);
  std::sort(slots.begin(), slots.end());
  out.u64(slots.size());
  for (const Slot slot : slots) {
    const std::vector<Slot>& others = partners_.at(slot);
    out.u32(slot);
    out.u64(others.size());
    for (const Slot other : others) out.u32(other);
  }

  slots.clear();
  for (const auto& [slot, volumes] : volumes_) slots.push_back(slot);
  std::sort(slots.begin(), slots.end());
  out.u64(slots.size());
  for (const Slot slot : slots) {
    const std::vector<std::uint32_t>& volumes = volumes_.at(slot);
    out.u32(slot);
    out.u64(volumes.size());
    for (const std::uint32_t volume : volumes) out.u32(volume);
  }
}

void AlertManager::restore(util::CheckpointReader& in) {
  const auto empty = [this] {
    pairs_.clear();
    partners_.clear();
    volumes_.clear();
    seq_ = 0;
    next_number_ = 1;
    active_ = 0;
    counters_ = {};
  };
  empty();
  try {
    in.section("alert_manager", kVersion);
    numbering_fields(in, seq_, next_number_, counters_);
    const std::uint64_t pairs = in.u64();
    for (std::uint64_t i = 0; i < pairs; ++i) {
      const std::size_t pair_at = in.offset();
      const std::uint64_t key = in.u64();
      PairState s = state_of_key(key);
      if (!s.area && s.lo >= s.hi) in.fail(pair_at, "a pair whose slots are not in order");
      pair_fields(in, s);
      if (s.active) ++active_;
      if (!pairs_.emplace(key, std::move(s)).second) in.fail(pair_at, "a pair written twice");
    }
    const std::uint64_t slots = in.u64();
    for (std::uint64_t i = 0; i < slots; ++i) {
      const Slot slot = in.u32();
      const std::uint64_t count = in.u64();
      std::vector<Slot>& others = partners_[slot];
      for (std::uint64_t j = 0; j < count; ++j) others.push_back(in.u32());
    }
    const std::uint64_t tracks = in.u64();
    for (std::uint64_t i = 0; i < tracks; ++i) {
      const Slot slot = in.u32();
      const std::uint64_t count = in.u64();
      std::vector<std::uint32_t>& volumes = volumes_[slot];
      for (std::uint64_t j = 0; j < count; ++j) volumes.push_back(in.u32());
    }
  } catch (const util::CheckpointError&) {
    empty();
    throw;
  }
}

}  // namespace kew::alert
