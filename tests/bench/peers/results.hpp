#pragma once
// What kew_peers_bench measures: each method's periods and the conflicts it found (to
// compare methods), and per fleet every method's result with kew's extra figures.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kew/pipeline/instrumentation.hpp"
#include "workload.hpp"

namespace kew::bench::peers {

struct Conflict {
  std::uint32_t record;
  Slot p, q;  // p < q
  auto operator<=>(const Conflict&) const = default;
};

struct PeriodResult {
  double seconds = 0.0;            // measured (or, for sampled brute force, extrapolated)
  double measured_seconds = 0.0;   // what the clock said
  std::uint64_t pairs_tested = 0;  // CPA tests (sampled updates only, when sampled)
  std::uint64_t queries = 0;
  std::vector<Conflict> conflicts;
  std::uint64_t fallbacks = 0;     // (c): periods needing a full rebuild
  std::uint64_t flips = 0;         // (c)
  std::uint64_t audit_violations = 0;
  kew::PhaseTimes phases;          // kew only: where the period's time went
};

struct MethodResult {
  std::string name;
  std::string label;
  std::size_t sample_stride = 1;  // every k-th record's update is evaluated (brute force)
  std::vector<PeriodResult> periods;
  std::uint64_t missing = 0, extra = 0;  // against kew, over all periods
  double mean_seconds() const {
    double sum = 0.0;
    for (const PeriodResult& p : periods) sum += p.seconds;
    return periods.empty() ? 0.0 : sum / static_cast<double>(periods.size());
  }
  std::uint64_t total(std::uint64_t PeriodResult::*field) const {
    std::uint64_t sum = 0;
    for (const PeriodResult& p : periods) sum += p.*field;
    return sum;
  }
};

// What kinetic detection (design §2.7) would have to keep, counted on
// kew-index's updates: H, the pairs whose horizontal separation is below S_h somewhere in
// the look-ahead window [t, t + T] (every pair that can be in conflict is in H).
struct HorizontalCensus {
  std::uint64_t updates = 0;
  std::uint64_t candidates = 0;        // pairs the exact search returned
  std::uint64_t horizontal = 0;        // of those, pairs in H at the update: Σ |H_i|
  std::uint64_t conflicts = 0;
  std::uint64_t distinct = 0;          // pairs in H at some update of the period
  std::uint64_t entering = 0;          // of those, pairs in H at no update of the period before
  std::uint64_t entering_two_hop = 0;  // of those, pairs with a common H partner the period before
};

struct FleetResult {
  std::size_t aircraft = 0;
  double radius_km = 0.0;
  std::size_t records = 0;
  std::uint64_t rejected = 0;
  std::vector<MethodResult> methods;  // kew first
  std::vector<MethodResult> split;    // kew and its variants with their parts timed
  struct IndexParts {                  // kew-index's three runs (IndexWork), s per period
    double maintenance = 0.0, with_search = 0.0, all = 0.0;
  };
  std::optional<IndexParts> index_parts;
  std::vector<HorizontalCensus> census;  // by measured period after the first
};

}  // namespace kew::bench::peers
