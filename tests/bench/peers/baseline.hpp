#pragma once
// The baselines' common driver: each baseline is a spatial index of the positions at the
// period's start t0, and the driver feeds it the workload's steps, queries it on every
// applied update and tests the candidates with the Pipeline's conflict test.
//
// An index answers for_each_candidate(world, slot, centre, radius, f): f(j) at least for
// every indexed track j whose t0 position is within radius of centre (others allowed).
// rebuild(world, t0, out) makes it from the live tracks at the period's start; audit()
// counts what its structure violates. The driver is a template over the index so that
// the candidate callback costs no indirect call.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "bench_report.hpp"
#include "method.hpp"
#include "world.hpp"

namespace kew::bench::peers {

inline double squared_distance(Point2 a, Point2 b) {
  const Vector2 d = a - b;
  return kew::geometry::dot(d, d);
}

template <class Index>
void run_index(const Params& prm, const Workload& w, Index& index, MethodResult& result) {
  World world;
  const kew::probe::SeparationMinima& minima = w.config.minima;
  const double lookahead = minima.lookahead_s;
  const std::size_t stride = result.sample_stride;
  std::size_t step = 0;
  for (; step < w.period_first_step[prm.warmup]; ++step) world.apply(w.steps[step]);
  {  // untimed: (c) starts each period from the previous one's triangulation
    PeriodResult unused;
    const double t_start = w.records[w.period_first_record[prm.warmup]].t;
    world.begin_period(t_start);
    index.rebuild(world, t_start, unused);
  }
  for (std::size_t period = prm.warmup; period < prm.warmup + prm.periods; ++period) {
    PeriodResult out;
    const double t0 = w.records[w.period_first_record[period]].t;
    double query_seconds = 0.0;
    std::uint64_t records_in_period = 0, sampled = 0;
    const Stopwatch clock;
    world.begin_period(t0);
    index.rebuild(world, t0, out);
    for (; step < w.period_first_step[period + 1]; ++step) {
      const Step& s = w.steps[step];
      world.apply(s);
      if (s.drop) continue;
      ++records_in_period;
      if (s.record % stride != 0) continue;
      ++sampled;
      std::optional<Stopwatch> query_clock;
      if (stride > 1) query_clock.emplace();
      const Kinematics k_self = world.state[s.slot].at(s.clock);
      const double radius = minima.horizontal_m * w.k_max +
                            lookahead * (kew::geometry::norm(k_self.velocity) + w.v_max) + 1.0 +
                            world.staleness(s.clock, w.v_max);
      const auto test = [&](Slot other) {
        if (other == s.slot || !world.live[other]) return;
        ++out.pairs_tested;
        if (in_conflict(world, s.slot, k_self, other, s.clock, minima))
          out.conflicts.push_back({s.record, std::min(s.slot, other), std::max(s.slot, other)});
      };
      // An index entry of a slot dropped since t0 is stale (the slot may hold a new track,
      // which is among the extras).
      index.for_each_candidate(world, s.slot, k_self.position, radius, [&](Slot other) {
        if (world.indexed[other]) test(other);
      });
      for (const Slot other : world.extras) test(other);
      ++out.queries;
      if (query_clock) query_seconds += query_clock->seconds();
    }
    out.measured_seconds = clock.seconds();
    out.seconds = out.measured_seconds;
    if (stride > 1 && sampled > 0)
      out.seconds += query_seconds * (static_cast<double>(records_in_period) / static_cast<double>(sampled) - 1.0);
    out.audit_violations += index.audit();
    result.periods.push_back(std::move(out));
  }
}

// One baseline as a Method: its index, run by the driver above.
template <class Index>
class Baseline final : public Method {
 public:
  template <class... IndexArgs>
  Baseline(std::string name, std::string label, std::size_t sample_stride, IndexArgs&&... index_args)
      : name_(std::move(name)), label_(std::move(label)), stride_(sample_stride),
        index_(std::forward<IndexArgs>(index_args)...) {}
  std::string name() const override { return name_; }
  MethodResult run(const Params& prm, const Workload& w) override {
    MethodResult m{name_, label_, stride_, {}, 0, 0};
    run_index(prm, w, index_, m);
    return m;
  }

 private:
  std::string name_, label_;
  std::size_t stride_;
  Index index_;
};

}  // namespace kew::bench::peers
