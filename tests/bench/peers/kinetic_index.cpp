// (a') kew-index: kew's method alone, measured as the baselines are, its time split by
// ablation and the census of H counted on its updates.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "bench_report.hpp"
#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/probe/proximity_search.hpp"
#include "method.hpp"
#include "world.hpp"

namespace kew::bench::peers {

namespace {

// How much of kew-index's work one run does. Three runs (maintenance alone, with the
// search, everything) split its time by their differences, without reading a clock
// around each part of each update: a clock read costs microseconds on virtual machines
// whose clock source is not the TSC, which is what distorts PipelineInstrumentation::time_phases.
enum class IndexWork { Maintenance, Search, All };

// Whether two tracks come within `s_h` of each other horizontally during [0, T] (m, s).
bool horizontally_close(const Kinematics& a, const Kinematics& b, double s_h, double lookahead_s) {
  const Vector2 d = b.position - a.position, v = b.velocity - a.velocity;
  const double vv = kew::geometry::dot(v, v);
  const double at = vv > 0.0 ? std::clamp(-kew::geometry::dot(d, v) / vv, 0.0, lookahead_s) : 0.0;
  const Vector2 closest = d + at * v;
  return kew::geometry::dot(closest, closest) < s_h * s_h;
}

// The Pipeline's kinetic triangulation and exact search (the disk of radius
// S_h·k_max + T·v_max + 2τ around p_i + v_i·T, design §2.1), fed the same updates as the
// baselines (the track table's output, World) and testing candidates with the same
// conflict test: the method's maintenance, search and CPA tests, without the track
// table, projection, eligibility rules and alert bookkeeping the Pipeline adds around
// them. v_max is the largest speed of the whole run, as the baselines' (the Pipeline's
// is that of the tracks live at the time).
// With `census`, counts H per measured period as well (an untimed run: hash sets).
MethodResult run_kinetic_index(const Params& prm, const Workload& w, IndexWork work = IndexWork::All,
                               std::vector<HorizontalCensus>* census = nullptr) {
  using kew::kinetic::kNoPoint;
  using kew::kinetic::PointId;
  MethodResult result{"kew-index", "kew's kinetic Delaunay triangulation and exact search alone, fed as the baselines are",
                      1, {}, 0, 0};
  const kew::probe::SeparationMinima& minima = w.config.minima;
  kew::kinetic::KineticDelaunay kdt(w.config.kinetic, 0.0);
  kew::probe::ProximitySearch search;
  World world;
  std::vector<PointId> point_of;  // by slot
  std::vector<Slot> slot_of;      // by point
  std::vector<PointId> found;
  const double epoch = w.steps.empty() ? 0.0 : std::floor(w.steps.front().clock);
  const double radius =
      minima.horizontal_m * w.k_max + minima.lookahead_s * w.v_max + 2.0 * w.config.kinetic.tolerance + 1.0;
  // The Pipeline's calls for one step (Pipeline::apply, leave_engine); the point updated.
  const auto apply = [&](const Step& s) -> PointId {
    world.grow(s.slot);
    if (point_of.size() <= s.slot) point_of.resize(s.slot + 1, kNoPoint);
    const double t = s.clock - epoch;
    kdt.advance(t);
    PointId& point = point_of[s.slot];
    if (s.drop) {
      if (point != kNoPoint) {
        kdt.remove(point, t);
        slot_of[point] = kNone;
        point = kNoPoint;
      }
      world.live[s.slot] = 0;
      return kNoPoint;
    }
    world.state[s.slot] = s.state;
    world.live[s.slot] = 1;
    const Kinematics now = s.state.at(s.clock);
    if (point == kNoPoint) {
      point = kdt.insert(t, now.position, now.velocity);
      if (slot_of.size() <= point) slot_of.resize(point + 1, kNone);
      slot_of[point] = s.slot;
    } else {
      kdt.update(point, t, now.position, now.velocity);
    }
    return point;
  };
  const auto pair_key = [](Slot a, Slot b) {
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
  };
  std::unordered_set<std::uint64_t> h_now, h_before;                      // pairs in H, this period and the one before
  std::unordered_map<Slot, std::vector<Slot>> partners_now, partners_before;  // H as adjacency lists
  std::size_t step = 0;
  for (; step < w.period_first_step[prm.warmup]; ++step) apply(w.steps[step]);
  for (std::size_t period = prm.warmup; period < prm.warmup + prm.periods; ++period) {
    PeriodResult out;
    HorizontalCensus counted;
    const Stopwatch clock;
    for (; step < w.period_first_step[period + 1]; ++step) {
      const Step& s = w.steps[step];
      const PointId point = apply(s);
      if (point == kNoPoint || work == IndexWork::Maintenance) continue;
      const Kinematics k_self = world.state[s.slot].at(s.clock);
      found.clear();
      search.within_around(kdt, point, kdt.position_now(point) + minima.lookahead_s * k_self.velocity, radius, found);
      ++out.queries;
      if (work == IndexWork::Search) continue;
      for (const PointId p : found) {
        const Slot other = slot_of[p];
        ++out.pairs_tested;
        if (in_conflict(world, s.slot, k_self, other, s.clock, minima))
          out.conflicts.push_back({s.record, std::min(s.slot, other), std::max(s.slot, other)});
        if (census) {
          const double s_h = minima.horizontal_m * kew::geo::Projection::pair_scale(world.state[s.slot].scale,
                                                                                   world.state[other].scale);
          if (horizontally_close(k_self, world.state[other].at(s.clock), s_h, minima.lookahead_s)) {
            ++counted.horizontal;
            if (h_now.insert(pair_key(s.slot, other)).second) {
              partners_now[s.slot].push_back(other);
              partners_now[other].push_back(s.slot);
            }
          }
        }
      }
    }
    out.seconds = out.measured_seconds = clock.seconds();
    if (census) {
      counted.updates = out.queries;
      counted.candidates = out.pairs_tested;
      counted.conflicts = out.conflicts.size();
      counted.distinct = h_now.size();
      std::vector<Slot> mine;
      for (const std::uint64_t key : h_now) {
        if (h_before.count(key)) continue;
        ++counted.entering;
        const auto a = partners_before.find(static_cast<Slot>(key >> 32));
        const auto b = partners_before.find(static_cast<Slot>(key & 0xFFFFFFFFu));
        if (a == partners_before.end() || b == partners_before.end()) continue;
        mine = a->second;
        std::sort(mine.begin(), mine.end());
        for (const Slot k : b->second)
          if (std::binary_search(mine.begin(), mine.end(), k)) {
            ++counted.entering_two_hop;
            break;
          }
      }
      // The period before the first measured one is not counted: nothing enters then.
      if (period > prm.warmup) census->push_back(counted);
      h_before.swap(h_now);
      partners_before.swap(partners_now);
      h_now.clear();
      partners_now.clear();
    }
    out.audit_violations += kdt.is_valid() ? 0 : 1;
    result.periods.push_back(std::move(out));
  }
  return result;
}

class KineticIndex final : public Method {
 public:
  std::string name() const override { return "kew-index"; }
  MethodResult run(const Params& prm, const Workload& w) override { return run_kinetic_index(prm, w); }
  // Its parts by ablation (three runs), then an untimed run counting H.
  void measure_more(const Params& prm, const Workload& w, FleetResult& fleet) override {
    fleet.index_parts = {run_kinetic_index(prm, w, IndexWork::Maintenance).mean_seconds(),
                         run_kinetic_index(prm, w, IndexWork::Search).mean_seconds(),
                         run_kinetic_index(prm, w, IndexWork::All).mean_seconds()};
    run_kinetic_index(prm, w, IndexWork::All, &fleet.census);
  }
};

}  // namespace

std::unique_ptr<Method> make_kinetic_index() { return std::make_unique<KineticIndex>(); }

}  // namespace kew::bench::peers
