// kew_peers_bench: kew's per-radar-period cost against what an engineer would otherwise
// build (design §6.7), on the same generated traffic and in one run:
//   (a) kew         the Pipeline (track table, projection, kinetic Delaunay updates and
//                   events, exact BFS probe, alert manager) — no alert output;
//   (a') kew-index  kew's kinetic triangulation and exact search alone, driven with the
//                   same updates and conflict test as (b)-(e): the method measured as
//                   the baselines are (also split into maintenance, search and tests,
//                   and H counted: what kinetic detection would keep, design §2.7);
//   (a'') kew-lookahead  the prototype of kinetic detection (design §2.7,
//                   tests/support/lookahead_pairs.hpp): H kept by events on a kinetic
//                   triangulation of the look-ahead points, each update testing H(i);
//   (b) cgal        a static Delaunay triangulation rebuilt by CGAL every period
//                   (spatial sort, then insertion with a hint; Epick) + the same BFS probe;
//   (c) flip        one triangulation kept across periods: every position updated in place
//                   at the period's start, every edge checked (exact incircle) and
//                   repaired by Lawson flips (a full rebuild when a face folded over);
//   (d) grid        a uniform grid of R_max cells rebuilt every period;
//   (e) brute       every live track for every update: BlueSky's state-based detection
//                   (all pairs, the same CPA) — sampled when it would take too long.
//
// All five evaluate the same thing: on every applied update of track i at time t, each
// candidate j with the conflict test of the Pipeline (kinematics extrapolated to t, lower
// slot first, minima scaled by the pair's projection scale). Each must find exactly the
// pairs in conflict that (a) finds for the same updates; a difference is printed and
// makes the exit status 1.
//
// The baselines index positions at the period's start t0, so an index position lags
// the track's current one by at most D(t) = v_max·(t − t0) + J, J the largest sum of
// measurement jumps of one track since t0 (both known online): their searches use
// R_i + D(t), with R_i = S_h·k_max + T·(|v_i| + v_max) (kew's R_i without its 2τ).
// Tracks that appeared since t0, or whose jumps add up to more than 500 m, are left out
// of the index (and of J) and tried by every query instead.
//
// Usage: kew_peers_bench [--quick] [--aircraft 1000,10000,100000] [--periods N]
//                        [--warmup N] [--seed S] [--scenario mixed|random|airways|stacks|tma]
//                        [--recording FILE] [--methods kew-index,grid,...]
//                        [--lookahead-tolerance M] [--lookahead-keep S] [--brute-budget PAIRS]
//                        [--first-order arrival|shuffled|hilbert] [--renumber-every S]
//                        [--json FILE]
// --methods picks which methods run beside kew (kew-centred, kew-eager, kew-tau50, kew-renumbered,
// kew-index, kew-lookahead, cgal, flip, grid, brute; all by default). --recording runs
// one fleet on a real recording (any format kew-replay detects, time-sorted here) instead
// of generated traffic: its periods from the first record on. --lookahead-tolerance is
// kew-lookahead's ε (m, default 1000), --lookahead-keep its K (s, default 10; ADS-B feeds
// that report every 5-15 s want more, or most kept reports end as Drifts).
// --first-order permutes the first period's records (which create every track, point and
// face) into a random or a Hilbert-curve order of their positions: the worst and the best
// memory order a renumbering could leave; arrival order by default.
// --renumber-every is kew-renumbered's PipelineConfig::renumber_every_s (default 60).
//
// Density: the region grows with √N (one aircraft per 126 km² at every N), but the
// mixed scenario puts its TMA arrivals (20 %) on one centre and its airways (40 %) on at
// most 40 routes, so its local density grows with N: at 100,000 aircraft an update has
// ~4× the candidates of 1,000. --scenario random keeps the density uniform.
//
// The parts are in tests/bench/peers/: the command line (params), the workload, one file
// per method behind the Method interface (method.hpp; the baselines share the driver of
// baseline.hpp), one fleet's runs and checks (fleet), and the tables and JSON (report).

#include <cstddef>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "bench_report.hpp"
#include "peers/fleet.hpp"
#include "peers/params.hpp"
#include "peers/report.hpp"
#include "peers/results.hpp"

int main(int argc, char** argv) {
  using namespace kew::bench::peers;
  Params prm = parse(argc, argv);
  std::cout << "machine: " << kew::bench::cpu_model_name() << ", " << kew::bench::hardware_threads()
            << " hardware threads, build " << KEW_BUILD_TYPE << "\n"
            << "traffic: "
            << (prm.recording.empty() ? "kew-gen scenario " + std::string(kew::replay::to_string(prm.scenario))
                                      : "recording " + prm.recording)
            << ", P = " << prm.period_s << " s, " << prm.warmup << " warm-up + " << prm.periods
            << " measured periods"
            << (prm.recording.empty() ? ", seed " + std::to_string(prm.seed) +
                                            ", one aircraft per 126 km² (region radius 2,000 km·√(N/100,000))"
                                      : "")
            << "\n";
  std::vector<FleetResult> fleets;
  bool all_agree = true;
  for (const std::size_t n : prm.aircraft) fleets.push_back(run_fleet(prm, n, all_agree));
  print_table(prm, fleets);
  print_split(prm, fleets);
  print_index_parts(fleets);
  print_census(fleets);
  if (!prm.json_path.empty()) write_json(prm, fleets);
  if (!all_agree) std::cerr << "kew_peers_bench: a baseline disagrees with kew (see MISMATCH lines)\n";
  return all_agree ? 0 : 1;
}
