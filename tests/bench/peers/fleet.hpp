#pragma once
// One fleet of kew_peers_bench: its workload, every picked method run on it, each
// checked against kew.

#include <cstddef>

#include "params.hpp"
#include "results.hpp"

namespace kew::bench::peers {

/// Runs kew and the methods prm.methods picks on `aircraft` generated aircraft (or on
/// prm.recording, whose measured periods then bound prm.periods). Clears `all_agree`
/// when a method finds other conflicts than its reference, or fails its audit; prints
/// progress and each mismatch to stderr.
FleetResult run_fleet(Params& prm, std::size_t aircraft, bool& all_agree);

}  // namespace kew::bench::peers
