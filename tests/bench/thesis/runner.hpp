#pragma once
// One configuration of the kinetic engine replaying a workload, timed per update kind.

#include <string>
#include <vector>

#include "kew/kinetic/kinetic_delaunay.hpp"
#include "workload.hpp"

namespace kew::bench::thesis {

/// How a measurement beyond τ reaches the triangulation.
enum class Reinsertion {
  /// KineticDelaunay::update: the point is detached and attached again with the walk
  /// starting next to where it was (design §8.3, "reinsertion walk").
  Engine,
  /// remove() then insert(), the thesis' "remove the point ... and reinsert it" (§10.3.3):
  /// the insertion locates the point by a walk from an arbitrary face, O(√N) steps.
  RemoveInsert,
};

struct Configuration {
  std::string name;
  kinetic::KineticConfig kinetic;
  Reinsertion reinsertion = Reinsertion::Engine;
  bool trace_queue = false;  ///< sample the queue once a second of data time
};

/// Seconds and calls of one kind of update.
struct KindCost {
  double seconds = 0;
  std::uint64_t calls = 0;
  double us_per_call() const { return calls ? 1e6 * seconds / static_cast<double>(calls) : 0.0; }
};

struct QueueSample {
  double t;                   ///< data time, s
  std::size_t failures;       ///< failures and approaches scheduled
  std::size_t renewals;       ///< renewal entries scheduled
};

struct RunResult {
  Configuration configuration;
  kinetic::KineticStatistics stats;
  double setup_s = 0;    ///< initial insertion of every aircraft (not compared)
  double advance_s = 0;  ///< events up to each measurement's time
  double update_s = 0;   ///< the update itself, its clock already at the measurement
  double loop_s = 0;     ///< the whole loop: advance + update + clock reads
  std::size_t updates = 0;
  KindCost kept, velocity_only, reinserted;  ///< update_s split by what the update did
  // Sampled after each advance() of the loop: the engine keeps only the current
  // renewals_queued, and its queue_mean() also samples the queue while it fills during
  // setup, so both are sampled here at the same instants.
  double failures_queued_mean = 0;
  double renewals_queued_mean = 0;
  std::vector<QueueSample> queue_trace;
  bool valid = false;  ///< the triangulation was valid at the end

  double entries_queued_mean() const { return failures_queued_mean + renewals_queued_mean; }
  double update_us() const { return 1e6 * update_s / static_cast<double>(updates); }
  double advance_us() const { return 1e6 * advance_s / static_cast<double>(updates); }
  double loop_us() const { return 1e6 * loop_s / static_cast<double>(updates); }
  double discarded_share() const;
};

/// Replays `workload` once with `configuration`. Times are wall seconds (steady clock).
RunResult run_once(const Configuration& configuration, const Workload& workload);

/// Runs every configuration `repeats` times, interleaved (each round runs them all, so a
/// slow spell of the machine touches every configuration alike), and keeps for each the
/// run of median loop time; counts are identical between repeats (the engine is
/// deterministic), so only the times differ.
std::vector<RunResult> run_medians(const std::vector<Configuration>& configurations, const Workload& workload,
                                   int repeats);

}  // namespace kew::bench::thesis
