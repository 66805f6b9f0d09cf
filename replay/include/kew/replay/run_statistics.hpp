#pragma once
// The statistics object of `kew-replay --stats-json` (SPEC §5.6): one JSON object with
// at least the keys the spec lists, in a fixed order.

#include <cstdint>
#include <string>

#include "kew/pipeline/pipeline.hpp"
#include "kew/util/rejections.hpp"

namespace kew::replay {

struct RunFigures {
  std::uint64_t records_decoded = 0;  ///< reports produced by the decoders
  double wall_s = 0.0;                ///< wall-clock duration of the run
  std::uint64_t audits = 0;           ///< audits run (--audit)
  std::uint64_t audit_violations_found = 0;
  std::uint64_t audit_violations_unrepaired = 0;
};

/// Renders the statistics of a finished run. `decoding` holds the decoders' rejections;
/// the pipeline's own rejections are merged into the same "rejected" object.
std::string run_statistics_json(const Pipeline& pipeline, const Rejections& decoding, const RunFigures& figures);

}  // namespace kew::replay
