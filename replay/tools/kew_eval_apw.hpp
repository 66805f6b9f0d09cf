#pragma once
// kew-eval's area proximity warnings (design §4.11; docs/alert-quality.md, "Area proximity
// warnings"): a run's APW alerts scored against the AreaTruth of its volumes, printed
// apart from the pair figures (which a configuration without volumes leaves byte for
// byte as they were): a table per kind of volume, list lines, and a JSON member.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "kew/replay/area_evaluation.hpp"
#include "kew/replay/area_truth.hpp"
#include "kew/replay/evaluation.hpp"

namespace kew::replay::tools {

/// One column's APW alerts, scored. `truth` is null when the column has neither volumes
/// nor APW alerts: then it prints nothing of APW.
struct AreaRun {
  std::shared_ptr<const AreaTruth> truth;
  std::vector<AlertSpan> alerts;  ///< the run's APW alerts
  AreaEvaluation evaluation;
};

/// The APW tables: for each kind of volume some column has, its volumes, then a row per
/// figure and a column per run (columns without APW read "-"). "" when no column has APW.
std::string area_table(const std::vector<std::pair<std::string, const AreaRun*>>& columns);

/// `--list`: a line per APW alert and per entry, prefixed "[name] apw".
std::string area_list(const Truth& truth, const std::string& name, const AreaRun& run);

/// The run's "apw" JSON object: its volumes, the figures by kind, and with `list` the
/// alert_list and entry_list.
std::string area_json(const Truth& truth, const AreaRun& run, bool list);

}  // namespace kew::replay::tools
