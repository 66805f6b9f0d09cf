#pragma once
// kew_peers_bench's command line (the flags are described in tests/bench/peers_bench.cpp).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "kew/replay/traffic_generator.hpp"

namespace kew::bench::peers {

struct Params {
  std::vector<std::size_t> aircraft{1000, 10000, 100000};
  std::size_t periods = 3;  // measured radar periods per fleet size
  std::size_t warmup = 2;   // periods replayed first, untimed (the first inserts everyone)
  double period_s = 4.0;
  std::uint64_t seed = 8;
  kew::replay::Scenario scenario = kew::replay::Scenario::Mixed;
  // Largest number of pair tests brute force runs per period; beyond it every k-th
  // update is timed and the period's time extrapolated (and labelled so).
  double brute_budget = 1.5e8;
  std::string json_path;
  std::vector<std::string> methods;  // empty: all of them; kew itself always runs
  double lookahead_tolerance_m = 1000.0;  // kew-lookahead's ε
  double lookahead_keep_s = 10.0;         // kew-lookahead's K
  std::string recording;  // a real recording instead of generated traffic
  enum class FirstOrder { Arrival, Shuffled, Hilbert } first_order = FirstOrder::Arrival;
  double renumber_every_s = 60.0;  // kew-renumbered's period
};

/// Whether `method` runs: --methods names it, or names none.
bool wanted(const Params& p, const std::string& method);

/// Prints `why` and the usage line, then exits with status 2.
[[noreturn]] void usage(const std::string& why);

/// The parameters argv gives; a flag or value it cannot take ends in usage().
Params parse(int argc, char** argv);

}  // namespace kew::bench::peers
