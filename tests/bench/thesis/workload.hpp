#pragma once
// The radar-like workload of kew_thesis_bench: aircraft flying straight or turning at
// constant speed over a square, each seen once per antenna rotation with Gaussian
// position noise. One measurement stream is generated per parameter set and replayed by
// every configuration compared on it.

#include <cmath>
#include <cstdint>
#include <vector>

#include "kew/geometry/vector2.hpp"

namespace kew::bench::thesis {

using geometry::Point2;
using geometry::Vector2;

struct WorkloadParameters {
  std::size_t aircraft = 2000;
  double period_s = 4.0;      ///< radar rotation period P, s (> 0)
  double duration_s = 300.0;  ///< simulated time D, s (≥ P)
  double noise_sigma_m = 30.0;  ///< standard deviation of each position coordinate, m (≥ 0)
  double max_turn_deg_s = 1.5;  ///< turn rates are drawn from [−max, max], °/s
  double speed_min_m_s = 120.0, speed_max_m_s = 260.0;
  std::uint64_t seed = 20240611;
  /// Side of the square, m: 800 km for 2,000 aircraft (one aircraft per 320 km², a busy
  /// en-route sector), scaled with √N so that every N has the same density.
  double side_m() const { return 800e3 * std::sqrt(static_cast<double>(aircraft) / 2000.0); }
};

struct Measurement {
  double t;  ///< s
  std::uint32_t aircraft;
  Point2 p;   ///< measured position, m (true position plus noise)
  Vector2 v;  ///< true velocity, m/s (a tracker's smoothed velocity)
};

struct Workload {
  std::vector<Measurement> initial;  ///< t = 0, one per aircraft, inserted during setup
  std::vector<Measurement> updates;  ///< in time order
  std::size_t periods = 0;
};

/// The measurement stream of `parameters`: deterministic for a given seed.
Workload make_workload(const WorkloadParameters& parameters);

}  // namespace kew::bench::thesis
