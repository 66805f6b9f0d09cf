#pragma once
// What benchmarks and tests may ask of a Pipeline beyond its configuration
// (Pipeline::instrument): none of it changes an alert, and the product leaves it all off.

#include <functional>

#include "kew/track/track_table.hpp"

namespace kew {

/// Where the time of updates goes (PipelineInstrumentation::time_phases): CPU seconds of the
/// calling thread, summed over the run.
struct PhaseTimes {
  double maintenance_s = 0.0;  ///< kinetic maintenance: insert, update, remove, advance (events)
  double search_s = 0.0;       ///< candidate search (ProximitySearch) and partner collection
  double tests_s = 0.0;        ///< CPA tests of the candidates and the alert bookkeeping
};

struct PipelineInstrumentation {
  /// Time the three parts of the work on updates (Pipeline::phase_times): two reads of
  /// the thread's CPU clock per part and update, about 1 µs.
  bool time_phases = false;
  /// Exact mode: search around the predicted position p_i + v_i·T, over the smaller disk
  /// of design §2.1 (a track under a turn hypothesis keeps the disk around p_i). Both
  /// are complete; false measures the difference (kew_peers_bench).
  bool search_ahead = true;
  /// Told of every pair evaluation that finds a conflict, before the eligibility rules
  /// and the alert manager see it (a pair the rules then suppress is told too): slots
  /// (p < q) of the pair, at the pipeline's clock. Alerts need `confirm` such
  /// evaluations; the tap sees each one, so benchmarks can check other candidate
  /// searches against the probe's.
  std::function<void(track::TrackSlot p, track::TrackSlot q)> conflict_tap;
};

}  // namespace kew
