// Kinetic detection (design §2.7): the prototype LookaheadPairs gives,
// at every update, candidates among which the conflict test finds exactly the pairs brute
// force finds: on the generated scenarios, on aircraft stacked at one position on
// several levels, on one airway flown at three levels in both directions, and on exact
// duplicates (twins of the q-triangulation).
#include "lookahead_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kew/geo/projection.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/replay/traffic_generator.hpp"
#include "kew/track/track_table.hpp"

namespace kew {
namespace {

using geometry::Point2;
using geometry::Vector2;
using probe::Kinematics;
using Key = testing::LookaheadPairs::Key;

/// One update as the probe sees it: the track's kinematics at time t.
struct Update {
  double t = 0.0;
  Key key = 0;
  bool drop = false;
  Kinematics state;
};

struct Comparison {
  std::uint64_t updates = 0;
  std::uint64_t conflicts = 0;  // pairs in conflict at updates, by brute force
  std::uint64_t missed = 0;     // of those, not among the prototype's candidates
  std::uint64_t extra = 0;      // candidates reported twice (none allowed)
  std::uint64_t invalid_checks = 0;
  std::uint64_t twins_made = 0;  // by the q-triangulation
  testing::LookaheadPairsStatistics statistics;
};

/// Feeds the updates to LookaheadPairs and, at each, compares the conflicts among its
/// candidates with those among every live track (brute force).
Comparison compare(const std::vector<Update>& updates, const probe::SeparationMinima& minima, double v_max,
                   double tolerance_m) {
  testing::LookaheadPairsConfig config;
  config.separation_m = minima.horizontal_m;
  config.lookahead_s = minima.lookahead_s;
  config.tolerance_m = tolerance_m;
  config.keep_s = 10.0;
  config.max_speed_mps = v_max;
  config.kinetic = PipelineConfig{}.kinetic;
  const double epoch = updates.empty() ? 0.0 : std::floor(updates.front().t);
  testing::LookaheadPairs pairs(config, 0.0);
  std::vector<Kinematics> state;  // at state_t
  std::vector<double> state_t;
  std::vector<std::uint8_t> live;
  std::vector<Key> live_keys;
  Comparison out;
  std::vector<std::uint32_t> seen;  // candidate marks, by key
  std::uint32_t round = 0;
  double next_check = epoch + 30.0;
  const auto at = [&](Key k, double t) { return probe::extrapolated(state[k], t - state_t[k]); };
  for (const Update& u : updates) {
    if (u.key >= state.size()) {
      state.resize(u.key + 1);
      state_t.resize(u.key + 1, 0.0);
      live.resize(u.key + 1, 0);
      seen.resize(u.key + 1, 0);
    }
    if (u.drop) {
      pairs.remove(u.key, u.t - epoch);
      if (live[u.key]) live_keys.erase(std::find(live_keys.begin(), live_keys.end(), u.key));
      live[u.key] = 0;
      continue;
    }
    if (!live[u.key]) live_keys.push_back(u.key);
    live[u.key] = 1;
    state[u.key] = u.state;
    state_t[u.key] = u.t;
    pairs.report(u.key, u.t - epoch, u.state.position, u.state.velocity);
    ++out.updates;
    ++round;
    const Kinematics self = u.state;
    const auto conflicting = [&](Key other) {
      const Kinematics them = at(other, u.t);
      return u.key < other ? probe::in_conflict(self, them, minima) : probe::in_conflict(them, self, minima);
    };
    pairs.for_each_candidate(u.key, [&](Key other) {
      if (seen[other] == round) ++out.extra;
      seen[other] = round;
    });
    for (const Key other : live_keys) {
      if (other == u.key || !conflicting(other)) continue;
      ++out.conflicts;
      if (seen[other] != round) ++out.missed;
    }
    if (u.t >= next_check) {
      out.invalid_checks += pairs.is_valid() ? 0 : 1;
      next_check += 30.0;
    }
  }
  out.statistics = pairs.statistics();
  out.twins_made = pairs.triangulation_statistics().twins_created;
  return out;
}

/// Generated traffic through the track table, as the Pipeline applies it.
std::vector<Update> generated(replay::Scenario scenario, std::size_t aircraft, double& v_max) {
  replay::GeneratorConfig traffic;
  traffic.scenario = scenario;
  traffic.aircraft = aircraft;
  traffic.duration_s = 100.0;
  traffic.seed = 20261202;
  traffic.position_noise_m = 30.0;
  traffic.missed_update_probability = 0.05;
  traffic.termination_probability_per_hour = 30.0;  // tracks leave, slots are reused
  traffic.radius_km = 300.0;
  replay::TrafficGenerator generator(traffic);
  PipelineConfig config;
  const geo::Projection projection(geo::GeodeticPosition{traffic.center_lat_deg, traffic.center_lon_deg}, 1.5e6);
  track::TrackTable table(config.tracks);
  std::vector<Update> out;
  std::vector<std::uint8_t> in;
  double clock = 0.0;
  v_max = 0.0;
  for (TrackReport r; generator.next(r);) {
    if (table.plausibility_problem(r) != kew::track::Refusal::None) continue;
    clock = std::max(clock, r.t);
    table.expire(clock, [&](track::TrackSlot slot, const track::Track&) {
      if (slot < in.size() && in[slot]) out.push_back({clock, slot, true, {}});
      if (slot < in.size()) in[slot] = 0;
    });
    const track::AdmitResult admitted = table.admit(r, clock, projection);
    if (admitted.admission == track::Admission::Rejected) continue;
    if (admitted.slot >= in.size()) in.resize(admitted.slot + 1, 0);
    if (admitted.admission == track::Admission::AwaitingVelocity) {
      if (in[admitted.slot]) out.push_back({clock, admitted.slot, true, {}});
      in[admitted.slot] = 0;
      continue;
    }
    const track::Track& track = table[admitted.slot];
    in[admitted.slot] = 1;
    out.push_back({clock, admitted.slot, false, probe::extrapolated(track.kinematics, clock - track.t)});
    v_max = std::max(v_max, geometry::norm(track.kinematics.velocity));
  }
  return out;
}

class LookaheadPairsEquivalence : public ::testing::TestWithParam<replay::Scenario> {};

TEST_P(LookaheadPairsEquivalence, FindsEveryConflictBruteForceFinds) {
  double v_max = 0.0;
  const std::vector<Update> updates = generated(GetParam(), 800, v_max);
  const probe::SeparationMinima minima;
  for (const double tolerance : {0.0, 1000.0}) {
    const Comparison c = compare(updates, minima, v_max, tolerance);
    SCOPED_TRACE("tolerance " + std::to_string(tolerance));
    EXPECT_EQ(c.missed, 0u) << "of " << c.conflicts;
    EXPECT_EQ(c.extra, 0u);
    EXPECT_EQ(c.invalid_checks, 0u);
    EXPECT_GE(c.conflicts, 20u) << "the scenario must exercise the detection";
    EXPECT_GT(c.statistics.entries, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenarios, LookaheadPairsEquivalence,
                         ::testing::Values(replay::Scenario::Random, replay::Scenario::Airways,
                                           replay::Scenario::Stacks, replay::Scenario::Tma,
                                           replay::Scenario::Mixed, replay::Scenario::Calibrated),
                         [](const auto& param_info) { return std::string(replay::to_string(param_info.param)); });

/// Hand-built traffic in the plane: reports every 4 s with noise, from `start(k)` moving
/// at `velocity(k)`; aircraft k at `altitude(k)`.
template <class Start, class Velocity, class Altitude>
std::vector<Update> flown(std::size_t aircraft, double duration_s, Start start, Velocity velocity, Altitude altitude,
                          std::uint64_t seed, std::size_t noise_free = 0) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> noise(0.0, 30.0), speed_noise(0.0, 2.0);
  std::uniform_real_distribution<double> jitter(0.0, 4.0);
  std::vector<double> phase(aircraft);
  for (double& p : phase) p = jitter(random);
  std::vector<Update> out;
  for (double t = 0.0; t < duration_s; t += 4.0)
    for (std::size_t k = 0; k < aircraft; ++k) {
      const double at = t + phase[k];
      Update u;
      u.t = 1.0e6 + at;  // reports in time order within each 4 s scan (phases sorted below)
      u.key = static_cast<Key>(k);
      u.state.position = start(k) + at * velocity(k);
      u.state.velocity = velocity(k);
      if (k >= noise_free) {  // the first `noise_free` aircraft report their exact paths
        u.state.position = u.state.position + Vector2{noise(random), noise(random)};
        u.state.velocity = u.state.velocity + Vector2{speed_noise(random), speed_noise(random)};
      }
      u.state.altitude_m = altitude(k);
      out.push_back(u);
    }
  std::stable_sort(out.begin(), out.end(), [](const Update& a, const Update& b) { return a.t < b.t; });
  return out;
}

TEST(LookaheadPairs, StackedLevelsAtOnePosition) {
  // Twelve aircraft over one point, 1,000 ft apart, each on its own heading, and twelve
  // more flying through the column: the pairs in H all share partners (the Gabriel gap
  // is everywhere), and the column's q-points nearly coincide.
  const probe::SeparationMinima minima;
  const auto start = [](std::size_t k) {
    if (k < 12) return Point2{0.0, 0.0};
    const double a = 0.5 * static_cast<double>(k);
    return Point2{60e3 * std::cos(a), 60e3 * std::sin(a)};
  };
  const auto velocity = [](std::size_t k) {
    if (k < 12) {
      const double a = 0.3 * static_cast<double>(k);
      return Vector2{60.0 * std::cos(a), 60.0 * std::sin(a)};  // slow: holding speeds
    }
    const double a = 0.5 * static_cast<double>(k);
    return Vector2{-220.0 * std::cos(a), -220.0 * std::sin(a)};
  };
  const auto altitude = [](std::size_t k) { return 3000.0 + 304.8 * static_cast<double>(k % 12); };
  const Comparison c = compare(flown(24, 400.0, start, velocity, altitude, 7), minima, 250.0, 1000.0);
  EXPECT_EQ(c.missed, 0u) << "of " << c.conflicts;
  EXPECT_EQ(c.extra, 0u);
  EXPECT_EQ(c.invalid_checks, 0u);
  EXPECT_GE(c.conflicts, 20u);
  EXPECT_GT(c.statistics.two_hop_considered, 0u);
}

TEST(LookaheadPairs, OneAirwayAtThreeLevelsBothWays) {
  // Forty aircraft on one straight airway, 15 km in trail: eastbound at FL350 and FL370
  // (some overtaking), westbound at FL360; a few climb through the others' levels.
  const probe::SeparationMinima minima;
  const auto start = [](std::size_t k) { return Point2{15e3 * static_cast<double>(k) - 300e3, 0.0}; };
  const auto velocity = [](std::size_t k) {
    const double speed = 220.0 + 3.0 * static_cast<double>(k % 7);
    return Vector2{k % 3 == 2 ? -speed : speed, 0.0};
  };
  const auto altitude = [](std::size_t k) { return 0.3048 * (k % 3 == 0 ? 35000.0 : k % 3 == 1 ? 37000.0 : 36000.0); };
  std::vector<Update> updates = flown(40, 600.0, start, velocity, altitude, 11);
  for (Update& u : updates)
    if (u.key % 10 == 4) {  // climbing through the levels above
      u.state.vertical_rate_mps = 8.0;
      u.state.altitude_m += 8.0 * (u.t - 1.0e6);
    }
  const Comparison c = compare(updates, minima, 250.0, 1000.0);
  EXPECT_EQ(c.missed, 0u) << "of " << c.conflicts;
  EXPECT_EQ(c.extra, 0u);
  EXPECT_EQ(c.invalid_checks, 0u);
  EXPECT_GE(c.conflicts, 20u);
}

TEST(LookaheadPairs, ExactDuplicatesAreTestedAsTwins) {
  // Six aircraft on one exact path at six levels (one q-point: the q-triangulation keeps
  // five as twins of the sixth) and twenty crossing them.
  const probe::SeparationMinima minima;
  const auto start = [](std::size_t k) {
    if (k < 6) return Point2{-40e3, 0.0};
    const double a = 0.7 * static_cast<double>(k);
    return Point2{50e3 * std::cos(a), 50e3 * std::sin(a)};
  };
  const auto velocity = [](std::size_t k) {
    if (k < 6) return Vector2{200.0, 0.0};
    const double a = 0.7 * static_cast<double>(k);
    return Vector2{-180.0 * std::cos(a), -180.0 * std::sin(a)};
  };
  const auto altitude = [](std::size_t k) { return 0.3048 * (30000.0 + 1000.0 * static_cast<double>(k % 6)); };
  const Comparison c = compare(flown(26, 400.0, start, velocity, altitude, 5, 6), minima, 250.0, 1000.0);
  EXPECT_GE(c.twins_made, 5u);
  EXPECT_EQ(c.missed, 0u) << "of " << c.conflicts;
  EXPECT_EQ(c.extra, 0u);
  EXPECT_EQ(c.invalid_checks, 0u);
  EXPECT_GE(c.conflicts, 20u);
}

}  // namespace
}  // namespace kew
