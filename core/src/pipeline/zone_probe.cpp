#include "zone_probe.hpp"

#include <algorithm>
#include <chrono>

#include "phase_timer.hpp"
#include "kew/util/units.hpp"

namespace kew::pipeline {

namespace {
// Widens R_i so that rounding in positions and speeds can never drop a pair whose CPA
// test is positive (metres; far below any separation minimum).
constexpr double kSearchSlack_m = 1.0;

/// The track's kinematics and point scale in `key`'s plane, at the track's last record:
/// its own when that plane is the one it was admitted in, else projected there.
probe::Kinematics kinematics_in(const geo::Projection& plane, zone::ZoneKey key, const track::Track& track,
                                double& scale) {
  if (track.plane == key) {
    scale = track.plane_scale;
    return track.kinematics;
  }
  // Another zone's plane: the reported position projected there, the ground velocity
  // the track's own plane gave, turned and scaled for this one (both are conformal).
  geo::ProjectionError ignored = geo::ProjectionError::None;
  const geo::PlanePosition at = plane.project({track.lat_deg, track.lon_deg}, ignored);
  probe::Kinematics k = track.kinematics;
  k.position = at.p;
  k.velocity = plane.velocity_to_plane(at, track.gs_kt * units::kMpsPerKnot, track.trk_deg);
  scale = at.scale;
  return k;
}
}  // namespace

zone::ProbeState member_state(const Snapshot& s, const geo::Projection& plane, zone::ZoneKey key) {
  zone::ProbeState state = s.base;
  state.kinematics = kinematics_in(plane, key, s.track, state.scale);
  state.kinematics.turn_rate_rps = s.base.kinematics.turn_rate_rps;
  return state;
}

ZoneProbe::ZoneProbe(const PipelineConfig& config, const PairJudge& judge, const PipelineInstrumentation& instruments,
                     const zone::ZoneTiling* tiling)
    : config_(config), judge_(judge), instruments_(instruments), tiling_(tiling) {}

double ZoneProbe::tolerance_bound_m(const zone::Zone& zone) const {
  const kinetic::KineticConfig& k = config_.kinetic;
  if (k.tolerance_mode == kinetic::ToleranceMode::Absolute) return k.tolerance;
  // Relative τ bounds the lag by τ·|p|, and |p| is at most the plane radius of coverage.
  const geo::Projection& plane = zone.projection();
  return k.tolerance * plane.coverage_radius_m() * plane.max_scale() * 1.05;
}

double ZoneProbe::search_radius(const zone::Zone& zone, double speed_mps) const {
  return judge_.largest_horizontal_m() * zone.projection().max_scale() +
         judge_.largest_lookahead_s() * (speed_mps + zone.fastest_mps()) + 2.0 * tolerance_bound_m(zone) +
         kSearchSlack_m;
}

void ZoneProbe::run(ZoneWork& w, const std::vector<Snapshot>& snapshots, double epoch, double clock) const {
  zone::Zone& zone = *w.zone;
  const bool timing = instruments_.time_phases;
  const auto started = std::chrono::steady_clock::now();
  for (const ZoneOp& op : w.ops) {
    const double engine_t = op.t - epoch;
    switch (op.kind) {
      case ZoneOp::Kind::Place: {
        const Snapshot& s = snapshots[op.snapshot];
        const zone::ProbeState made = member_state(s, zone.projection(), zone.key());
        kinetic::PointId point = kinetic::kNoPoint;
        timed(timing, w.phases, &PhaseTimes::maintenance_s, [&] {
          point = zone.place(op.slot, engine_t, probe::extrapolated(made.kinematics, op.t - s.track.t));
        });
        zone.state(point) = made;
        break;
      }
      case ZoneOp::Kind::Remove:
        timed(timing, w.phases, &PhaseTimes::maintenance_s, [&] { zone.remove(op.slot, engine_t); });
        break;
      case ZoneOp::Kind::Renumber:
        timed(timing, w.phases, &PhaseTimes::maintenance_s, [&] { zone.renumber(engine_t, op.t); });
        break;
      case ZoneOp::Kind::Probe: {
        ProbeResult result;
        result.first = static_cast<std::uint32_t>(w.found.size());
        // Worldwide brute force is the alert stage's (over the whole sphere).
        if (!(tiling_ && config_.probe_mode == probe::ProbeMode::Brute)) {
          const kinetic::PointId self = zone.point_of(op.slot);
          timed(timing, w.phases, &PhaseTimes::search_s, [&] { collect_candidates(w, self); });
          timed(timing, w.phases, &PhaseTimes::tests_s, [&] { test_candidates(w, self, op.t); });
          result.candidates = w.candidates.size();
        }
        result.count = static_cast<std::uint32_t>(w.found.size()) - result.first;
        w.probes.push_back(result);
        ++zone.statistics().probes;
        break;
      }
    }
  }
  timed(timing, w.phases, &PhaseTimes::maintenance_s, [&] { zone.advance(clock - epoch); });
  zone.statistics().busy_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void ZoneProbe::collect_candidates(ZoneWork& w, kinetic::PointId self) const {
  zone::Zone& zone = *w.zone;
  const zone::ProbeState& state = zone.state(self);
  w.candidates.clear();
  // Each point once, never the track's own (within() marks what it visited).
  switch (config_.probe_mode) {
    case probe::ProbeMode::Exact:
      // Straight-line prediction: every j that can come within S_h of i within T is within
      // S_h + v_max·T (+ 2τ) of i's position T ahead (design §2.1), a disk that is smaller
      // the faster i flies; an arc stays only within |v_i|·T of its start.
      if (instruments_.search_ahead && state.kinematics.turn_rate_rps == 0.0) {
        const geometry::Point2 ahead =
            zone.engine().position_now(self) + judge_.largest_lookahead_s() * state.kinematics.velocity;
        zone.search().within_around(zone.engine(), self, ahead, search_radius(zone, 0.0), w.candidates);
      } else {
        zone.search().within(zone.engine(), self, search_radius(zone, geometry::norm(state.kinematics.velocity)),
                             w.candidates);
      }
      break;
    case probe::ProbeMode::Edges:
      zone.search().neighbours(zone.engine(), self, w.candidates);
      // A few points; within() gives each once by construction, this makes sure here.
      std::sort(w.candidates.begin(), w.candidates.end());
      w.candidates.erase(std::unique(w.candidates.begin(), w.candidates.end()), w.candidates.end());
      break;
    case probe::ProbeMode::Brute:  // one plane; worldwide: the alert stage's
      for (kinetic::PointId other = 0; other < zone.point_end(); ++other)
        if (zone.slot_of(other) != zone::kNoSlot && other != self) w.candidates.push_back(other);
      break;
  }
}

void ZoneProbe::test_candidates(ZoneWork& w, kinetic::PointId self_point, double now) const {
  zone::Zone& zone = *w.zone;
  const zone::ProbeState& self = zone.state(self_point);
  const probe::Kinematics k_self = self.at(now);
  const track::TrackSlot slot = self.slot;
  // Most candidates are clear: only pairs in conflict go on to the alert stage, with
  // their verdict, and it adds the partners and sorts the few by slot (design §2.5).
  constexpr std::size_t kPrefetchAhead = 4;  // the candidates are scattered in memory
  const std::vector<kinetic::PointId>& candidates = w.candidates;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i + kPrefetchAhead < candidates.size()) {
      const zone::ProbeState* ahead = &zone.state(candidates[i + kPrefetchAhead]);
      __builtin_prefetch(ahead);
      __builtin_prefetch(reinterpret_cast<const char*>(ahead) + 64);
    }
    const zone::ProbeState& them = zone.state(candidates[i]);
    const track::TrackSlot other = them.slot;
    const probe::Kinematics k_other = them.at(now);
    const probe::SeparationMinima minima = judge_.minima(self, them);
    if (probe::vertically_apart_for_ever(k_self, k_other, minima)) continue;
    if (slot < other ? !judge_.in_conflict(k_self, k_other, minima) : !judge_.in_conflict(k_other, k_self, minima))
      continue;
    // In conflict here: judged here only when this zone owns the pair (design §4.9).
    if (tiling_ && tiling_->owner({self.lat_deg, self.lon_deg}, {them.lat_deg, them.lon_deg}) != zone.key()) continue;
    w.found.push_back({other, judge_.pair(self, k_self, them, now)});
  }
}

}  // namespace kew::pipeline
