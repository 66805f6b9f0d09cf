#pragma once
// kew_peers_bench's workload: the records of one fleet (generated or a recording), and
// what the Pipeline's track table makes of them, the steps every method is fed.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kew/pipeline/pipeline.hpp"
#include "params.hpp"

namespace kew::bench::peers {

using kew::probe::Kinematics;
using Slot = kew::track::TrackSlot;
inline constexpr Slot kNone = kew::track::kNoTrack;

// A track's state as the probe reads it (the Pipeline's ProbeState).
struct TrackState {
  Kinematics kinematics;  // at t
  double t = 0.0;
  double scale = 1.0;
  Kinematics at(double at_t) const {  // the Pipeline's extrapolation, operation for operation
    Kinematics k = kinematics;
    const double dt = at_t - t;
    k.position = k.position + dt * k.velocity;
    k.altitude_m += dt * k.vertical_rate_mps;
    return k;
  }
};

// One applied update (the Pipeline probes) or one track leaving the engine.
struct Step {
  bool drop = false;
  Slot slot = 0;
  std::uint32_t record = 0;  // index in Workload::records
  double clock = 0.0;        // pipeline clock when it happens (UTC s)
  TrackState state;          // after the update
};

struct Workload {
  std::size_t aircraft = 0;
  double radius_km = 0.0;
  kew::PipelineConfig config;
  std::vector<kew::TrackReport> records;
  std::vector<Step> steps;
  std::vector<std::size_t> period_first_record;  // period k: [first[k], first[k+1])
  std::vector<std::size_t> period_first_step;
  double v_max = 0.0;  // fastest plane speed of any state (m/s)
  double k_max = 1.0;  // projection scale bound
  std::uint64_t rejected = 0;
  std::size_t periods_with_records = 0;
};

/// The workload of `aircraft` generated aircraft, or of prm.recording when it names one.
Workload make_workload(const Params& prm, std::size_t aircraft);

}  // namespace kew::bench::peers
