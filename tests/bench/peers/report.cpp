// kew_peers_bench's report: the Markdown tables on stdout and the JSON file.

#include "report.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "bench_report.hpp"

namespace kew::bench::peers {

std::string fixed(double x, int decimals) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, x);
  return text;
}

void print_table(const Params& prm, const std::vector<FleetResult>& fleets) {
  std::cout << "\n| aircraft | method | ms / period (mean of " << prm.periods
            << ") | × kew | µs / update | pairs tested / update | conflicts | mismatches |\n"
               "|---|---|---|---|---|---|---|---|\n";
  for (const FleetResult& fleet : fleets) {
    const double kew_s = fleet.methods.front().mean_seconds();
    for (const MethodResult& m : fleet.methods) {
      const double queries = static_cast<double>(m.total(&PeriodResult::queries));
      const double updates = static_cast<double>(fleet.methods.front().total(&PeriodResult::queries)) /
                             static_cast<double>(prm.periods);
      std::string name = m.name;
      if (m.sample_stride > 1) name += " (1/" + std::to_string(m.sample_stride) + " sampled, extrapolated)";
      if (m.total(&PeriodResult::fallbacks) > 0)
        name += " (" + std::to_string(m.total(&PeriodResult::fallbacks)) + " rebuilds)";
      std::uint64_t conflicts = 0;
      for (const PeriodResult& p : m.periods) conflicts += p.conflicts.size();
      std::cout << "| " << fleet.aircraft << " | " << name << " | " << fixed(1e3 * m.mean_seconds(), 1) << " | "
                << fixed(m.mean_seconds() / kew_s, 2) << " | " << fixed(1e6 * m.mean_seconds() / updates, 2) << " | "
                << fixed(static_cast<double>(m.total(&PeriodResult::pairs_tested)) / queries, 1) << " | " << conflicts
                << " | " << (m.missing + m.extra) << " |\n";
    }
  }
}

void print_split(const Params& prm, const std::vector<FleetResult>& fleets) {
  std::cout << "\n| aircraft | method | maintenance ms (%) | search ms (%) | CPA tests ms (%) | other ms (%) |\n"
               "|---|---|---|---|---|---|\n";
  for (const FleetResult& fleet : fleets)
    for (const MethodResult& m : fleet.split) {
      kew::PhaseTimes sum;
      for (const PeriodResult& p : m.periods) {
        sum.maintenance_s += p.phases.maintenance_s;
        sum.search_s += p.phases.search_s;
        sum.tests_s += p.phases.tests_s;
      }
      const double n = static_cast<double>(prm.periods), total = m.mean_seconds();
      const auto cell = [&](double seconds) {
        return fixed(1e3 * seconds / n, 1) + " (" + fixed(100.0 * seconds / n / total, 0) + ")";
      };
      std::cout << "| " << fleet.aircraft << " | " << m.name << " | " << cell(sum.maintenance_s) << " | "
                << cell(sum.search_s) << " | " << cell(sum.tests_s) << " | "
                << cell(total * n - sum.maintenance_s - sum.search_s - sum.tests_s) << " |\n";
    }
}

void print_index_parts(const std::vector<FleetResult>& fleets) {
  bool any = false;
  for (const FleetResult& fleet : fleets) any = any || fleet.index_parts.has_value();
  if (!any) return;
  std::cout << "\n| aircraft | kew-index ms / period | maintenance ms | search ms | CPA tests ms | grid ms / period | "
               "kew-index × grid |\n|---|---|---|---|---|---|---|\n";
  for (const FleetResult& fleet : fleets) {
    if (!fleet.index_parts) continue;
    const FleetResult::IndexParts& parts = *fleet.index_parts;
    const auto grid = std::find_if(fleet.methods.begin(), fleet.methods.end(),
                                   [](const MethodResult& m) { return m.name == "grid"; });
    const double grid_s = grid == fleet.methods.end() ? 0.0 : grid->mean_seconds();
    std::cout << "| " << fleet.aircraft << " | " << fixed(1e3 * parts.all, 1) << " | " << fixed(1e3 * parts.maintenance, 1)
              << " | " << fixed(1e3 * (parts.with_search - parts.maintenance), 1) << " | "
              << fixed(1e3 * (parts.all - parts.with_search), 1) << " | "
              << (grid_s > 0.0 ? fixed(1e3 * grid_s, 1) + " | " + fixed(parts.all / grid_s, 2) : std::string("- | -"))
              << " |\n";
  }
}

void print_census(const std::vector<FleetResult>& fleets) {
  bool any = false;
  for (const FleetResult& fleet : fleets) any = any || !fleet.census.empty();
  if (!any) return;
  std::cout << "\n| aircraft | candidates / update | in H / update | conflicts / update | pairs in H / period | "
               "entering H / period | entering with a common partner |\n|---|---|---|---|---|---|---|\n";
  for (const FleetResult& fleet : fleets) {
    if (fleet.census.empty()) continue;
    HorizontalCensus sum;
    for (const HorizontalCensus& c : fleet.census) {
      sum.updates += c.updates, sum.candidates += c.candidates, sum.horizontal += c.horizontal;
      sum.conflicts += c.conflicts, sum.distinct += c.distinct, sum.entering += c.entering;
      sum.entering_two_hop += c.entering_two_hop;
    }
    const auto per_update = [&](std::uint64_t x) {
      return fixed(static_cast<double>(x) / static_cast<double>(sum.updates), 1);
    };
    const auto per_period = [&](std::uint64_t x) {
      return fixed(static_cast<double>(x) / static_cast<double>(fleet.census.size()), 0);
    };
    std::cout << "| " << fleet.aircraft << " | " << per_update(sum.candidates) << " | " << per_update(sum.horizontal)
              << " | " << per_update(sum.conflicts) << " | " << per_period(sum.distinct) << " | "
              << per_period(sum.entering) << " | "
              << fixed(100.0 * static_cast<double>(sum.entering_two_hop) / static_cast<double>(std::max<std::uint64_t>(1, sum.entering)), 0)
              << " % |\n";
  }
}

void write_json(const Params& prm, const std::vector<FleetResult>& fleets) {
  JsonText j;
  j.begin_object();
  kew::bench::put_machine(j, KEW_BUILD_TYPE);
  j.key("parameters").begin_object();
  if (prm.recording.empty()) j.key("scenario").value(kew::replay::to_string(prm.scenario));
  else j.key("recording").value(prm.recording);
  j.key("period_s").value(prm.period_s);
  j.key("periods").value(std::uint64_t{prm.periods});
  j.key("warmup_periods").value(std::uint64_t{prm.warmup});
  j.key("seed").value(prm.seed);
  j.key("density_km2_per_aircraft").value(3.14159265358979 * 2000.0 * 2000.0 / 100000.0);
  j.end_object();
  j.key("fleets").begin_array();
  for (const FleetResult& fleet : fleets) {
    const double kew_s = fleet.methods.front().mean_seconds();
    j.begin_object();
    j.key("aircraft").value(std::uint64_t{fleet.aircraft});
    j.key("region_radius_km").value(fleet.radius_km);
    j.key("records").value(std::uint64_t{fleet.records});
    j.key("records_rejected").value(fleet.rejected);
    j.key("methods").begin_object();
    for (const MethodResult& m : fleet.methods) {
      j.key(m.name).begin_object();
      j.key("label").value(m.label);
      j.key("sample_stride").value(std::uint64_t{m.sample_stride});
      j.key("mean_s_per_period").value(m.mean_seconds());
      j.key("ratio_to_kew").value(m.mean_seconds() / kew_s);
      j.key("missing_vs_kew").value(m.missing);
      j.key("extra_vs_kew").value(m.extra);
      j.key("periods").begin_array();
      for (const PeriodResult& p : m.periods) {
        j.begin_object();
        j.key("s").value(p.seconds);
        j.key("measured_s").value(p.measured_seconds);
        j.key("updates").value(p.queries);
        j.key("pairs_tested").value(p.pairs_tested);
        j.key("conflicts").value(std::uint64_t{p.conflicts.size()});
        j.key("full_rebuilds").value(p.fallbacks);
        j.key("flips").value(p.flips);
        j.key("audit_violations").value(p.audit_violations);
        j.end_object();
      }
      j.end_array();
      j.end_object();
    }
    j.end_object();
    if (fleet.index_parts) {  // kew-index's three runs (seconds per period)
      j.key("kew_index_parts").begin_object();
      j.key("maintenance_s").value(fleet.index_parts->maintenance);
      j.key("maintenance_and_search_s").value(fleet.index_parts->with_search);
      j.key("all_s").value(fleet.index_parts->all);
      j.end_object();
    }
    if (!fleet.census.empty()) {
      j.key("kew_index_census").begin_array();
      for (const HorizontalCensus& c : fleet.census) {
        j.begin_object();
        j.key("updates").value(c.updates);
        j.key("candidates").value(c.candidates);
        j.key("in_h").value(c.horizontal);
        j.key("conflicts").value(c.conflicts);
        j.key("distinct_in_h").value(c.distinct);
        j.key("entering_h").value(c.entering);
        j.key("entering_h_with_common_partner").value(c.entering_two_hop);
        j.end_object();
      }
      j.end_array();
    }
    // The runs with their parts timed (CPU seconds per period).
    j.key("split").begin_object();
    for (const MethodResult& m : fleet.split) {
      j.key(m.name).begin_array();
      for (const PeriodResult& p : m.periods) {
        j.begin_object();
        j.key("measured_s").value(p.measured_seconds);
        j.key("maintenance_s").value(p.phases.maintenance_s);
        j.key("search_s").value(p.phases.search_s);
        j.key("tests_s").value(p.phases.tests_s);
        j.end_object();
      }
      j.end_array();
    }
    j.end_object();
    j.end_object();
  }
  j.end_array();
  j.end_object();
  if (!j.save(prm.json_path)) {
    std::cerr << "kew_peers_bench: cannot write " << prm.json_path << "\n";
    std::exit(1);
  }
}

}  // namespace kew::bench::peers
