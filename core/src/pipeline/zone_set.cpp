#include "zone_set.hpp"

#include <algorithm>

#include "kew/util/gentle_growth.hpp"
#include "kew/util/units.hpp"

namespace kew::pipeline {

namespace {
// The largest point scale of a zone's plane (design §4.9: below 1.02) with room to spare,
// and the zone margin's own slack (m).
constexpr double kScaleBound = 1.05;
constexpr double kMarginSlack_m = 1000.0;
// A batch with fewer zone operations than this runs on the calling thread alone.
constexpr std::size_t kParallelOps = 48;

std::optional<zone::ZoneTiling> make_tiling(const PipelineConfig& config, const PairJudge& judge) {
  if (config.zone_mode != ZoneMode::Worldwide) return std::nullopt;
  // Two aircraft whose last reports are D apart can come within S_h of each other
  // within T only if D ≤ S_h + (v_i + v_j)·(T + age), each report at most the track
  // timeout old and every speed at most max_ground_speed_kt (faster reports lose the
  // speed, faster derived ones reset the track, design §4.3). The midpoint of such a
  // pair is within D/2 of both, so a margin of D/2 holds both in the midpoint's zone.
  const double fastest_mps = config.tracks.max_ground_speed_kt * units::kMpsPerKnot;
  return zone::ZoneTiling(0.5 * judge.largest_horizontal_m() * kScaleBound +
                          fastest_mps * (judge.largest_lookahead_s() + config.tracks.track_timeout_s) +
                          kMarginSlack_m);
}
}  // namespace

ZoneSet::ZoneSet(const PipelineConfig& config, const PairJudge& judge, const PipelineInstrumentation& instruments)
    : config_(config),
      tiling_(make_tiling(config, judge)),
      probe_(config, judge, instruments, tiling_ ? &*tiling_ : nullptr) {
  if (!tiling_) {
    work_.resize(1);
    return;
  }
  work_.resize(zone::ZoneTiling::key_end());
  if (!config_.served_longitudes) return;
  // One core width beyond the band: an alert's pair moves far less while it lasts, so
  // the zones that judged it before its midpoint entered the band are worked too.
  const LongitudeBand band = *config_.served_longitudes;
  worked_zone_.assign(zone::ZoneTiling::key_end(), false);
  for (zone::ZoneKey key = 0; key < zone::ZoneTiling::key_end(); ++key) {
    if (!tiling_->valid(key)) continue;
    const zone::ZoneTiling::Core core = tiling_->core(key);
    const double width = core.east_deg - core.west_deg;
    bool worked = width >= 360.0;  // a cap
    for (const double shift : {-360.0, 0.0, 360.0})
      worked = worked || (core.west_deg - width + shift < band.east_deg && band.west_deg < core.east_deg + width + shift);
    worked_zone_[key] = worked;
  }
}

void ZoneSet::open_single_plane(const geo::GeodeticPosition& centre, double radius_m, double clock) {
  single_plane_.emplace(centre, radius_m);
  zone_at(0, clock);
}

const geo::Projection& ZoneSet::home_plane(zone::ZoneKey key, double clock) {
  if (worked_zone_.empty() || worked_zone_[key]) return zone_at(key, clock).projection();
  // A zone this pipeline does not work still gives its tracks their kinematics, on the
  // very plane its zone would have: a track entering the worked zones is the same track
  // as in a pipeline that works them all.
  return plane(key);
}

const geo::Projection& ZoneSet::plane(zone::ZoneKey key) {
  if (work_[key].zone) return work_[key].zone->projection();
  util::grow_to(spare_planes_, work_.size());
  std::optional<geo::Projection>& plane = spare_planes_[key];
  if (!plane) plane.emplace(tiling_->centre(key), tiling_->extent_m(key));
  return *plane;
}

zone::ZoneKey ZoneSet::owner_of(const track::Track& a, const track::Track& b) const {
  if (!tiling_) return 0;
  return tiling_->owner({a.lat_deg, a.lon_deg}, {b.lat_deg, b.lon_deg});
}

bool ZoneSet::holds_both(zone::ZoneKey key, const track::Track& a, const track::Track& b) {
  if (!tiling_) return true;
  for (const track::Track* t : {&a, &b}) {
    tiling_->zones_near({t->lat_deg, t->lon_deg}, scratch_);
    if (std::find(scratch_.begin(), scratch_.end(), key) == scratch_.end()) return false;
  }
  return true;
}

zone::Zone& ZoneSet::zone_at(zone::ZoneKey key, double clock) {
  ZoneWork& w = work_[key];
  if (!w.zone) {
    const double engine_now = clock - epoch_;
    if (tiling_) {
      w.zone = std::make_unique<zone::Zone>(key, tiling_->name(key),
                                            geo::Projection(tiling_->centre(key), tiling_->extent_m(key)),
                                            config_.kinetic, engine_now);
    } else {
      w.zone = std::make_unique<zone::Zone>(key, "single", *single_plane_, config_.kinetic, engine_now);
    }
    ++zone_count_;
    ++zones_created_;
    touch(key);  // retired at the end of the batch if nothing joins it
  }
  return *w.zone;
}

void ZoneSet::touch(zone::ZoneKey key) {
  ZoneWork& w = work_[key];
  if (w.touched) return;
  w.touched = true;
  touched_.push_back(key);
}

std::uint32_t ZoneSet::place(track::TrackSlot slot, std::uint32_t snapshot, double lat_deg, double lon_deg,
                             double t, std::vector<zone::ZoneKey>& step_zones, bool probe) {
  util::grow_to(members_, static_cast<std::size_t>(slot) + 1);
  std::vector<zone::ZoneKey>& members = members_[slot];
  // The zones that hold the track now (design §4.9): it leaves the others first.
  scratch_.clear();
  if (tiling_) tiling_->zones_near({lat_deg, lon_deg}, scratch_);
  else scratch_.push_back(0);
  if (!worked_zone_.empty()) std::erase_if(scratch_, [&](zone::ZoneKey key) { return !worked_zone_[key]; });
  for (const zone::ZoneKey key : members) {
    if (std::find(scratch_.begin(), scratch_.end(), key) != scratch_.end()) continue;
    ZoneWork& w = work_[key];
    w.ops.push_back({ZoneOp::Kind::Remove, slot, 0, t});
    --w.members;
    touch(key);
  }
  for (const zone::ZoneKey key : scratch_) {
    zone_at(key, t);
    ZoneWork& w = work_[key];
    if (std::find(members.begin(), members.end(), key) == members.end()) ++w.members;
    w.ops.push_back({ZoneOp::Kind::Place, slot, snapshot, t});
    if (probe) w.ops.push_back({ZoneOp::Kind::Probe, slot, snapshot, t});
    touch(key);
    step_zones.push_back(key);
  }
  members.assign(scratch_.begin(), scratch_.end());
  return static_cast<std::uint32_t>(scratch_.size());
}

void ZoneSet::remove(track::TrackSlot slot, double t) {
  if (slot >= members_.size()) return;
  for (const zone::ZoneKey key : members_[slot]) {
    ZoneWork& w = work_[key];
    w.ops.push_back({ZoneOp::Kind::Remove, slot, 0, t});
    --w.members;
    touch(key);
  }
  members_[slot].clear();
}

void ZoneSet::schedule_renumbering(double clock) {
  if (config_.renumber_every_s <= 0.0) return;
  for (std::size_t key = 0; key < work_.size(); ++key) {
    ZoneWork& w = work_[key];
    if (!w.zone || clock < w.next_renumber) continue;
    if (w.next_renumber > 0.0) {
      w.ops.push_back({ZoneOp::Kind::Renumber, track::kNoTrack, 0, clock});
      touch(static_cast<zone::ZoneKey>(key));
    }
    w.next_renumber = clock + config_.renumber_every_s;
  }
}

void ZoneSet::reset(bool keep_single_plane) {
  if (!keep_single_plane) single_plane_.reset();
  // The new run's zones start with its clock, and so do their counters and renumbering
  // schedules.
  for (ZoneWork& w : work_) w = ZoneWork{};
  zone_count_ = 0;
  retired_kinetic_ = {};
}

void ZoneSet::run(const std::vector<Snapshot>& snapshots, double clock, util::WorkerPool* pool, PhaseTimes& phases) {
  const auto run_one = [&](std::size_t i) { probe_.run(work_[touched_[i]], snapshots, epoch_, clock); };
  std::size_t ops = 0;
  for (const zone::ZoneKey key : touched_) ops += work_[key].ops.size();
  // Waking the workers costs more than a few operations take (a live feed's batch after
  // one read holds a handful of records): those run here.
  if (pool && ops >= kParallelOps) {
    // The zones with the most work first, so that the last ones to finish are small.
    std::stable_sort(touched_.begin(), touched_.end(), [&](zone::ZoneKey a, zone::ZoneKey b) {
      return work_[a].ops.size() > work_[b].ops.size();
    });
    pool->run(touched_.size(), run_one);
  } else {
    for (std::size_t i = 0; i < touched_.size(); ++i) run_one(i);
  }
  for (const zone::ZoneKey key : touched_) {
    PhaseTimes& p = work_[key].phases;
    phases.maintenance_s += p.maintenance_s;
    phases.search_s += p.search_s;
    phases.tests_s += p.tests_s;
    p = {};
  }
}

ZoneSet::Probed ZoneSet::next_probe(zone::ZoneKey key) {
  ZoneWork& w = work_[key];
  const ProbeResult& r = w.probes[w.cursor++];
  return {r.candidates, std::span<const FoundPair>(w.found).subspan(r.first, r.count)};
}

void ZoneSet::end_batch() {
  for (const zone::ZoneKey key : touched_) {
    ZoneWork& w = work_[key];
    w.touched = false;
    w.ops.clear();
    w.probes.clear();
    w.found.clear();
    w.cursor = 0;
    // The single zone stays: its engine's counters are the run's.
    if (w.zone && w.members == 0 && tiling_) {
      add_statistics(retired_kinetic_, w.zone->kinetic_statistics());
      w.zone.reset();
      w.next_renumber = 0.0;
      --zone_count_;
      ++zones_retired_;
    }
  }
  touched_.clear();
}

void ZoneSet::for_each_zone(const std::function<void(const zone::Zone&)>& f) const {
  for (const ZoneWork& w : work_)
    if (w.zone) f(*w.zone);
}

const zone::Zone* ZoneSet::home_zone(const track::Track& track) const {
  return track.in_use && track.plane < work_.size() ? work_[track.plane].zone.get() : nullptr;
}

kinetic::KineticStatistics ZoneSet::kinetic_statistics() const {
  kinetic::KineticStatistics total = retired_kinetic_;
  for (const ZoneWork& w : work_)
    if (w.zone) add_statistics(total, w.zone->kinetic_statistics());
  return total;
}

kinetic::KineticAudit ZoneSet::audit(double clock) {
  kinetic::KineticAudit total;
  for (ZoneWork& w : work_) {
    if (!w.zone) continue;
    w.zone->advance(clock - epoch_);
    const kinetic::KineticAudit a = w.zone->engine().audit_and_repair();
    total.violations_found += a.violations_found;
    total.violations_unrepaired += a.violations_unrepaired;
  }
  return total;
}

bool ZoneSet::is_valid() const {
  for (const ZoneWork& w : work_)
    if (w.zone && !w.zone->engine().is_valid()) return false;
  return true;
}

}  // namespace kew::pipeline
