// Who may alert (design §4.5): one aircraft seen as two tracks never alerts
// against itself, targets that are not airborne aircraft open no alert, level pairs at
// adjacent levels are separated, and every suppression is counted by rule.
#include "kew/eligibility/eligibility.hpp"
#include "kew/pipeline/pipeline.hpp"

#include <gtest/gtest.h>

#include "scripted_flight.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace kew {
namespace {

using test_support::Flight;
using test_support::head_on;
using test_support::fly;
using test_support::kT0;
using test_support::Outcome;

TEST(Eligibility, AHeadOnPairAtOneLevelAlerts) {
  EXPECT_EQ(fly(head_on()).opened(), 1u);
}

TEST(Eligibility, SlowTargetsOpenNoAlert) {
  // Stationary test targets at FL250, 2 NM apart: in conflict, but not aircraft.
  std::vector<Flight> targets = head_on(25000.0, 25000.0);
  targets[0].east_m = -1852.0;
  targets[1].east_m = 1852.0;
  for (Flight& f : targets) f.gs_kt = 5.0;
  const Outcome run = fly(targets, 40.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("slow"), 0u);
  for (Flight& f : targets) f.gs_kt = 60.0;
  EXPECT_EQ(fly(targets).opened(), 1u);
}

TEST(Eligibility, NoAlertOpensBelowTheLowerLimit) {
  const Outcome run = fly(head_on(1000.0, 1200.0), 40.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("below_lower_limit"), 0u);
  EXPECT_EQ(fly(head_on(2000.0, 2200.0)).opened(), 1u);
  PipelineConfig disabled;
  disabled.eligibility.lower_limit_ft = 0.0;
  disabled.eligibility.aerodrome_height_ft = 0.0;
  EXPECT_EQ(fly(head_on(1000.0, 1200.0), 40.0, disabled).opened(), 1u);
}

// Granada (LEGA), 2,297 ft above the sea: terminal traffic 8 NM apart head-on at 200 kt,
// centred on the aerodrome, loses separation 27 s after the first records.
std::vector<Flight> over_granada(double alt_ft) {
  std::vector<Flight> pair = head_on(alt_ft, alt_ft);
  for (Flight& f : pair) {
    f.lat0_deg = 37.1332;
    f.lon0_deg = -3.6357;
    f.gs_kt = 200.0;
    f.east_m = f.east_m / 10.0 * 4.0;  // ±4 NM
  }
  return pair;
}

// The pipeline's defaults with Granada as the one aerodrome (its row of data/aerodromes.csv).
PipelineConfig with_granada() {
  PipelineConfig config;
  config.eligibility.aerodromes = std::make_shared<const eligibility::AerodromeTable>(
      std::vector<eligibility::Aerodrome>{{"LEGA", 37.1332, -3.6357, 2297}});
  return config;
}

TEST(Eligibility, TheLowerLimitStandsAboveTheNearestAerodrome) {
  // 3,500 ft is 1,200 ft above Granada: above its aerodrome traffic, alerted as early as
  // the same geometry at FL200 far from any aerodrome.
  const Outcome terminal = fly(over_granada(3500.0), 60.0, with_granada());
  std::vector<Flight> en_route = over_granada(20000.0);
  for (Flight& f : en_route) {
    f.lat0_deg = 50.0;
    f.lon0_deg = 8.0;
  }
  const Outcome high = fly(en_route, 60.0, with_granada());
  ASSERT_EQ(terminal.opened(), 1u);
  ASSERT_EQ(high.opened(), 1u);
  EXPECT_EQ(terminal.first_opened_t(), high.first_opened_t());
  // The second look once both were seen twice (no addresses: first_records, design §4.5).
  EXPECT_EQ(terminal.first_opened_t(), kT0 + 8.0);
  // 3,000 ft there is 700 ft above the runway, in the circuit: no alert, though it is
  // 1,500 ft above the sea.
  const Outcome circuit = fly(over_granada(3000.0), 60.0, with_granada());
  EXPECT_EQ(circuit.opened(), 0u);
  EXPECT_GT(circuit.pipeline->suppressed().count("below_lower_limit"), 0u);
  EXPECT_DOUBLE_EQ(circuit.pipeline->config().eligibility.aerodrome_height_ft, 1000.0);
  // The height switched off, or no table: 1,500 ft above the sea is the only limit.
  PipelineConfig sea_level = with_granada();
  sea_level.eligibility.aerodrome_height_ft = 0.0;
  EXPECT_EQ(fly(over_granada(3000.0), 60.0, sea_level).opened(), 1u);
  EXPECT_EQ(fly(over_granada(3000.0), 60.0, PipelineConfig{}).opened(), 1u);
}

TEST(Eligibility, AltitudesOutsideTheBandAreNotAircraft) {
  const Outcome run = fly(head_on(71900.0, 71900.0), 40.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("altitude_band"), 0u);
}

TEST(Eligibility, Code7777OpensNoAlertButEmergencyCodesAlwaysAlert) {
  std::vector<Flight> pair = head_on();
  pair[0].edit = [](TrackReport& r) { r.mode3a = 07777; };
  const Outcome run = fly(pair, 40.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("excluded_code"), 0u);
  // 7700 listed by a program (the configuration refuses it) still alerts.
  PipelineConfig config;
  config.eligibility.excluded_mode3a = {07700, 07777};
  pair[0].edit = [](TrackReport& r) { r.mode3a = 07700; };
  EXPECT_EQ(fly(pair, 40.0, config).opened(), 1u);
}

TEST(Eligibility, CoastingTracksOpenNoAlertButAnOpenAlertStaysOpen) {
  std::vector<Flight> pair = head_on();
  pair[0].edit = [](TrackReport& r) { r.coasting = true; };
  const Outcome run = fly(pair, 40.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("coasting"), 0u);
  // Coasting from 20 s on, after the alert opened: it stays open, no End.
  pair[0].edit = [](TrackReport& r) { r.coasting = r.t >= kT0 + 20.0; };
  const Outcome later = fly(pair, 40.0);
  EXPECT_EQ(later.opened(), 1u);
  for (const AlertEvent& e : later.events) EXPECT_NE(e.state, AlertState::End);
}

TEST(Eligibility, AStaleTrackOpensNoAlert) {
  // B reports once, then nothing: 24 s later A still predicts a conflict with B's
  // extrapolation, but B's position is older than max_position_age_s (20 s).
  std::vector<Flight> pair = head_on();
  PipelineConfig config;
  config.eligibility.max_position_age_s = 6.0;
  Pipeline pipeline(config);
  std::vector<AlertEvent> events;
  pipeline.set_alert_sink([&](const AlertEvent& e) { events.push_back(e); });
  pipeline.process(pair[0].at(kT0));
  pipeline.process(pair[1].at(kT0));
  for (double dt = 8.0; dt < 28.0; dt += 4.0) pipeline.process(pair[0].at(kT0 + dt));
  EXPECT_TRUE(events.empty());
  EXPECT_GT(pipeline.suppressed().count("position_stale"), 0u);
}

TEST(Eligibility, LevelPairsAtAdjacentLevelsAreSeparated) {
  // FL370 and FL380 reported 975 ft apart: separated. 700 ft apart: a conflict.
  const Outcome run = fly(head_on(37000.0, 37975.0), 40.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("level_pair"), 0u);
  EXPECT_EQ(fly(head_on(37000.0, 37700.0)).opened(), 1u);
  // A climbing aircraft 975 ft below is judged as before.
  std::vector<Flight> climbing = head_on(37000.0, 37975.0);
  climbing[0].vr_fpm = 1000.0;
  EXPECT_EQ(fly(climbing).opened(), 1u);
  PipelineConfig disabled;
  disabled.eligibility.level_rate_fpm = 0.0;
  EXPECT_EQ(fly(head_on(37000.0, 37975.0), 40.0, disabled).opened(), 1u);
}

TEST(Eligibility, FlightLevelsExactly1000FtApartAreSeparated) {
  // jade 14:45:52Z: a new track at FL340 whose first records carry no vertical rate (so
  // no level-pair rule) met an aircraft level at FL350; 35,000 − 34,000 ft converted to
  // metres reads a hair under 1,000 ft, the pair was "within S_v" and alerted. The same
  // rounding kept a pair exactly 1,000 ft apart and slowly diverging "within S_v" for the
  // whole look-ahead (grid_20250602 19:29:10Z, an alert of severity loss).
  // As on jade, the level aircraft reports first in each scan, so the pair is evaluated
  // twice while the new track has only one record and no rate.
  std::vector<Flight> unknown_rate = head_on(34000.0, 35000.0);
  std::swap(unknown_rate[0], unknown_rate[1]);
  unknown_rate[1].edit = [](TrackReport& r) { r.vr_fpm.reset(); };
  EXPECT_EQ(fly(unknown_rate).opened(), 0u);
  std::vector<Flight> diverging = head_on(34000.0, 35000.0);
  diverging[1].vr_fpm = 64.0;
  EXPECT_EQ(fly(diverging).opened(), 0u);
  // A real loss still alerts, with or without a rate.
  std::vector<Flight> loss = head_on(34000.0, 34700.0);
  EXPECT_EQ(fly(loss).opened(), 1u);
  loss[0].edit = [](TrackReport& r) { r.vr_fpm.reset(); };
  EXPECT_EQ(fly(loss).opened(), 1u);
}

TEST(Eligibility, OneAircraftSeenByTwoSourcesNeverAlertsAgainstItself) {
  // The same aircraft from radar and ADS-B, 200 m apart: the same address.
  Flight radar{"1234", "cat062/25.100"};
  radar.edit = [](TrackReport& r) { r.address = 0x4CA123; };
  Flight adsb{"4CA123", "sbs"};
  adsb.north_m = 200.0;
  adsb.edit = radar.edit;
  const Outcome run = fly({radar, adsb}, 40.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GT(run.pipeline->suppressed().count("same_aircraft"), 0u);
  // Two different addresses are never one aircraft, whatever their codes.
  adsb.edit = [](TrackReport& r) { r.address = 0x4CA124; r.mode3a = 04711; };
  radar.edit = [](TrackReport& r) { r.address = 0x4CA123; r.mode3a = 04711; };
  EXPECT_EQ(fly({radar, adsb}).opened(), 1u);
}

TEST(Eligibility, TheSameDiscreteCodeOnCoincidingTracksIsOneAircraft) {
  Flight radar{"1234", "cat062/25.100"};
  Flight other{"0077", "cat062/25.101"};
  other.north_m = 500.0;
  other.alt_ft = 35200.0;
  radar.edit = other.edit = [](TrackReport& r) { r.mode3a = 04711; };
  EXPECT_EQ(fly({radar, other}).opened(), 0u);
  // Conspicuity codes are shared by many aircraft: not identity.
  radar.edit = other.edit = [](TrackReport& r) { r.mode3a = 07000; };
  EXPECT_EQ(fly({radar, other}).opened(), 1u);
  radar.edit = other.edit = [](TrackReport& r) { r.mode3a = 07700; };
  EXPECT_EQ(fly({radar, other}).opened(), 1u);
  // The rule switched off (same_code_distance_nm = 0): two aircraft.
  PipelineConfig off;
  off.eligibility.same_code_distance_nm = 0.0;
  radar.edit = other.edit = [](TrackReport& r) { r.mode3a = 04711; };
  EXPECT_EQ(fly({radar, other}, 40.0, off).opened(), 1u);
  // One code, 500 m apart, but crossing: the velocities say two aircraft (a duplicated
  // code), and so does a speed 40 kt apart.
  Flight crossing = other;
  crossing.trk_deg = 120.0;
  EXPECT_EQ(fly({radar, crossing}).opened(), 1u);
  Flight faster = other;
  faster.gs_kt = radar.gs_kt + 40.0;
  EXPECT_EQ(fly({radar, faster}).opened(), 1u);
  // The same discrete code 3 NM apart: two aircraft.
  other.north_m = 3.0 * 1852.0;
  EXPECT_EQ(fly({radar, other}).opened(), 1u);
}

TEST(Eligibility, AFormationAlertsHoweverCloseAndAlikeItFlies) {
  // Two aircraft 0.2 NM apart at one level, one speed and heading, for two minutes: the
  // most dangerous pair there is. Closeness is no evidence of one aircraft.
  Flight lead{"4CA123", "adsb"};
  Flight wing{"4CA124", "adsb"};
  wing.east_m = 0.2 * 1852.0;
  lead.edit = [](TrackReport& r) { r.address = 0x4CA123; };
  wing.edit = [](TrackReport& r) { r.address = 0x4CA124; };
  EXPECT_EQ(fly({lead, wing}, 120.0).opened(), 1u);
  // Two radar tracks without addresses or codes, as close and alike: two aircraft too.
  lead.edit = wing.edit = [](TrackReport&) {};
  EXPECT_EQ(fly({lead, wing}, 120.0).opened(), 1u);
  // The same, both squawking one code but one address between them: the code and the
  // coincidence make them one aircraft; with two addresses they are two whatever the code.
  lead.edit = [](TrackReport& r) { r.mode3a = 04711; r.address = 0x4CA123; };
  wing.edit = [](TrackReport& r) { r.mode3a = 04711; };
  EXPECT_EQ(fly({lead, wing}, 120.0).opened(), 0u);
  wing.edit = [](TrackReport& r) { r.mode3a = 04711; r.address = 0x4CA124; };
  EXPECT_EQ(fly({lead, wing}, 120.0).opened(), 1u);
}

TEST(Eligibility, OneAircraftSeenAsTwoTracksForAMinuteDoesNotAlert) {
  // Radar and ADS-B tracks of one aircraft (one address) 0.1 NM and 50 ft apart for 60 s.
  Flight radar{"1234", "cat062/25.100"};
  Flight adsb{"4CA123", "adsb"};
  adsb.east_m = 0.1 * 1852.0;
  adsb.alt_ft = radar.alt_ft + 50.0;
  radar.edit = adsb.edit = [](TrackReport& r) { r.address = 0x4CA123; };
  const Outcome run = fly({radar, adsb}, 60.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_GE(run.pipeline->suppressed().count("same_aircraft"), 15u);  // every evaluation of 60 s
}

TEST(Eligibility, ADuplicatedCodeNeverEndsAnOpenAlert) {
  // Two aircraft squawking one code (a code duplication) head-on: the alert opens while
  // they are far apart and must stay open as they come within 1 NM and 500 ft.
  std::vector<Flight> pair = head_on();
  pair[0].edit = pair[1].edit = [](TrackReport& r) { r.mode3a = 04711; };
  const Outcome run = fly(pair, 88.0);  // they pass each other at 80 s
  EXPECT_EQ(run.opened(), 1u);
  for (const AlertEvent& e : run.events) {
    if (e.t < kT0 + 80.0) {
      EXPECT_NE(e.state, AlertState::End) << e.t - kT0;
    }
  }
}

TEST(Eligibility, AReusedTrackNumberForgetsTheOldAircraftsAddress) {
  // Track 17 was aircraft 4CA1B2; the number is reused 80 NM away by an aircraft without
  // an address (the jump resets the velocity). The new one must not be "one aircraft"
  // with 4CA1B2, still seen by ADS-B.
  Flight old_aircraft{"17", "cat062/25.100"};
  old_aircraft.edit = [](TrackReport& r) { r.address = 0x4CA1B2; };
  Pipeline pipeline;
  pipeline.process(old_aircraft.at(kT0));
  pipeline.process(old_aircraft.at(kT0 + 4.0));
  Flight reused{"17", "cat062/25.100"};
  reused.east_m = 80.0 * 1852.0;
  reused.edit = [](TrackReport& r) {  // positions only: the jump is seen when deriving
    r.gs_kt.reset();
    r.trk_deg.reset();
  };
  pipeline.process(reused.at(kT0 + 8.0));
  const track::Track& track = pipeline.tracks()[pipeline.tracks().find("cat062/25.100", "17")];
  EXPECT_FALSE(track.address.has_value());
  EXPECT_EQ(pipeline.tracks().velocity_resets(), 1u);
}

TEST(Eligibility, OneTrackStaysOneTrackWithAndWithoutAnAddress) {
  // A CAT062 track whose I062/380 comes and goes: one track, no alert against itself.
  Flight track{"1234", "cat062/25.100"};
  track.edit = [](TrackReport& r) {
    if (static_cast<int>(r.t - kT0) % 8 == 0) r.address = 0x4CA123;
  };
  const Outcome run = fly({track}, 40.0);
  EXPECT_EQ(run.opened(), 0u);
  EXPECT_EQ(run.pipeline->tracks().size(), 1u);
  EXPECT_EQ(run.pipeline->statistics().tracks_restarted, 0u);
}

TEST(Eligibility, AnotherAddressOnTheSameIdStartsANewTrack) {
  std::vector<Flight> pair = head_on();
  pair[0].edit = [](TrackReport& r) { r.address = r.t < kT0 + 20.0 ? 0x4CA123 : 0x3C6543; };
  const Outcome run = fly(pair, 40.0);
  EXPECT_EQ(run.pipeline->statistics().tracks_restarted, 1u);
  // The alert of the first aircraft ended when its track was replaced; a new one opened.
  ASSERT_GE(run.opened(), 2u);
  bool ended = false;
  for (const AlertEvent& e : run.events) ended |= e.end_reason == AlertEndReason::TrackDropped;
  EXPECT_TRUE(ended);
}

TEST(Eligibility, TheSourceEndingATrackEndsIt) {
  std::vector<Flight> pair = head_on();
  pair[0].edit = [](TrackReport& r) { r.track_end = r.t >= kT0 + 20.0; };
  const Outcome run = fly(pair, 24.0);
  EXPECT_EQ(run.pipeline->statistics().tracks_ended, 1u);
  ASSERT_FALSE(run.events.empty());
  EXPECT_EQ(run.events.back().state, AlertState::End);
  EXPECT_EQ(run.events.back().end_reason, AlertEndReason::TrackDropped);
  EXPECT_EQ(run.pipeline->tracks().size(), 1u);
}

TEST(Eligibility, AnUnknownVerticalRateIsNotLevel) {
  // grid_20250602 (readsb): a climbing aircraft's first record had no vertical rate, so it
  // read 0 ft/min and its pair 975 ft apart was taken for a level pair; the alert opened
  // after the loss had begun.
  eligibility::Rules rules({}, probe::SeparationMinima{});
  track::Track a, b;
  a.alt_ft = 3625.0;
  b.alt_ft = 4600.0;
  a.vertical_rate_known = b.vertical_rate_known = true;
  EXPECT_TRUE(rules.level_pair(a, b));
  a.vertical_rate_known = false;
  EXPECT_FALSE(rules.level_pair(a, b));
}

TEST(Eligibility, SlowDriftsTowardsEachOtherAreNotALevelPair) {
  // 850 ft apart, each "level" at 290 ft/min towards the other: 580 ft/min closing, 560 ft
  // apart after T_v = 30 s. Not at adjacent levels for long: judged by the conflict test.
  eligibility::Rules rules({}, probe::SeparationMinima{});
  track::Track a, b;
  a.alt_ft = 35000.0;
  b.alt_ft = 35850.0;
  a.vertical_rate_known = b.vertical_rate_known = true;
  EXPECT_TRUE(rules.level_pair(a, b));
  a.vr_fpm = 290.0;
  b.vr_fpm = -290.0;
  EXPECT_FALSE(rules.level_pair(a, b));
  // Drifting apart is still a level pair.
  a.vr_fpm = -290.0;
  b.vr_fpm = 290.0;
  EXPECT_TRUE(rules.level_pair(a, b));
}

// Track a at alt_a_ft with a rate derived from one 25 ft step (vr_fpm), b level at alt_b_ft.
std::pair<track::Track, track::Track> one_step_apart(double alt_a_ft, double alt_b_ft, double vr_fpm) {
  track::Track a, b;
  a.alt_ft = alt_a_ft;
  b.alt_ft = alt_b_ft;
  a.vertical_rate_known = b.vertical_rate_known = true;
  a.vertical_rate_derived = true;
  a.altitude_step_ft = 25.0;
  a.vr_fpm = vr_fpm;
  return {a, b};
}

TEST(Eligibility, OneAltitudeStepBetweenRadarRecordsIsLevel) {
  // upc-bcn-cat048: CAT048 carries no vertical rate; one 25 ft step in a 4 s scan derives
  // 375 ft/min, and level aircraft at FL360 and FL370 (975 ft apart) alerted.
  eligibility::Rules rules({}, probe::SeparationMinima{});
  auto [a, b] = one_step_apart(36025.0, 37000.0, 375.0);
  EXPECT_TRUE(rules.level_pair(a, b));
  // The same step in one second is a 1,500 ft/min climb.
  a.vr_fpm = 1500.0;
  EXPECT_FALSE(rules.level_pair(a, b));
  // Two steps in 4 s: 750 ft/min.
  a.altitude_step_ft = 50.0;
  a.vr_fpm = 750.0;
  EXPECT_FALSE(rules.level_pair(a, b));
  // A reported 375 ft/min is a climb (the threshold is 300).
  a.vertical_rate_derived = false;
  a.altitude_step_ft = 0.0;
  a.vr_fpm = 375.0;
  EXPECT_FALSE(rules.level_pair(a, b));
}

TEST(Eligibility, OneStepEveryScanTheSameWayIsADescentNotLevel) {
  // upc-bcn-cat048 08:07–08:11Z: VLG4LY descending in trail 825–900 ft below KLM97C, one
  // 25 ft step a scan, read as level: its alert ended and reopened five times, and its
  // loss was warned 36 s ahead instead of 2 minutes.
  std::vector<Flight> trail = head_on(4150.0, 3300.0);
  trail[0].vr_fpm = -375.0;  // 25 ft every 4 s, towards B
  for (Flight& f : trail) f.edit = [](TrackReport& r) { r.vr_fpm.reset(); };
  const Outcome run = fly(trail, 60.0);
  EXPECT_EQ(run.opened(), 1u);
  // Only at its first step, which one record cannot tell from quantisation.
  EXPECT_LE(run.pipeline->suppressed().count("level_pair"), 1u);
  // The rule on its own: the step before went the same way.
  eligibility::Rules rules({}, probe::SeparationMinima{});
  auto [a, b] = one_step_apart(4125.0, 3300.0, -375.0);
  a.altitude_change_ft = -25.0;
  EXPECT_TRUE(rules.level_pair(a, b));
  a.altitude_moving_one_way = true;
  EXPECT_FALSE(rules.level_pair(a, b));
}

struct AdjacentLevelCase {
  const char* name;
  double mover_alt_ft, mover_vr_fpm;
  double level_alt_ft, level_vr_fpm;
  bool expected;
  double mover_age_s = 0.0;  // the mover's last record this long before the evaluation
};

TEST(Eligibility, AdjacentLevelOffFollowsDesign4_5) {
  // Level traffic at FL360 (or FL350); stopping distances at 0.05 g: 110 ft at 1,088
  // ft/min, 80 ft at 960, 497 ft at 2,400 (design §4.5).
  const AdjacentLevelCase cases[] = {
      {"can stop at FL350 (switzerland 06:13:30Z)", 34750.0, 1088.0, 36000.0, 0.0, true},
      {"too close to stop short of FL350", 34925.0, 960.0, 36000.0, 0.0, false},
      {"2,400 ft/min 200 ft below FL350 (jade 14:51:36Z)", 34800.0, 2400.0, 36000.0, 0.0, false},
      {"descending to FL370 above FL360", 37250.0, -1152.0, 36000.0, 0.0, true},
      {"moving away from the level one", 34750.0, -1088.0, 36000.0, 0.0, false},
      {"neither level", 34750.0, 1088.0, 36000.0, -1000.0, false},
      {"both level: the level-pair rule's", 34750.0, 100.0, 36000.0, 0.0, false},
      {"the mover's last record 10 s old: now 181 ft higher", 34750.0, 1088.0, 36000.0, 0.0, false, 10.0},
      {"the level one drifts 290 ft/min down: still 995 ft after T_v", 34750.0, 1088.0, 36000.0, -290.0, true},
      {"1,500 ft/min 2,000 ft below: can stop at FL350", 34000.0, 1500.0, 36000.0, 0.0, true},
      {"1,600 ft/min: faster than ICAO's 1,500 near traffic", 34000.0, 1600.0, 36000.0, 0.0, false},
      {"traffic at 5,000 ft, below FL100: visual rules, no clearance", 3750.0, 1088.0, 5000.0, 0.0, false},
      {"traffic at FL100", 8750.0, 1088.0, 10000.0, 0.0, true},
  };
  eligibility::Rules rules({}, probe::SeparationMinima{});
  const double now = 1000.0;
  for (const AdjacentLevelCase& c : cases) {
    SCOPED_TRACE(c.name);
    track::Track mover, level;
    mover.alt_ft = c.mover_alt_ft;
    mover.vr_fpm = c.mover_vr_fpm;
    mover.t = now - c.mover_age_s;
    level.alt_ft = c.level_alt_ft;
    level.vr_fpm = c.level_vr_fpm;
    level.t = now;
    mover.vertical_rate_known = level.vertical_rate_known = true;
    EXPECT_EQ(rules.adjacent_level_off(mover, level, now), c.expected);
    EXPECT_EQ(rules.adjacent_level_off(level, mover, now), c.expected) << "either order";
  }
}

TEST(Eligibility, AdjacentLevelOffNeedsAKnownRateNoSelectionAndTheRuleOn) {
  eligibility::Rules rules({}, probe::SeparationMinima{});
  track::Track mover, level;
  mover.alt_ft = 34750.0;
  mover.vr_fpm = 1088.0;
  level.alt_ft = 36000.0;
  mover.vertical_rate_known = level.vertical_rate_known = true;
  ASSERT_TRUE(rules.adjacent_level_off(mover, level, 0.0));
  // The mover's own selection decides where it stops (the probe's intent, design §4.4).
  mover.intent.sel_ft = 36000.0;
  EXPECT_FALSE(rules.adjacent_level_off(mover, level, 0.0));
  mover.intent.sel_ft.reset();
  level.vertical_rate_known = false;
  EXPECT_FALSE(rules.adjacent_level_off(mover, level, 0.0)) << "0 ft/min that nothing reported is not level";
  level.vertical_rate_known = true;
  eligibility::EligibilityConfig off;
  off.adjacent_level_off = false;
  EXPECT_FALSE(eligibility::Rules(off, probe::SeparationMinima{}).adjacent_level_off(mover, level, 0.0));
  // A long vertical look-ahead lets the level one's drift of 290 ft/min bring it within
  // S_v less the tolerance: 1,140 − 580 = 560 ft after 120 s.
  probe::SeparationMinima long_look;
  long_look.vertical_lookahead_s = 120.0;
  level.vr_fpm = -290.0;
  EXPECT_FALSE(eligibility::Rules({}, long_look).adjacent_level_off(mover, level, 0.0));
}

TEST(Eligibility, ATrackWithoutAnAddressOpensNoAlertOnItsFirstRecord) {
  eligibility::Rules rules({}, probe::SeparationMinima{});
  track::Track t;
  t.alt_ft = 36000.0;
  t.gs_kt = 440.0;
  t.records = 1;
  EXPECT_EQ(rules.exclusion(t, 0.0), eligibility::Exclusion::FirstRecords);
  t.records = 2;
  EXPECT_EQ(rules.exclusion(t, 0.0), eligibility::Exclusion::None);
  // An address is the aircraft's own report: one record of it is an aircraft.
  t.records = 1;
  t.address = 0x4CA1B2;
  EXPECT_EQ(rules.exclusion(t, 0.0), eligibility::Exclusion::None);
  t.address.reset();
  eligibility::EligibilityConfig once;
  once.min_records = 1;
  EXPECT_EQ(eligibility::Rules(once, probe::SeparationMinima{}).exclusion(t, 0.0), eligibility::Exclusion::None);
}

// jade-cat062-ff 14:46Z: a CAT062 duplicate of track 286 (same code, 4 NM away, one level)
// lived for one record; the next frame's record of 286 confirmed a loss against its
// extrapolation, and the source's end of the duplicate, one frame later, ended it.
std::vector<AlertEvent> duplicate_for_one_record(const PipelineConfig& config) {
  Flight real{"286", "cat062/70.16"};
  real.trk_deg = 270.0;
  Flight duplicate{"890", "cat062/70.16"};
  duplicate.trk_deg = 267.0;
  duplicate.north_m = 4.0 * 1852.0;
  for (Flight* f : {&real, &duplicate}) f->edit = [](TrackReport& r) { r.mode3a = 06010; };
  std::vector<AlertEvent> events;
  Pipeline pipeline(config);
  pipeline.set_alert_sink([&events](const AlertEvent& e) { events.push_back(e); });
  pipeline.process(real.at(kT0 - 5.0));
  pipeline.process(real.at(kT0));
  pipeline.process(duplicate.at(kT0));
  pipeline.process(real.at(kT0 + 5.0));
  TrackReport end = duplicate.at(kT0);
  end.track_end = true;
  pipeline.process(end);
  pipeline.set_alert_sink({});
  return events;
}

TEST(Eligibility, ATrackersDuplicateForOneRecordOpensNoAlert) {
  EXPECT_TRUE(duplicate_for_one_record({}).empty());
  PipelineConfig once;
  once.eligibility.min_records = 1;
  EXPECT_FALSE(duplicate_for_one_record(once).empty()) << "without the rule it alerts";
}

TEST(Eligibility, ARefusedLastRecordStillEndsTheTrack) {
  Flight a{"1234", "cat062/25.100"};
  Pipeline pipeline;
  pipeline.process(a.at(kT0));
  pipeline.process(a.at(kT0 + 4.0));
  TrackReport last = a.at(kT0 + 4.0);  // the same time again: refused as duplicate_time
  last.track_end = true;
  pipeline.process(last);
  EXPECT_EQ(pipeline.rejections().count("duplicate_time"), 1u);
  EXPECT_EQ(pipeline.statistics().tracks_ended, 1u);
  EXPECT_EQ(pipeline.tracks().size(), 0u);
}

TEST(Eligibility, ARefusedRecordWithAnotherAddressKeepsTheOldTrack) {
  Flight a{"17", "cat062/25.100"};
  a.edit = [](TrackReport& r) { r.address = 0x4CA1B2; };
  PipelineConfig limited;  // worldwide zones with an explicit coverage limit
  limited.coverage_radius_m = 1.5e6;
  Pipeline pipeline(limited);
  pipeline.process(a.at(kT0));
  pipeline.process(a.at(kT0 + 4.0));
  TrackReport far = a.at(kT0 + 8.0);  // outside the 1,500 km coverage
  far.address = 0x3C6543;
  far.lat_deg = -40.0;
  pipeline.process(far);
  EXPECT_EQ(pipeline.rejections().count("outside_coverage"), 1u);
  EXPECT_EQ(pipeline.statistics().tracks_restarted, 0u);
  ASSERT_NE(pipeline.tracks().find("cat062/25.100", "17"), track::kNoTrack);
  EXPECT_EQ(pipeline.live_tracks(), 1u);
}

TEST(Eligibility, RulesOnTheirOwn) {
  eligibility::Rules rules({}, probe::SeparationMinima{});
  track::Track t;
  t.records = 2;  // seen twice: first_records has its own test
  t.alt_ft = 35000.0;
  t.gs_kt = 450.0;
  t.t = 100.0;
  EXPECT_EQ(rules.exclusion(t, 110.0), eligibility::Exclusion::None);
  EXPECT_EQ(rules.exclusion(t, 121.0), eligibility::Exclusion::PositionStale);
  t.gs_kt = 49.0;
  EXPECT_EQ(rules.exclusion(t, 110.0), eligibility::Exclusion::Slow);
  EXPECT_FALSE(eligibility::may_exclude_mode3a(07500));
  EXPECT_FALSE(eligibility::may_exclude_mode3a(07600));
  EXPECT_FALSE(eligibility::may_exclude_mode3a(07700));
  EXPECT_TRUE(eligibility::may_exclude_mode3a(07777));
  for (const int code : {01000, 01200, 02000, 07000, 07500, 07600, 07700})
    EXPECT_FALSE(eligibility::is_discrete_mode3a(static_cast<std::uint16_t>(code))) << code;
  EXPECT_TRUE(eligibility::is_discrete_mode3a(04711));
  EXPECT_EQ(eligibility::kExclusionNames.parse("below_lower_limit"), eligibility::Exclusion::BelowLowerLimit);
}

}  // namespace
}  // namespace kew
