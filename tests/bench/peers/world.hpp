#pragma once
// The tracks as the methods outside the Pipeline see them, fed the workload's steps, and
// the Pipeline's conflict test they all apply to their candidates.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "kew/geo/projection.hpp"
#include "kew/probe/cpa.hpp"
#include "workload.hpp"

namespace kew::bench::peers {

using kew::geometry::Point2;
using kew::geometry::Vector2;

// What every baseline knows of the tracks: the probe states, and how stale the index
// built at the period's start t0 may be.
struct World {
  static constexpr double kMaxIndexedJump_m = 500.0;
  std::vector<TrackState> state;
  std::vector<std::uint8_t> live;     // in the engine
  std::vector<std::uint8_t> indexed;  // in this period's index, at its t0 position
  std::vector<double> jumps;          // Σ |new − predicted| since t0, per indexed track (m)
  std::vector<Slot> extras;           // live tracks not in the index (appeared since t0)
  std::vector<std::uint8_t> in_extras;
  double jump_max = 0.0;
  double t0 = 0.0;

  void grow(Slot slot) {
    if (slot < state.size()) return;
    state.resize(slot + 1);
    live.resize(slot + 1, 0);
    indexed.resize(slot + 1, 0);
    jumps.resize(slot + 1, 0.0);
    in_extras.resize(slot + 1, 0);
  }
  void begin_period(double t) {
    t0 = t;
    jump_max = 0.0;
    for (const Slot s : extras) in_extras[s] = 0;
    extras.clear();
    for (std::size_t s = 0; s < live.size(); ++s) {
      indexed[s] = live[s];
      jumps[s] = 0.0;
    }
  }
  void apply(const Step& step) {
    grow(step.slot);
    const Slot s = step.slot;
    if (step.drop) {
      live[s] = 0;
      indexed[s] = 0;  // the slot may be reused by a new track: its index entry is stale
      return;
    }
    if (indexed[s]) {
      const Vector2 jump = step.state.at(step.clock).position - state[s].at(step.clock).position;
      jumps[s] += kew::geometry::norm(jump);
      // One track that jumped far (a manoeuvre, a bad plot) would widen every search;
      // it leaves the index instead and is tried by every query until the next rebuild.
      if (jumps[s] > kMaxIndexedJump_m) indexed[s] = 0;
      else jump_max = std::max(jump_max, jumps[s]);
    }
    if (!indexed[s] && !in_extras[s]) {
      in_extras[s] = 1;
      extras.push_back(s);
    }
    state[s] = step.state;
    live[s] = 1;
  }
  /// Bound on |current position − index position| of any indexed track at t (m).
  double staleness(double t, double v_max) const { return v_max * (t - t0) + jump_max; }
};

// The Pipeline's conflict test of the pair (slot, other) at `clock` (Pipeline::probe).
inline bool in_conflict(const World& world, Slot slot, const Kinematics& k_self, Slot other, double clock,
                        const kew::probe::SeparationMinima& base) {
  const TrackState& self = world.state[slot];
  const TrackState& them = world.state[other];
  kew::probe::SeparationMinima minima = base;
  minima.horizontal_m *= kew::geo::Projection::pair_scale(self.scale, them.scale);
  const Kinematics k_other = them.at(clock);
  return slot < other ? kew::probe::in_conflict(k_self, k_other, minima)
                      : kew::probe::in_conflict(k_other, k_self, minima);
}

}  // namespace kew::bench::peers
