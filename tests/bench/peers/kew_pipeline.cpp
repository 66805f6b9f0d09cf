// (a) kew: the Pipeline as configured, and each of its speed levers turned back off,
// beside it in one run.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_report.hpp"
#include "kew/pipeline/instrumentation.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/util/name_table.hpp"
#include "method.hpp"
#include "report.hpp"

namespace kew::bench::peers {

namespace {

enum class KewVariant { Default, Centred, Eager, Reinserting, Renumbered };
inline constexpr kew::util::NameTable<KewVariant, 5> kKewVariantNames({{
    {KewVariant::Default, "kew"},
    {KewVariant::Centred, "kew-centred"},
    {KewVariant::Eager, "kew-eager"},
    {KewVariant::Reinserting, "kew-tau50"},
    {KewVariant::Renumbered, "kew-renumbered"},
}});
std::string variant_name(KewVariant variant) { return std::string(kKewVariantNames.name(variant)); }

// kew's time per period, then (time_phases) a second run for the split of print_split:
// timing the parts costs a few clock reads per update (about 1 µs with a TSC clock
// source, several on a virtual machine without one), kept out of the first.
MethodResult run_kew(const Params& prm, const Workload& w, KewVariant variant = KewVariant::Default,
                     bool time_phases = false) {
  kew::PipelineConfig config = w.config;
  kew::PipelineInstrumentation instruments;
  instruments.time_phases = time_phases;
  MethodResult result{variant_name(variant), "", 1, {}, 0, 0};
  switch (variant) {
    case KewVariant::Default:
      result.label = "kew: KDT updates (lazy certificates) + exact BFS probe around p + v·T (Pipeline)";
      break;
    case KewVariant::Centred:
      result.label = "kew with the earlier query: BFS around p, radius S_h + T(|v| + v_max)";
      instruments.search_ahead = false;
      break;
    case KewVariant::Eager:
      result.label = "kew with every certificate solved over the whole horizon";
      config.kinetic.lazy_window_s = 0.0;
      break;
    case KewVariant::Reinserting:
      result.label = "kew with the earlier tolerance: τ = 50 m, every update within τ changes the velocity";
      config.kinetic.tolerance = 50.0;
      config.kinetic.keep_model_s = 0.0;
      break;
    case KewVariant::Renumbered:
      result.label = "kew renumbering its points and probe states along a Hilbert curve every " +
                     fixed(prm.renumber_every_s, 0) + " s";
      config.renumber_every_s = prm.renumber_every_s;
      break;
  }
  kew::Pipeline pipeline(config);
  std::uint32_t current = 0;
  std::vector<Conflict>* sink = nullptr;
  instruments.conflict_tap = [&](Slot p, Slot q) {
    if (sink) sink->push_back({current, p, q});
  };
  pipeline.instrument(instruments);
  for (std::size_t period = 0; period < prm.warmup + prm.periods; ++period) {
    const bool measured = period >= prm.warmup;
    PeriodResult out;
    sink = measured ? &out.conflicts : nullptr;
    const std::uint64_t probes0 = pipeline.statistics().probes, pairs0 = pipeline.statistics().candidates;
    const kew::PhaseTimes phases0 = pipeline.phase_times();
    const Stopwatch clock;
    for (std::size_t i = w.period_first_record[period]; i < w.period_first_record[period + 1]; ++i) {
      current = static_cast<std::uint32_t>(i);
      pipeline.process(w.records[i]);
    }
    out.seconds = out.measured_seconds = clock.seconds();
    out.queries = pipeline.statistics().probes - probes0;
    out.pairs_tested = pipeline.statistics().candidates - pairs0;
    const kew::PhaseTimes& phases = pipeline.phase_times();
    out.phases = {phases.maintenance_s - phases0.maintenance_s, phases.search_s - phases0.search_s,
                  phases.tests_s - phases0.tests_s};
    if (measured) result.periods.push_back(std::move(out));
  }
  return result;
}

class KewMethod final : public Method {
 public:
  explicit KewMethod(KewVariant variant) : variant_(variant) {}
  std::string name() const override { return variant_name(variant_); }
  MethodResult run(const Params& prm, const Workload& w) override { return run_kew(prm, w, variant_); }
  std::optional<MethodResult> run_parts_timed(const Params& prm, const Workload& w) override {
    return run_kew(prm, w, variant_, true);
  }

 private:
  KewVariant variant_;
};

}  // namespace

std::unique_ptr<Method> make_kew() { return std::make_unique<KewMethod>(KewVariant::Default); }

Methods make_kew_variants() {
  Methods out;
  for (const KewVariant variant :
       {KewVariant::Centred, KewVariant::Eager, KewVariant::Reinserting, KewVariant::Renumbered})
    out.push_back(std::make_unique<KewMethod>(variant));
  return out;
}

}  // namespace kew::bench::peers
