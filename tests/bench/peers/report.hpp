#pragma once
// kew_peers_bench's report: the Markdown tables on stdout and the JSON file.

#include <string>
#include <vector>

#include "params.hpp"
#include "results.hpp"

namespace kew::bench::peers {

/// x with `decimals` digits after the point.
std::string fixed(double x, int decimals);

/// Every method per fleet: time per period, against kew, per update, pairs tested, conflicts, mismatches.
void print_table(const Params& prm, const std::vector<FleetResult>& fleets);
/// kew's time per period split by part (PipelineInstrumentation::time_phases; "other" is
/// the track table, projection and what the parts do not cover).
void print_split(const Params& prm, const std::vector<FleetResult>& fleets);
/// kew-index's parts from its three runs, beside the grid's whole period.
void print_index_parts(const std::vector<FleetResult>& fleets);
/// The census of H (HorizontalCensus), per update and per period.
void print_census(const std::vector<FleetResult>& fleets);
/// Everything above and the parameters to prm.json_path; exits with status 1 when it cannot.
void write_json(const Params& prm, const std::vector<FleetResult>& fleets);

}  // namespace kew::bench::peers
