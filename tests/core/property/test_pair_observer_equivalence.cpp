// A pair observer changes no alert (design §4.10): on generated traffic of every kind, a
// pipeline whose observer watches every pair of tracks gives the same events, byte for
// byte in the alert stream's encoding, as one without an observer.
#include "kew/pipeline/pair_observer.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/replay/traffic_generator.hpp"

#include <gtest/gtest.h>

#include <array>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace kew {
namespace {

/// Watches every pair of the tracks it was told an applied record of, and counts the
/// judgements by stage.
class EveryPair final : public PairObserver {
 public:
  bool watches(std::string_view, std::string_view) const override { return true; }
  std::vector<alert::PartyName> partners(std::string_view source, std::string_view id, double) const override {
    std::vector<alert::PartyName> out;
    for (const auto& [s, i] : seen_)
      if (s != source || i != id) out.push_back({s, i});
    return out;
  }
  void record(const TrackReport& report, const RecordOutcome& outcome) override {
    if (outcome.applied()) seen_.emplace(report.source, report.id);
  }
  void pair_judged(const PairObservation& observation) override {
    ++judged[static_cast<std::size_t>(observation.stage)];
  }

  std::array<std::size_t, static_cast<std::size_t>(PairStage::Alerting) + 1> judged{};

 private:
  std::set<std::pair<std::string, std::string>> seen_;  // a set: partners' names stay put
};

/// The alert stream of `traffic` through a pipeline, observed by `observer` if not null.
std::string alert_stream(const replay::GeneratorConfig& traffic, PairObserver* observer) {
  PipelineConfig config;
  config.batch_records = 1;  // an observer's requirement: the same for the run without one
  Pipeline pipeline(config);
  pipeline.set_pair_observer(observer);
  std::string stream;
  pipeline.set_alert_sink([&](const AlertEvent& e) { protocol::append_alert_json(stream, e, e.seq); });
  replay::TrafficGenerator generator(traffic);
  TrackReport report;
  while (generator.next(report)) pipeline.process(report);
  pipeline.end_of_input();
  pipeline.drop_all();
  return stream;
}

class PairObserverEquivalence : public ::testing::TestWithParam<replay::Scenario> {};

TEST_P(PairObserverEquivalence, EveryPairWatchedChangesNoAlert) {
  const replay::GeneratorConfig traffic{.scenario = GetParam(), .aircraft = 120, .duration_s = 120.0,
                                       .seed = 20261123, .missed_update_probability = 0.05, .radius_km = 80.0,
                                       .aerodromes = nullptr};
  EveryPair observer;
  const std::string watched = alert_stream(traffic, &observer);
  const std::string unwatched = alert_stream(traffic, nullptr);
  EXPECT_EQ(watched, unwatched);
  EXPECT_NE(unwatched.find("\"state\":\"new\""), std::string::npos) << "the scenario must raise alerts";
  // The observer was told of pairs in conflict and of clear ones.
  for (const PairStage stage : {PairStage::ProbeClear, PairStage::ConfirmPending, PairStage::Alerting})
    EXPECT_GT(observer.judged[static_cast<std::size_t>(stage)], 0u) << static_cast<int>(stage);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, PairObserverEquivalence,
                         ::testing::Values(replay::Scenario::Random, replay::Scenario::Airways,
                                           replay::Scenario::Stacks, replay::Scenario::Tma,
                                           replay::Scenario::Mixed),
                         [](const auto& param_info) { return std::string(replay::to_string(param_info.param)); });

}  // namespace
}  // namespace kew
