#pragma once
// The peer baseline of kew-eval --baseline statebased (design §2.6): the all-pairs linear
// state-based conflict detection that BlueSky's StateBasedCD and most research
// simulators use, run over the same records as kew and scored by the same truth.
//
// Every `step_s` of data time, every pair of tracks with a state is predicted in straight
// lines from its last records (positions, ground velocities and vertical rates: reported,
// else derived from the last two records) and is in conflict when it comes closer than
// S_h horizontally and S_v vertically at one moment of [0, T]. No rule filters anything:
// ground traffic, slow targets, one aircraft seen twice and level pairs alert alike. A
// pair alerts while it is in conflict: the alert opens at its first conflicting step and
// ends at its first clear one (no confirmation, no hysteresis).

#include <span>
#include <vector>

#include "kew/replay/evaluation.hpp"
#include "kew/track/track_report.hpp"
#include "kew/util/units.hpp"

namespace kew::replay {

struct StateBasedConfig {
  double horizontal_m = 5.0 * units::kMetresPerNauticalMile;  ///< S_h (m, > 0): 5 NM
  double vertical_ft = 1000.0;         ///< S_v (ft, > 0)
  double lookahead_s = 300.0;          ///< T (s, > 0): BlueSky's default dtlookahead
  double step_s = 1.0;                 ///< time between evaluations (s, > 0): BlueSky's asas_dt
  /// A track without a record for this long is forgotten (s, > 0): a recording, unlike a
  /// simulation, has aircraft that leave coverage. kew's track timeout.
  double timeout_s = 30.0;
};

/// The baseline's alerts over `records`, taken in their order (a record older than its
/// track's last is ignored), as kew-eval scores them; alerts still in conflict at the
/// end stay open. Ids are "sb" and a serial number. Deterministic.
std::vector<AlertSpan> state_based_alerts(std::span<const TrackReport> records, const StateBasedConfig& config = {});

}  // namespace kew::replay
