// One fleet of kew_peers_bench: every picked method run on its workload, each checked
// against kew.

#include "fleet.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "method.hpp"
#include "report.hpp"
#include "workload.hpp"

namespace kew::bench::peers {

namespace {

// The conflicts m found against those of the reference (kew) on the updates m evaluated:
// counted in m, the first five of each kind printed.
void compare(const MethodResult& kew_result, MethodResult& m) {
  for (std::size_t k = 0; k < m.periods.size(); ++k) {
    std::vector<Conflict> expected;
    for (const Conflict& c : kew_result.periods[k].conflicts)
      if (c.record % m.sample_stride == 0) expected.push_back(c);
    std::vector<Conflict>& found = m.periods[k].conflicts;
    std::sort(expected.begin(), expected.end());
    std::sort(found.begin(), found.end());
    std::vector<Conflict> missing, extra;
    std::set_difference(expected.begin(), expected.end(), found.begin(), found.end(), std::back_inserter(missing));
    std::set_difference(found.begin(), found.end(), expected.begin(), expected.end(), std::back_inserter(extra));
    m.missing += missing.size();
    m.extra += extra.size();
    const auto show = [&](const char* what, const std::vector<Conflict>& list) {
      for (std::size_t i = 0; i < std::min<std::size_t>(list.size(), 5); ++i)
        std::cerr << "  MISMATCH " << m.name << " period " << k << ": " << what << " record " << list[i].record
                  << " slots " << list[i].p << "-" << list[i].q << "\n";
    };
    show("kew found, baseline did not:", missing);
    show("baseline found, kew did not:", extra);
  }
}

// Those of `all` that --methods picks, in their order.
Methods picked(const Params& prm, Methods all) {
  std::erase_if(all, [&](const std::unique_ptr<Method>& m) { return !wanted(prm, m->name()); });
  return all;
}

// kew's variants, kew-index and kew-lookahead.
Methods kew_methods(const Params& prm) {
  Methods all = make_kew_variants();
  all.push_back(make_kinetic_index());
  all.push_back(make_lookahead());
  return picked(prm, std::move(all));
}

// The baselines: cgal, flip, grid and brute (sampled beyond prm.brute_budget pair tests).
Methods baselines(const Params& prm, const Workload& w, std::size_t aircraft) {
  const double r_max = w.config.minima.horizontal_m * w.k_max + 2.0 * w.config.minima.lookahead_s * w.v_max;
  const double pairs = static_cast<double>(aircraft) * static_cast<double>(aircraft);
  const auto stride = static_cast<std::size_t>(std::max(1.0, std::ceil(pairs / prm.brute_budget)));
  Methods all;
  all.push_back(make_cgal_rebuild());
  all.push_back(make_flip_repair());
  all.push_back(make_uniform_grid(r_max));
  all.push_back(make_brute_force(stride));
  return picked(prm, std::move(all));
}

}  // namespace

FleetResult run_fleet(Params& prm, std::size_t n, bool& all_agree) {
  std::cerr << (prm.recording.empty() ? std::to_string(n) + " aircraft: generating..." : "reading...") << "\n";
  const Workload w = make_workload(prm, n);
  if (!prm.recording.empty()) {  // measure the recording's periods, not more
    prm.periods = std::max<std::size_t>(1, std::min(prm.periods, w.periods_with_records - std::min(w.periods_with_records, prm.warmup)));
    std::cerr << "  " << prm.periods << " periods measured\n";
  }
  FleetResult fleet{w.aircraft, w.radius_km, w.records.size(), w.rejected, {}, {}, {}, {}};
  std::cerr << "  " << w.records.size() << " records (" << w.rejected << " rejected), region radius "
            << fixed(w.radius_km, 0) << " km; (a) kew...\n";
  const std::unique_ptr<Method> kew = make_kew();
  fleet.methods.push_back(kew->run(prm, w));
  // On a recording the Pipeline's own rules (the time guard, young runs, sources) give
  // its tracks other slots than the bench's track table does: the methods are checked
  // against the first one run after kew instead, which is fed what they are fed.
  const auto reference = [&]() -> const MethodResult& {
    return prm.recording.empty() ? fleet.methods.front() : fleet.methods[1];
  };
  const auto checked = [&](MethodResult m) {
    if (prm.recording.empty() || fleet.methods.size() > 1) compare(reference(), m);
    all_agree = all_agree && m.missing == 0 && m.extra == 0;
    fleet.methods.push_back(std::move(m));
  };
  const Methods kinetic = kew_methods(prm);
  for (const std::unique_ptr<Method>& method : kinetic) {
    MethodResult m = method->run(prm, w);
    std::cerr << "  " << m.name << " done\n";
    checked(std::move(m));
    method->measure_more(prm, w, fleet);
  }
  std::cerr << "  kew's variants again, timing their parts...\n";
  const auto time_parts = [&](Method& method) {
    if (std::optional<MethodResult> timed = method.run_parts_timed(prm, w)) fleet.split.push_back(std::move(*timed));
  };
  time_parts(*kew);
  for (const std::unique_ptr<Method>& method : kinetic) time_parts(*method);

  for (std::unique_ptr<Method>& method : baselines(prm, w, n)) {
    std::cerr << "  " << method->name() << "...\n";
    checked(method->run(prm, w));
    method.reset();  // its index's memory is freed before the next one runs
  }
  for (const MethodResult& m : fleet.methods)
    for (const PeriodResult& p : m.periods)
      if (p.audit_violations) {
        std::cerr << "  " << m.name << ": triangulation audit found " << p.audit_violations << " violations\n";
        all_agree = false;
      }
  return fleet;
}

}  // namespace kew::bench::peers
