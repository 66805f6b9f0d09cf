// STCA filters (design §4.4, §4.8): vertical intent from the selected altitude,
// parameter regions and inhibition volumes, and the turn hypothesis.
#include "kew/pipeline/pipeline.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/track/vertical_intent.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "scripted_flight.hpp"

namespace kew {
namespace {

using test_support::Flight;
using test_support::fly;
using test_support::kT0;

// ---- update_intent: when the selection may stop the prediction --------------------

struct IntentStep {
  double t;
  std::optional<double> sel_ft;
  double alt_ft;
  double vr_fpm;
  std::optional<double> expected;  // level-off altitude, or none (linear)
};

std::vector<std::optional<double>> run_intent(const std::vector<IntentStep>& steps) {
  track::IntentState state;
  const track::IntentConfig config;
  std::vector<std::optional<double>> out;
  for (const IntentStep& s : steps)
    out.push_back(track::update_intent(state, config, s.t, s.sel_ft, SelectedAltitudeSource::Mcp, s.alt_ft, s.vr_fpm));
  return out;
}

struct IntentCase {
  const char* name;
  std::vector<IntentStep> steps;
};

TEST(VerticalIntent, FollowsTheRulesOfDesign4_4) {
  const std::vector<IntentCase> cases = {
      {"climbing towards the selection levels off there",
       {{0, 34000, 30000, 2000, 34000}, {4, std::nullopt, 30130, 2000, 34000}}},
      {"descending towards it too", {{0, 20000, 24000, -1500, 20000}}},
      {"moving away from it: linear", {{0, 34000, 36000, 1000, std::nullopt}}},
      {"level: linear (nothing to stop)", {{0, 34000, 30000, 0, std::nullopt}}},
      {"older than 20 s: forgotten",
       {{0, 34000, 30000, 2000, 34000}, {20, std::nullopt, 30660, 2000, 34000}, {21, std::nullopt, 30700, 2000, std::nullopt}}},
      {"a fresh report renews it", {{0, 34000, 30000, 2000, 34000}, {25, 34000, 30830, 2000, 34000}}},
      {"more than 200 ft past: busted, linear until the selection changes",
       {{0, 34000, 33000, 2000, 34000},
        {4, 34000, 34250, 2000, std::nullopt},
        {8, 34000, 34100, -1000, std::nullopt},
        {12, 35000, 34100, 1000, 35000}}},
      {"within 200 ft past and coming back: trusted",
       {{0, 34000, 33000, 2000, 34000}, {4, 34000, 34150, -500, 34000}}},
      {"in the capture band with the rate falling: trusted",
       {{0, 34000, 33100, 3000, 34000}, {4, 34000, 33700, 1500, 34000}, {8, 34000, 33900, 600, 34000}}},
      // 3,000 ft/min needs 777 ft to stop at 0.05 g: 300 ft short, still at full rate.
      {"in the capture band, too close to stop, rate not falling: linear",
       {{0, 34000, 33100, 3000, 34000}, {4, 34000, 33700, 3000, std::nullopt}}},
      // 1,000 ft/min needs 86 ft: at 600 ft, a capture need not have begun.
      {"in the capture band, far enough to stop: trusted", {{0, 34000, 33400, 1000, 34000}}},
  };
  for (const IntentCase& c : cases) {
    SCOPED_TRACE(c.name);
    const std::vector<std::optional<double>> got = run_intent(c.steps);
    for (std::size_t i = 0; i < c.steps.size(); ++i) EXPECT_EQ(got[i], c.steps[i].expected) << "step " << i;
  }
}

// ---- the level-off prediction in the conflict test ---------------------------------

// A climber from 32,600 ft at 1,500 ft/min to FL340 (rate falling over its last 300 ft)
// meets level traffic at FL350 head-on; `with_selection` reports the selected altitude.
std::vector<Flight> climb_below_traffic(bool with_selection) {
  Flight climber{"CLIMB"};
  climber.east_m = -12.0 * 1852.0;
  climber.alt_ft = 32600.0;
  climber.edit = [with_selection](TrackReport& r) {
    const double s = r.t - kT0;
    const double capture_from = (33700.0 - 32600.0) / 1500.0 * 60.0;  // 44 s
    if (s <= capture_from) {
      r.alt_ft = 32600.0 + 1500.0 * s / 60.0;
      r.vr_fpm = 1500.0;
    } else {  // the rate falls linearly to 0 over 24 s: 300 ft
      const double u = std::min(s - capture_from, 24.0);
      r.alt_ft = std::round(33700.0 + (1500.0 * u - 1500.0 * u * u / 48.0) / 60.0);
      r.vr_fpm = 1500.0 * (1.0 - u / 24.0);
    }
    if (with_selection) r.sel_ft = 34000.0;
  };
  Flight traffic{"LEVEL"};
  traffic.east_m = 12.0 * 1852.0;
  traffic.trk_deg = 270.0;
  return {climber, traffic};
}

TEST(VerticalIntent, AClimbToTheLevelBelowTrafficRaisesNoAlertWithItsSelection) {
  const auto with = fly(climb_below_traffic(true), 100.0);
  EXPECT_EQ(with.opened(), 0u);
  // Without a selection the adjacent-level presumption (design §4.5) would keep it quiet
  // too; switched off, the prediction is linear.
  PipelineConfig linear;
  linear.eligibility.adjacent_level_off = false;
  const auto without = fly(climb_below_traffic(false), 100.0, linear);
  EXPECT_EQ(without.opened(), 1u) << "the same climb predicted linearly";
}

TEST(AdjacentLevelOff, AClimbToTheLevelBelowTrafficWithoutASelectionRaisesNoAlert) {
  // opensky switzerland, jade-cat062-ff: feeds without selected altitudes, where climbs
  // and descents to the level next to traffic were half of the nuisance alerts.
  const auto run = fly(climb_below_traffic(false), 100.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("adjacent_level_off"), 0u);
}

TEST(AdjacentLevelOff, AClimbThroughTheLevelBelowTrafficAlertsTwentySecondsAhead) {
  // The same climber without a selection climbs on at 1,500 ft/min through FL340 into
  // the traffic at FL350: 800 ft apart at 64 s, 5 NM apart at 76 s, the loss. It can
  // stop at FL340 (194 ft at 0.05 g) until 33,806 ft, 48 s; then the test is linear.
  std::vector<Flight> flights = climb_below_traffic(false);
  flights[0].vr_fpm = 1500.0;
  flights[0].edit = {};
  const auto run = fly(flights, 100.0);
  ASSERT_EQ(run.opened(), 1u);
  const double loss_t = kT0 + 76.0;
  EXPECT_LE(run.first_opened_t(), loss_t - 20.0);
  PipelineConfig linear;
  linear.eligibility.adjacent_level_off = false;
  const auto without = fly(flights, 100.0, linear);
  ASSERT_EQ(without.opened(), 1u);
  EXPECT_LT(without.first_opened_t(), run.first_opened_t()) << "the presumption costs warning time, and only so much";
}

TEST(VerticalIntent, ABustOfTheSelectionStillAlerts) {
  // The climber selected FL340 but climbs on through it at 1,500 ft/min.
  std::vector<Flight> flights = climb_below_traffic(true);
  flights[0].vr_fpm = 1500.0;
  flights[0].edit = [](TrackReport& r) { r.sel_ft = 34000.0; };
  const auto run = fly(flights, 100.0);
  ASSERT_EQ(run.opened(), 1u);
  EXPECT_EQ(run.events.front().hypothesis, Hypothesis::Linear);
}

TEST(VerticalIntent, ALevelOffIntoTrafficIsNamed) {
  // Selected FL350, where the traffic is: the level-off itself is the conflict.
  std::vector<Flight> flights = climb_below_traffic(false);
  flights[0].edit = [](TrackReport& r) {
    r.alt_ft = 33000.0 + 1500.0 * (r.t - kT0) / 60.0;
    r.vr_fpm = 1500.0;
    r.sel_ft = 35000.0;
  };
  const auto run = fly(flights, 60.0);
  ASSERT_GE(run.opened(), 1u);
  EXPECT_EQ(run.events.front().hypothesis, Hypothesis::LevelOff);
}

TEST(VerticalIntent, PiecewiseWindowMatchesSampling) {
  // The closed-form window with level-offs against a 10 ms sampling of both distances.
  probe::SeparationMinima m;
  std::uint32_t seed = 7;
  const auto uniform = [&seed](double lo, double hi) {
    seed = seed * 1664525u + 1013904223u;
    return lo + (hi - lo) * (seed >> 8) / double(1u << 24);
  };
  int conflicts = 0;
  for (int i = 0; i < 400; ++i) {
    probe::Kinematics a, b;
    a.position = {0.0, 0.0};
    b.position = {uniform(-20e3, 20e3), uniform(-20e3, 20e3)};
    a.velocity = {uniform(-250, 250), uniform(-250, 250)};
    b.velocity = {uniform(-250, 250), uniform(-250, 250)};
    a.altitude_m = uniform(9000, 11000);
    b.altitude_m = uniform(9000, 11000);
    a.vertical_rate_mps = uniform(-15, 15);
    b.vertical_rate_mps = uniform(-15, 15);
    a.level_off_m = a.altitude_m + a.vertical_rate_mps * uniform(1, 100);
    if (i % 3 == 0) b.level_off_m = b.altitude_m + b.vertical_rate_mps * uniform(1, 100);
    const probe::ConflictGeometry g = probe::evaluate_pair(a, b, m);
    EXPECT_EQ(g.in_conflict, probe::in_conflict(a, b, m));
    conflicts += g.in_conflict;
    if (!g.in_conflict || g.lost_now) continue;
    // Inside the window (away from its ends) both distances are below the minima.
    for (double s = g.t_los_s + 0.01; s < g.t_end_s - 0.01; s += 0.5) {
      const probe::Kinematics pa = probe::extrapolated(a, s), pb = probe::extrapolated(b, s);
      EXPECT_LT(geometry::norm(pb.position - pa.position), m.horizontal_m) << i << " at " << s;
      EXPECT_LT(std::abs(pb.altitude_m - pa.altitude_m), m.vertical_m) << i << " at " << s;
    }
  }
  EXPECT_GT(conflicts, 20);
}

// ---- parameter regions and inhibition volumes --------------------------------------

// Two aircraft at FL300 on parallel opposite tracks 4 NM apart: in conflict under 5 NM,
// clear under a terminal area's 3 NM.
std::vector<Flight> passing_4nm() {
  Flight a{"A"};
  a.east_m = -15.0 * 1852.0;
  a.alt_ft = 30000.0;
  Flight b{"B"};
  b.east_m = 15.0 * 1852.0;
  b.north_m = 4.0 * 1852.0;
  b.trk_deg = 270.0;
  b.alt_ft = 30000.0;
  return {a, b};
}

region::Region terminal_area(double center_lat) {
  region::Region r;
  r.name = "tma";
  r.center = {center_lat, 8.0};
  r.radius_m = 40.0 * 1852.0;
  r.ceiling_ft = 24500.0 + 10000.0;
  r.parameters.horizontal_m = 3.0 * 1852.0;
  return r;
}

TEST(Regions, ARegionsMinimaApplyInsideItAndNotOutside) {
  PipelineConfig inside;
  inside.regions = {terminal_area(50.0)};
  EXPECT_EQ(fly(passing_4nm(), 60.0, inside).opened(), 0u);
  PipelineConfig elsewhere;
  elsewhere.regions = {terminal_area(52.0)};
  const auto outside = fly(passing_4nm(), 60.0, elsewhere);
  ASSERT_EQ(outside.opened(), 1u);
  EXPECT_EQ(outside.events.front().region, "");
  PipelineConfig below;  // the same area, but the pair flies above its ceiling
  below.regions = {terminal_area(50.0)};
  below.regions[0].ceiling_ft = 25000.0;
  EXPECT_EQ(fly(passing_4nm(), 60.0, below).opened(), 1u);
}

TEST(Regions, AnAlertNamesTheRegionThatJudgedIt) {
  PipelineConfig config;
  config.regions = {terminal_area(50.0)};
  config.regions[0].parameters.horizontal_m = 5.0 * 1852.0;
  config.regions[0].parameters.confirm = 1;
  const auto run = fly(passing_4nm(), 60.0, config);
  ASSERT_EQ(run.opened(), 1u);
  EXPECT_EQ(run.events.front().region, "tma");
}

TEST(Regions, AnAircraftOnEachSideTakesTheStricterParameters) {
  // A is inside a 3 NM area whose edge the pair crosses, B outside: 5 NM applies.
  PipelineConfig config;
  region::Region half;
  half.name = "west";
  half.polygon = {{49.0, 6.0}, {51.0, 6.0}, {51.0, 8.0}, {49.0, 8.0}};
  half.parameters.horizontal_m = 3.0 * 1852.0;
  config.regions = {half};
  std::vector<Flight> flights = passing_4nm();
  for (Flight& f : flights) f.gs_kt = 150.0;  // slow: in 60 s A stays west of 8° E, B east
  flights[0].east_m = -5.0 * 1852.0;
  flights[1].east_m = 5.0 * 1852.0;
  EXPECT_EQ(fly(flights, 60.0, config).opened(), 1u);
  config.regions[0].polygon = {{49.0, 6.0}, {51.0, 6.0}, {51.0, 10.0}, {49.0, 10.0}};  // both inside
  EXPECT_EQ(fly(flights, 60.0, config).opened(), 0u);
}

TEST(Regions, AnInhibitionVolumeSuppresses) {
  PipelineConfig config;
  region::Region aerodrome;
  aerodrome.name = "aerodrome";
  aerodrome.center = {50.0, 8.0};
  aerodrome.radius_m = 30.0 * 1852.0;
  aerodrome.inhibit = true;
  config.regions = {aerodrome};
  const auto run = fly(passing_4nm(), 60.0, config);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("inhibited"), 0u);
}

// ---- the turn hypothesis ------------------------------------------------------------

// A (450 kt, north) turns right through 180° at 2°/s (90 s), ending 2R = 13.3 km east
// of its start heading south, into B, which flies north on that line (250 kt) and is
// there when the turn ends. Straight ahead, A and B never come within 5 NM.
std::vector<Flight> reversal_into_traffic() {
  Flight a{"TURN"};
  a.gs_kt = 450.0;
  a.trk_deg = 0.0;
  a.turn_dps = 2.0;
  a.turn_s = 90.0;
  a.alt_ft = 20000.0;
  a.edit = [](TrackReport& r) {
    if (r.t - kT0 < 90.0) r.tar_dps = 2.0;
  };
  const double diameter_m = 2.0 * 450.0 * test_support::kKnot / (2.0 * M_PI / 180.0);
  Flight b{"TRAFFIC"};
  b.gs_kt = 250.0;
  b.trk_deg = 0.0;
  b.east_m = diameter_m;
  b.north_m = -250.0 * test_support::kKnot * 90.0;
  b.alt_ft = 20000.0;
  return {a, b};
}

TEST(TurnHypothesis, FindsA180DegreeTurnConflict30SecondsEarlier) {
  PipelineConfig linear;
  const auto straight = fly(reversal_into_traffic(), 100.0, linear);
  PipelineConfig turning;
  turning.turn.enabled = true;
  const auto turn = fly(reversal_into_traffic(), 100.0, turning);
  ASSERT_GE(straight.opened(), 1u);
  ASSERT_GE(turn.opened(), 1u);
  EXPECT_LE(turn.first_opened_t() + 30.0, straight.first_opened_t())
      << "turn " << turn.first_opened_t() - kT0 << " s, linear " << straight.first_opened_t() - kT0 << " s";
  EXPECT_EQ(turn.events.front().hypothesis, Hypothesis::Turn);
}

TEST(TurnHypothesis, OffByDefault) {
  EXPECT_FALSE(PipelineConfig{}.turn.enabled);
}

TEST(TurnHypothesis, ArcPositionsFollowTheTurn) {
  probe::Kinematics k;
  k.velocity = {0.0, 100.0};        // north at 100 m/s
  k.turn_rate_rps = -M_PI / 60.0;  // clockwise, 180° in 60 s
  const geometry::Point2 half = probe::position_along_turn(k, 60.0);
  const double radius = 100.0 / (M_PI / 60.0);
  EXPECT_NEAR(half.x, 2.0 * radius, 1e-6);
  EXPECT_NEAR(half.y, 0.0, 1e-6);
  const geometry::Point2 quarter = probe::position_along_turn(k, 30.0);
  EXPECT_NEAR(quarter.x, radius, 1e-6);
  EXPECT_NEAR(quarter.y, radius, 1e-6);
}

}  // namespace
}  // namespace kew
