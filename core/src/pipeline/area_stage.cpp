#include "area_stage.hpp"

#include <algorithm>
#include <cmath>

#include "alert_party.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/util/units.hpp"
#include "kew/util/wildcard.hpp"
#include "zone_probe.hpp"

namespace kew::pipeline {

namespace {

std::vector<volume::Volume> fixed_areas(const std::vector<volume::WatchedVolume>& volumes) {
  std::vector<volume::Volume> areas;
  for (const volume::WatchedVolume& v : volumes)
    if (v.area) areas.push_back(*v.area);
  return areas;
}

bool names_track(const std::string& pattern, const track::Track& t) {
  return util::matches_wildcard(pattern, t.id) || (!t.callsign.empty() && util::matches_wildcard(pattern, t.callsign));
}

// Beyond this the followed circle's plane is not trusted (m): a followed circle is a
// few miles across and its alerts look a few minutes ahead.
constexpr double kFollowReachCap_m = 500e3;

}  // namespace

AreaStage::AreaStage(const std::vector<volume::WatchedVolume>& volumes, const eligibility::Rules& rules,
                     ZoneSet& zones)
    : volumes_(volumes), rules_(rules), zones_(zones), centre_(volumes.size(), track::kNoTrack),
      index_(fixed_areas(volumes)) {
  for (std::uint32_t v = 0; v < volumes.size(); ++v) {
    (volumes[v].area ? fixed_ : followers_).push_back(v);
    if (volumes[v].area) bands_.push_back({volumes[v].area->band().floor_ft, volumes[v].area->band().ceiling_ft, true});
    else bands_.push_back({});
    longest_lookahead_s_ = std::max(longest_lookahead_s_, volumes[v].lookahead_s);
  }
}

void AreaStage::follow(track::TrackSlot slot, const track::Track& t) {
  for (const std::uint32_t v : followers_)
    if (centre_[v] == track::kNoTrack && names_track(volumes_[v].follow, t)) centre_[v] = slot;
}

void AreaStage::judge(track::TrackSlot slot, const std::vector<Snapshot>& view, double now,
                      alert::AlertManager& alerts, Rejections& suppressed, std::vector<AlertEvent>& out) {
  if (volumes_.empty()) return;
  const Snapshot& s = view[slot];
  const track::Track& t = s.track;
  follow(slot, t);

  const double late = std::max(0.0, now - t.t);
  judged_.clear();
  alerts.volumes_of(slot, judged_);
  held_.assign(judged_.begin(), judged_.end());
  std::sort(held_.begin(), held_.end());
  if (!fixed_.empty()) {
    volume::Motion path;
    path.start = {t.lat_deg, t.lon_deg};
    path.track_deg = t.trk_deg;
    path.gs_kt = std::min(t.gs_kt, volume::kMaxGroundSpeed_kt);
    for (const std::uint32_t i : index_.candidates(path, std::min(longest_lookahead_s_ + late, volume::kMaxHorizon_s)))
      judged_.push_back(fixed_[i]);
  }
  for (const std::uint32_t v : followers_)
    if (centre_[v] != track::kNoTrack && centre_[v] != slot) judged_.push_back(v);
  std::sort(judged_.begin(), judged_.end());
  judged_.erase(std::unique(judged_.begin(), judged_.end()), judged_.end());

  // The altitudes the track can reach over the longest look-ahead, whatever its intent
  // (a level-off only narrows them): most candidates' bands lie elsewhere.
  const double climb_ft = t.vr_fpm * (longest_lookahead_s_ + late) / 60.0;
  const double lowest_ft = t.alt_ft + std::min(0.0, climb_ft), highest_ft = t.alt_ft + std::max(0.0, climb_ft);
  for (const std::uint32_t v : judged_) {
    const Band& band = bands_[v];
    const bool held = std::binary_search(held_.begin(), held_.end(), v);
    if (band.fixed && (highest_ft < band.floor_ft || lowest_ft > band.ceiling_ft) && !held) continue;  // clear
    const volume::WatchedVolume& w = volumes_[v];
    Approach a;
    if (w.schedule.active_at(now) && w.traffic.concerns(t.id, t.callsign, t.mode3a)) {
      if (w.area) {
        a = fixed_approach(w, s, now);
      } else if (const std::optional<Approach> followed = followed_approach(v, slot, view, now)) {
        a = *followed;
      }
    }
    if (a.enters && !alerts.is_area_active(slot, v)) {
      // The rules stop alerts from opening, never end one (design §4.5).
      const eligibility::Exclusion why = rules_.area_exclusion(t, now);
      if (why != eligibility::Exclusion::None) {
        suppressed.reject(eligibility::kExclusionNames.name(why));
        a = Approach{};
      }
    }
    if (!a.enters && !held) continue;  // clear, and the manager knows nothing of it
    alert::Evaluation e;
    e.in_conflict = a.enters;
    e.observed_t = t.t;
    if (a.enters) {
      e.severity = alerts.classify(a.inside_now, a.t_entry_s, w.warning_s);
      e.t_los_s = a.t_entry_s;
    }
    alerts.evaluate_area(
        slot, v, e, now,
        [&](AlertEvent& event) {
          event.a = party_of(t);
          event.t_los_s = a.t_entry_s;
          event.volume = w.name;
          event.volume_kind = volume::kVolumeKindNames.name(w.kind);
          event.hypothesis = a.inside_now  ? Hypothesis::Proximity
                             : a.level_off ? Hypothesis::LevelOff
                                           : Hypothesis::Linear;
        },
        out);
  }
}

AreaStage::Approach AreaStage::fixed_approach(const volume::WatchedVolume& v, const Snapshot& s, double now) const {
  const track::Track& t = s.track;
  volume::Motion m;
  m.start = {t.lat_deg, t.lon_deg};
  m.alt_ft = t.alt_ft;
  m.track_deg = t.trk_deg;
  m.gs_kt = t.gs_kt;
  m.vr_fpm = t.vr_fpm;
  if (t.level_off_ft && now <= s.base.level_off_until_t) m.sel_ft = *t.level_off_ft;
  // A record judged after its own time (the clock ran ahead) is followed from its time,
  // and only what lies after `now` counts.
  const double late = std::min(std::max(0.0, now - t.t), volume::kMaxHorizon_s - v.lookahead_s);
  const volume::Entry e = volume::entry(*v.area, m, v.lookahead_s + late, late);
  Approach a;
  if (e.error != volume::MotionError::None || !e.entry_s) return a;
  a.enters = true;
  a.inside_now = e.inside_now;
  a.t_entry_s = *e.entry_s - late;
  const std::optional<double> levels = volume::level_off_s(m);
  a.level_off = levels && *levels < *e.entry_s;
  return a;
}

std::optional<AreaStage::Approach> AreaStage::followed_approach(std::uint32_t v, track::TrackSlot slot,
                                                                const std::vector<Snapshot>& view, double now) {
  const track::TrackSlot centre = centre_[v];
  if (centre == track::kNoTrack || centre == slot || centre >= view.size()) return std::nullopt;
  const volume::WatchedVolume& w = volumes_[v];
  const Snapshot& self = view[slot];
  const Snapshot& followed = view[centre];
  const double reach_m =
      std::min(kFollowReachCap_m,
               w.follow_radius_m + (self.track.gs_kt + followed.track.gs_kt) * units::kMpsPerKnot * w.lookahead_s);
  if (geo::Projection::geodesic_distance_m({self.track.lat_deg, self.track.lon_deg},
                                           {followed.track.lat_deg, followed.track.lon_deg}) > reach_m)
    return std::nullopt;
  const zone::ZoneKey owner = zones_.owner_of(self.track, followed.track);
  if (owner == zone::kNoZone) return std::nullopt;
  const geo::Projection& plane = zones_.plane(owner);
  const zone::ProbeState mine = member_state(self, plane, owner);
  const zone::ProbeState theirs = member_state(followed, plane, owner);
  // The circle is a pair's minima around the followed aircraft: S_h its radius, and its
  // band [alt + floor, alt + ceiling] as the followed aircraft's altitude moved to the
  // band's middle with S_v half its height, predicted linearly over the look-ahead.
  probe::Kinematics centre_k = theirs.at(now);
  const double floor_m = w.follow_band.floor_ft * units::kMetresPerFoot;
  const double ceiling_m = w.follow_band.ceiling_ft * units::kMetresPerFoot;
  centre_k.altitude_m += 0.5 * (floor_m + ceiling_m);
  if (centre_k.levels_off()) centre_k.level_off_m += 0.5 * (floor_m + ceiling_m);
  probe::SeparationMinima minima;
  minima.horizontal_m = w.follow_radius_m * geo::Projection::pair_scale(mine.scale, theirs.scale);
  minima.vertical_m = 0.5 * (ceiling_m - floor_m);
  minima.lookahead_s = w.lookahead_s;
  minima.vertical_lookahead_s = w.lookahead_s;
  minima.altimetry_tolerance_m = 0.0;
  const probe::ConflictGeometry g = probe::evaluate_pair(mine.at(now), centre_k, minima);
  Approach a;
  a.enters = g.in_conflict;
  a.inside_now = g.lost_now;
  a.t_entry_s = g.lost_now ? 0.0 : g.t_los_s;
  a.level_off = g.level_off;
  return a;
}

void AreaStage::track_left(track::TrackSlot slot, double now, alert::AlertManager& alerts,
                           std::vector<AlertEvent>& out) {
  for (const std::uint32_t v : followers_) {
    if (centre_[v] != slot) continue;
    alerts.drop_volume(v, now, out);
    centre_[v] = track::kNoTrack;
  }
}

void AreaStage::save(util::CheckpointWriter& out) const {
  out.u64(centre_.size());
  for (const track::TrackSlot slot : centre_) out.u32(slot);
}

void AreaStage::restore(util::CheckpointReader& in) {
  const std::size_t at = in.offset();
  const std::uint64_t n = in.u64();
  if (n != centre_.size()) in.fail(at, "a checkpoint of another list of volumes");
  for (track::TrackSlot& slot : centre_) slot = in.u32();
}

}  // namespace kew::pipeline
