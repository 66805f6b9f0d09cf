#pragma once
// The methods kew_peers_bench compares: kew (the Pipeline) and its variants, kew's
// kinetic index alone, the kinetic-detection prototype, and the baselines. Each one runs
// on a workload and gives its measured periods and the conflicts it found.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "params.hpp"
#include "results.hpp"
#include "workload.hpp"

namespace kew::bench::peers {

class Method {
 public:
  virtual ~Method() = default;
  /// As --methods, the tables and the JSON name it.
  virtual std::string name() const = 0;
  /// The measured periods of w (after prm.warmup untimed ones).
  virtual MethodResult run(const Params& prm, const Workload& w) = 0;
  /// kew and its variants: a second run with the period's time split by part, which
  /// timing the parts slows (print_split). Other methods: none.
  virtual std::optional<MethodResult> run_parts_timed(const Params&, const Workload&) { return std::nullopt; }
  /// Figures the fleet records beside the method's row (kew-index: its parts, the census of H).
  virtual void measure_more(const Params&, const Workload&, FleetResult&) {}
};

using Methods = std::vector<std::unique_ptr<Method>>;

/// (a) kew: the Pipeline, which every other method is checked against.
std::unique_ptr<Method> make_kew();
/// kew with each of its speed levers turned back off: kew-centred, kew-eager, kew-tau50,
/// kew-renumbered.
Methods make_kew_variants();
/// (a') kew-index: kew's kinetic triangulation and exact search alone, fed as the baselines are.
std::unique_ptr<Method> make_kinetic_index();
/// (a'') kew-lookahead: the prototype of kinetic detection.
std::unique_ptr<Method> make_lookahead();
/// (b) cgal: CGAL's Delaunay triangulation rebuilt every period.
std::unique_ptr<Method> make_cgal_rebuild();
/// (c) flip: one triangulation moved in place and repaired by flips.
std::unique_ptr<Method> make_flip_repair();
/// (d) grid: a uniform grid of `cell_m` cells rebuilt every period.
std::unique_ptr<Method> make_uniform_grid(double cell_m);
/// (e) brute: every live track for every update, every `sample_stride`-th record's update evaluated.
std::unique_ptr<Method> make_brute_force(std::size_t sample_stride);

}  // namespace kew::bench::peers
