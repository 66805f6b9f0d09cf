// (a'') kew-lookahead: the prototype of kinetic detection (design §2.7,
// tests/support/lookahead_pairs.hpp) fed the same steps, testing the candidates
// LookaheadPairs gives with the same conflict test. Its own counters (reports kept and
// replaced, disk searches, entries) are printed to stderr.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>

#include "bench_report.hpp"
#include "lookahead_pairs.hpp"
#include "method.hpp"
#include "report.hpp"
#include "world.hpp"

namespace kew::bench::peers {

namespace {

MethodResult run_lookahead(const Params& prm, const Workload& w) {
  MethodResult result{"kew-lookahead", "prototype: H kept by events on a kinetic triangulation of p + v·T (design §2.7)",
                      1, {}, 0, 0};
  const kew::probe::SeparationMinima& minima = w.config.minima;
  kew::testing::LookaheadPairsConfig config;
  config.separation_m = minima.horizontal_m * w.k_max;
  config.lookahead_s = minima.lookahead_s;
  config.tolerance_m = prm.lookahead_tolerance_m;
  config.keep_s = prm.lookahead_keep_s;
  config.max_speed_mps = w.v_max;
  config.kinetic = w.config.kinetic;
  const double epoch = w.steps.empty() ? 0.0 : std::floor(w.steps.front().clock);
  kew::testing::LookaheadPairs pairs(config, 0.0);
  World world;
  const auto apply = [&](const Step& s) {
    world.grow(s.slot);
    const double t = s.clock - epoch;
    if (s.drop) {
      pairs.remove(s.slot, t);
      world.live[s.slot] = 0;
      return;
    }
    world.state[s.slot] = s.state;
    world.live[s.slot] = 1;
    const Kinematics now = s.state.at(s.clock);
    pairs.report(s.slot, t, now.position, now.velocity);
  };
  std::size_t step = 0;
  for (; step < w.period_first_step[prm.warmup]; ++step) apply(w.steps[step]);
  const kew::testing::LookaheadPairsStatistics before = pairs.statistics();
  // Reports whose track replaced its model within the last 10, 30 and 60 s (this one
  // included): the tracks a hybrid would search for instead of keeping in H.
  constexpr double kRecent_s[] = {10.0, 30.0, 60.0};
  std::uint64_t recent[3] = {0, 0, 0};
  std::uint64_t measured_reports = 0;
  for (std::size_t period = prm.warmup; period < prm.warmup + prm.periods; ++period) {
    PeriodResult out;
    const Stopwatch clock;
    for (; step < w.period_first_step[period + 1]; ++step) {
      const Step& s = w.steps[step];
      apply(s);
      if (s.drop) continue;
      ++measured_reports;
      const double age = s.clock - epoch - pairs.last_replaced(s.slot);
      for (int k = 0; k < 3; ++k) recent[k] += age < kRecent_s[k] ? 1 : 0;
      const Kinematics k_self = world.state[s.slot].at(s.clock);
      pairs.for_each_candidate(s.slot, [&](Slot other) {
        ++out.pairs_tested;
        if (in_conflict(world, s.slot, k_self, other, s.clock, minima))
          out.conflicts.push_back({s.record, std::min(s.slot, other), std::max(s.slot, other)});
      });
      ++out.queries;
    }
    out.seconds = out.measured_seconds = clock.seconds();
    result.periods.push_back(std::move(out));
  }
  const kew::testing::LookaheadPairsStatistics& after = pairs.statistics();
  const auto per_period = [&](std::uint64_t a, std::uint64_t b) {
    return fixed(static_cast<double>(a - b) / static_cast<double>(prm.periods), 0);
  };
  std::cerr << "  kew-lookahead per period (epsilon " << fixed(config.tolerance_m, 0) << " m): reports "
            << per_period(after.reports, before.reports) << ", replaced " << per_period(after.replaced, before.replaced)
            << " ("
            << fixed(100.0 * static_cast<double>(after.replaced + after.drifts - before.replaced - before.drifts) /
                         std::max(1.0, static_cast<double>(after.reports - before.reports)),
                     1)
            << " % of reports with drifts)"
            << ", drifts " << per_period(after.drifts, before.drifts) << ", disk searches "
            << per_period(after.disk_searches, before.disk_searches) << ", edges told "
            << per_period(after.edges_told, before.edges_told) << ", entries "
            << per_period(after.entries, before.entries) << ", exits " << per_period(after.exits, before.exits)
            << ", candidate pairs computed " << per_period(after.two_hop_considered, before.two_hop_considered)
            << " (two-hop entries pruned " << per_period(after.two_hop_pruned, before.two_hop_pruned) << ")"
            << ", entries queued " << per_period(after.entries_queued, before.entries_queued) << ", stale "
            << per_period(after.events_stale, before.events_stale) << ", queue max " << after.queue_max << ", |H| per track "
            << fixed(static_cast<double>(pairs.pair_ends()) / static_cast<double>(w.aircraft), 1) << ", twins made "
            << pairs.triangulation_statistics().twins_created << ", reports of tracks replaced within 10/30/60 s "
            << fixed(100.0 * static_cast<double>(recent[0]) / std::max(1.0, static_cast<double>(measured_reports)), 1) << " / "
            << fixed(100.0 * static_cast<double>(recent[1]) / std::max(1.0, static_cast<double>(measured_reports)), 1) << " / "
            << fixed(100.0 * static_cast<double>(recent[2]) / std::max(1.0, static_cast<double>(measured_reports)), 1) << " %\n";
  return result;
}

class Lookahead final : public Method {
 public:
  std::string name() const override { return "kew-lookahead"; }
  MethodResult run(const Params& prm, const Workload& w) override { return run_lookahead(prm, w); }
};

}  // namespace

std::unique_ptr<Method> make_lookahead() { return std::make_unique<Lookahead>(); }

}  // namespace kew::bench::peers
