#include "runner.hpp"

#include <algorithm>
#include <chrono>

namespace kew::bench::thesis {
namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

double RunResult::discarded_share() const {
  return stats.events_computed
             ? static_cast<double>(stats.events_discarded) / static_cast<double>(stats.events_computed)
             : 0.0;
}

RunResult run_once(const Configuration& configuration, const Workload& w) {
  using kinetic::KineticDelaunay;
  using kinetic::UpdateKind;
  RunResult r;
  r.configuration = configuration;
  const kinetic::KineticConfig& config = configuration.kinetic;
  KineticDelaunay kdt(config, 0.0);
  std::vector<kinetic::PointId> id(w.initial.size());

  const auto s0 = Clock::now();
  for (const Measurement& m : w.initial) id[m.aircraft] = kdt.insert(m.t, m.p, m.v);
  r.setup_s = seconds(Clock::now() - s0);

  double next_sample = 0.0;
  // advance() runs before the update so that the events up to the measurement's time
  // are timed apart from the update: update() would otherwise advance internally and
  // the τ comparison would mostly measure the (shared) event processing.
  const auto l0 = Clock::now();
  for (const Measurement& m : w.updates) {
    const auto a0 = Clock::now();
    kdt.advance(m.t);
    const auto a1 = Clock::now();
    const kinetic::KineticStatistics& s = kdt.statistics();
    r.failures_queued_mean += static_cast<double>(s.queue_now);
    r.renewals_queued_mean += static_cast<double>(s.renewals_queued);
    if (configuration.trace_queue && m.t >= next_sample) {
      r.queue_trace.push_back({m.t, s.queue_now, s.renewals_queued});
      next_sample = std::floor(m.t) + 1.0;
    }
    kinetic::PointId& point = id[m.aircraft];
    UpdateKind kind;
    if (configuration.reinsertion == Reinsertion::RemoveInsert &&
        geometry::norm(m.p - kdt.position(point, m.t)) > config.tolerance) {
      kdt.remove(point, m.t);
      point = kdt.insert(m.t, m.p, m.v);
      kind = UpdateKind::Reinserted;
    } else {
      kind = kdt.update(point, m.t, m.p, m.v);
    }
    const auto a2 = Clock::now();
    const double spent = seconds(a2 - a1);
    r.advance_s += seconds(a1 - a0);
    r.update_s += spent;
    KindCost& cost = kind == UpdateKind::Kept ? r.kept : kind == UpdateKind::VelocityOnly ? r.velocity_only : r.reinserted;
    cost.seconds += spent;
    ++cost.calls;
  }
  r.loop_s = seconds(Clock::now() - l0);

  r.updates = w.updates.size();
  r.failures_queued_mean /= static_cast<double>(r.updates);
  r.renewals_queued_mean /= static_cast<double>(r.updates);
  r.stats = kdt.statistics();
  r.valid = kdt.is_valid();  // a fast run that broke the triangulation proves nothing
  return r;
}

std::vector<RunResult> run_medians(const std::vector<Configuration>& configurations, const Workload& workload,
                                   int repeats) {
  std::vector<std::vector<RunResult>> runs(configurations.size());
  for (int round = 0; round < std::max(1, repeats); ++round)
    for (std::size_t c = 0; c < configurations.size(); ++c) runs[c].push_back(run_once(configurations[c], workload));
  std::vector<RunResult> medians;
  for (auto& of_one : runs) {
    std::sort(of_one.begin(), of_one.end(), [](const RunResult& a, const RunResult& b) { return a.loop_s < b.loop_s; });
    medians.push_back(std::move(of_one[of_one.size() / 2]));
  }
  return medians;
}

}  // namespace kew::bench::thesis
