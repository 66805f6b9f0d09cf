// The exact probe (Delaunay BFS within R_i) produces exactly the alert events of brute
// force, event for event, on generated traffic of every kind (design §2.1, §4).
#include "kew/pipeline/pipeline.hpp"
#include "kew/replay/traffic_generator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace kew {
namespace {

/// Turns one generated record into the records a test feeds (none, it, or several).
using Edit = void (*)(const TrackReport& in, std::vector<TrackReport>& out);

struct RunResult {
  std::vector<AlertEvent> events;
  std::uint64_t candidates = 0;
  std::uint64_t probes = 0;
  std::size_t audit_violations = 0;
  std::map<std::string, std::uint64_t, std::less<>> suppressed;
  std::uint64_t fields_dropped = 0;
  std::uint64_t renumberings = 0;
};

using Configure = void (*)(PipelineConfig& config);

RunResult run(const replay::GeneratorConfig& traffic, probe::ProbeMode mode, double tolerance,
              kinetic::ToleranceMode tolerance_mode = kinetic::ToleranceMode::Absolute, Edit edit = nullptr,
              Configure configure = nullptr) {
  PipelineConfig config;
  if (configure) configure(config);
  config.probe_mode = mode;
  config.kinetic.tolerance = tolerance;
  config.kinetic.tolerance_mode = tolerance_mode;
  Pipeline pipeline(config);
  RunResult out;
  pipeline.set_alert_sink([&](const AlertEvent& e) { out.events.push_back(e); });
  replay::TrafficGenerator generator(traffic);
  TrackReport report;
  std::vector<TrackReport> edited;
  double next_audit = traffic.start_time + 30.0;
  while (generator.next(report)) {
    edited.clear();
    if (edit) edit(report, edited);
    else edited.push_back(report);
    for (const TrackReport& r : edited) pipeline.process(r);
    if (pipeline.now() >= next_audit) {
      out.audit_violations += pipeline.audit().violations_found;
      next_audit += 30.0;
    }
  }
  pipeline.drop_all();
  out.candidates = pipeline.statistics().candidates;
  out.probes = pipeline.statistics().probes;
  out.suppressed = pipeline.suppressed().by_reason();
  out.fields_dropped = pipeline.dropped_fields().total();
  out.renumberings = pipeline.kinetic_statistics().renumberings;
  return out;
}

void expect_same_party(const AlertParty& x, const AlertParty& y) {
  EXPECT_EQ(x.id, y.id);
  EXPECT_EQ(x.lat_deg, y.lat_deg);
  EXPECT_EQ(x.alt_ft, y.alt_ft);
  EXPECT_EQ(x.gs_kt, y.gs_kt);
}

void expect_identical(const std::vector<AlertEvent>& exact, const std::vector<AlertEvent>& brute) {
  ASSERT_EQ(exact.size(), brute.size());
  for (std::size_t i = 0; i < exact.size(); ++i) {
    SCOPED_TRACE("event " + std::to_string(i));
    const AlertEvent& x = exact[i];
    const AlertEvent& y = brute[i];
    EXPECT_EQ(x.seq, y.seq);
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.state, y.state);
    EXPECT_EQ(x.severity, y.severity);
    EXPECT_EQ(x.end_reason, y.end_reason);
    EXPECT_EQ(x.t, y.t);
    EXPECT_EQ(x.t_los_s, y.t_los_s);
    EXPECT_EQ(x.t_cpa_s, y.t_cpa_s);
    EXPECT_EQ(x.cpa_h_m, y.cpa_h_m);
    EXPECT_EQ(x.cpa_v_ft, y.cpa_v_ft);
    EXPECT_EQ(x.sep_h_m, y.sep_h_m);
    EXPECT_EQ(x.hypothesis, y.hypothesis);
    EXPECT_EQ(x.region, y.region);
    expect_same_party(x.a, y.a);
    expect_same_party(x.b, y.b);
    if (::testing::Test::HasFailure()) return;
  }
}

class ProbeEquivalence : public ::testing::TestWithParam<replay::Scenario> {};

TEST_P(ProbeEquivalence, ExactEqualsBruteEventForEvent) {
  replay::GeneratorConfig traffic;
  traffic.scenario = GetParam();
  traffic.aircraft = 2000;
  traffic.duration_s = 90.0;
  traffic.seed = 20261122;
  traffic.position_noise_m = 30.0;
  traffic.missed_update_probability = 0.05;
  traffic.radius_km = 500.0;
  const RunResult exact = run(traffic, probe::ProbeMode::Exact, 50.0);
  const RunResult brute = run(traffic, probe::ProbeMode::Brute, 50.0);
  expect_identical(exact.events, brute.events);
  std::size_t opened = 0;
  for (const AlertEvent& e : exact.events) opened += e.state == AlertState::New;
  EXPECT_GE(opened, 5u) << "the scenario must exercise the probe";
  EXPECT_EQ(exact.audit_violations, 0u);
  // The exact probe evaluates far fewer pairs than brute force.
  EXPECT_LT(exact.candidates * 4, brute.candidates);
  RecordProperty("alerts_opened", static_cast<int>(opened));
}

INSTANTIATE_TEST_SUITE_P(Scenarios, ProbeEquivalence,
                         ::testing::Values(replay::Scenario::Random, replay::Scenario::Airways,
                                           replay::Scenario::Stacks, replay::Scenario::Tma,
                                           replay::Scenario::Mixed),
                         [](const auto& param_info) { return std::string(replay::to_string(param_info.param)); });

TEST(ProbeEquivalence, RelativeToleranceAndStrictZeroTolerance) {
  // τ = 0 (every update reinserts) and the thesis' relative τ keep the equivalence.
  replay::GeneratorConfig traffic;
  traffic.scenario = replay::Scenario::Mixed;
  traffic.aircraft = 1000;
  traffic.duration_s = 100.0;
  traffic.seed = 7;
  traffic.radius_km = 200.0;
  expect_identical(run(traffic, probe::ProbeMode::Exact, 0.0).events,
                   run(traffic, probe::ProbeMode::Brute, 0.0).events);
  const auto relative = kinetic::ToleranceMode::Relative;
  expect_identical(run(traffic, probe::ProbeMode::Exact, 2e-4, relative).events,
                   run(traffic, probe::ProbeMode::Brute, 2e-4, relative).events);
}

// Gives generated traffic what real feeds have and every rule of design §4.5 reads:
// addresses and Mode 3/A codes, test transponders (7777), coasting, slow targets, one
// aircraft seen twice (a second source with the same address, or the same discrete code
// without addresses), aircraft reported 25 ft off their level (so level pairs read
// 975 ft apart), traffic below the lower limit and absurd vertical rates (dropped
// fields).
void with_every_rule(const TrackReport& in, std::vector<TrackReport>& out) {
  std::uint32_t h = 2166136261u;
  for (const char c : in.id) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  TrackReport r = in;
  r.address = h & 0xFFFFFF;
  r.mode3a = static_cast<std::uint16_t>(h % 4096u);
  if (h % 11 == 0) r.mode3a = 07777;
  if (h % 7 == 0) r.coasting = static_cast<long long>(r.t / 20.0) % 2 == 1;
  if (h % 19 == 0 && r.gs_kt) *r.gs_kt = 20.0;
  if (h % 3 == 0) r.alt_ft -= 25.0;
  if (h % 4 == 1) r.alt_ft = 500.0 + r.alt_ft / 100.0;  // aerodrome traffic below the lower limit
  if (h % 17 == 0) r.vr_fpm = -165100.0;
  out.push_back(r);
  if (h % 5 == 0) {
    // A second sensor: 150 m north, the same address (or, one time in two, no address
    // but the same discrete code), half a second later.
    TrackReport twin = r;
    twin.source = "second";
    twin.t += 0.5;
    twin.lat_deg += 150.0 / 111200.0;
    if (h % 10 == 0) {
      twin.address.reset();
      out.back().address.reset();
      twin.mode3a = out.back().mode3a = static_cast<std::uint16_t>(01234 + h % 512u);
    }
    out.push_back(twin);
  }
}

// Two minutes of mixed traffic through the exact probe and brute force, with `edit` and
// `configure`: the events and suppressions must be identical. Returns the exact run.
RunResult expect_exact_equals_brute(std::size_t aircraft, double radius_km, std::uint64_t seed, Edit edit,
                                    Configure configure = nullptr) {
  replay::GeneratorConfig traffic;
  traffic.scenario = replay::Scenario::Mixed;
  traffic.aircraft = aircraft;
  traffic.duration_s = 120.0;
  traffic.seed = seed;
  traffic.radius_km = radius_km;
  const RunResult exact =
      run(traffic, probe::ProbeMode::Exact, 50.0, kinetic::ToleranceMode::Absolute, edit, configure);
  const RunResult brute =
      run(traffic, probe::ProbeMode::Brute, 50.0, kinetic::ToleranceMode::Absolute, edit, configure);
  expect_identical(exact.events, brute.events);
  EXPECT_EQ(exact.suppressed, brute.suppressed);
  return exact;
}

TEST(ProbeEquivalence, ExactEqualsBruteWithEveryRuleOn) {
  const RunResult exact = expect_exact_equals_brute(1500, 300.0, 17, with_every_rule);
  std::size_t opened = 0;
  for (const AlertEvent& e : exact.events) opened += e.state == AlertState::New;
  EXPECT_GE(opened, 5u) << "the scenario must exercise the probe";
  // Every rule has turned conflicts clear, so the equivalence covers each.
  for (const char* rule :
       {"same_aircraft", "level_pair", "adjacent_level_off", "slow", "excluded_code", "coasting", "below_lower_limit",
        "first_records"})
    EXPECT_GT(exact.suppressed.count(rule) ? exact.suppressed.at(rule) : 0u, 0u) << rule;
  EXPECT_GT(exact.fields_dropped, 0u);
  EXPECT_EQ(exact.audit_violations, 0u);
}

// Selected altitudes on most climbing and descending aircraft (the next thousand feet
// but one in the direction of motion, so that the level-off is within the look-ahead),
// and a reported rate of turn on one aircraft in five.
void with_intent_and_turns(const TrackReport& in, std::vector<TrackReport>& out) {
  out.push_back(in);
  TrackReport& r = out.back();
  const std::uint32_t h = static_cast<std::uint32_t>(std::hash<std::string>{}(r.id));
  if (r.vr_fpm && std::abs(*r.vr_fpm) > 300.0 && h % 4 != 0) {
    const double step = *r.vr_fpm > 0.0 ? 1000.0 : -1000.0;
    r.sel_ft = (std::round(r.alt_ft / 1000.0) + 2.0 * (step > 0.0 ? 1.0 : -1.0)) * 1000.0;
    r.sel_src = h % 2 ? SelectedAltitudeSource::Mcp : SelectedAltitudeSource::Fms;
  }
  if (h % 5 == 0) r.tar_dps = (h % 2 ? 1.0 : -1.0) * (1.0 + (h >> 8) % 3);
}

// A terminal area with smaller minima, a longer look-ahead and its own confirm/clear,
// and an inhibition volume overlapping its edge (design §4.8).
void with_regions_and_turns(PipelineConfig& config) {
  config.turn.enabled = true;
  region::Region tma;
  tma.name = "tma";
  tma.center = {50.0, 8.0};
  tma.radius_m = 120e3;
  tma.ceiling_ft = 24500.0;
  tma.parameters.horizontal_m = 3.0 * 1852.0;
  tma.parameters.lookahead_s = 300.0;  // the search radius must grow for it
  tma.parameters.warning_s = 40.0;
  tma.parameters.confirm = 1;
  tma.parameters.clear = 2;
  region::Region inhibited;
  inhibited.name = "aerodrome";
  inhibited.polygon = {{50.6, 7.5}, {51.4, 7.6}, {51.3, 8.9}, {50.7, 8.6}};
  inhibited.inhibit = true;
  config.regions = {inhibited, tma};
}

TEST(ProbeEquivalence, ExactEqualsBruteWithRegionsIntentAndTurns) {
  const RunResult exact = expect_exact_equals_brute(600, 200.0, 19, with_intent_and_turns, with_regions_and_turns);
  // Every hypothesis and both regions took part, so the equivalence covers each.
  std::map<Hypothesis, int> by_hypothesis;
  std::map<std::string, int> by_region;
  for (const AlertEvent& e : exact.events) {
    ++by_hypothesis[e.hypothesis];
    ++by_region[e.region];
  }
  for (const Hypothesis h : {Hypothesis::Linear, Hypothesis::LevelOff, Hypothesis::Turn, Hypothesis::Proximity})
    EXPECT_GT(by_hypothesis[h], 0) << to_string(h);
  EXPECT_GT(by_region["tma"], 0);
  EXPECT_GT(by_region[""], 0);
  EXPECT_GT(exact.suppressed.count("inhibited") ? exact.suppressed.at("inhibited") : 0u, 0u);
  EXPECT_EQ(exact.audit_violations, 0u);
}

// Memory order (design §8.3): the engine rebuilt in Hilbert order every 8 s, with the
// probe states moved to the new points, changes no event and no suppression, with every
// rule, both regions, vertical intent and turns on.
TEST(ProbeEquivalence, RenumberingChangesNoEvent) {
  replay::GeneratorConfig traffic;
  traffic.scenario = replay::Scenario::Mixed;
  traffic.aircraft = 1200;
  traffic.duration_s = 120.0;
  traffic.seed = 23;
  traffic.radius_km = 250.0;
  const Configure renumbered = [](PipelineConfig& config) {
    with_regions_and_turns(config);
    config.renumber_every_s = 8.0;
  };
  const auto edit = [](const TrackReport& in, std::vector<TrackReport>& out) {
    std::vector<TrackReport> ruled;
    with_every_rule(in, ruled);
    for (const TrackReport& r : ruled) with_intent_and_turns(r, out);
  };
  const RunResult brute =
      run(traffic, probe::ProbeMode::Brute, 50.0, kinetic::ToleranceMode::Absolute, edit, with_regions_and_turns);
  for (const probe::ProbeMode mode : {probe::ProbeMode::Exact, probe::ProbeMode::Brute}) {
    SCOPED_TRACE(std::string(probe::to_string(mode)));
    const RunResult ordered = run(traffic, mode, 50.0, kinetic::ToleranceMode::Absolute, edit, renumbered);
    EXPECT_GE(ordered.renumberings, 13u);
    expect_identical(ordered.events, brute.events);
    EXPECT_EQ(ordered.suppressed, brute.suppressed);
    EXPECT_EQ(ordered.audit_violations, 0u);
  }
  std::size_t opened = 0;
  for (const AlertEvent& e : brute.events) opened += e.state == AlertState::New;
  EXPECT_GE(opened, 5u) << "the scenario must exercise the probe";
  EXPECT_EQ(brute.renumberings, 0u);
}

}  // namespace
}  // namespace kew
