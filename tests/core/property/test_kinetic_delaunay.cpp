// Property tests of the kinetic Delaunay triangulation: random and adversarial motions,
// checked at many random times against CGAL's static triangulation of the same
// positions, with is_valid() and an exact audit that must find nothing to repair.
//
// Every scenario draws from a fixed seed, so a run is reproducible. To explore other
// seeds, set KEW_PROPERTY_SEED=<n> (n ≥ 0; unset or 0: the committed seeds); every
// scenario then draws from a different, equally reproducible stream.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <numbers>
#include <random>

#include "delaunay_oracle.hpp"
#include "kew/kinetic/kinetic_delaunay.hpp"

namespace kew::kinetic {
namespace {

using geometry::Point2;
using geometry::Vector2;

/// Totals over the whole suite, checked by the last test.
struct SuiteTotals {
  std::uint64_t events_executed = 0;
  std::uint64_t audits = 0;
  std::uint64_t unrepaired = 0;
  std::uint64_t oracle_comparisons = 0;
  std::uint64_t kept_updates = 0;        // kept models: the lag check above covers them
  std::uint64_t drift_reinsertions = 0;  // and their deadlines
};
SuiteTotals& totals() {
  static SuiteTotals t;
  return t;
}

/// Added to every scenario's seed: KEW_PROPERTY_SEED × a large prime, 0 when unset.
std::uint64_t seed_offset() {
  const char* value = std::getenv("KEW_PROPERTY_SEED");
  return value ? std::strtoull(value, nullptr, 10) * 1'000'003ull : 0ull;
}

struct Aircraft {
  PointId id = kNoPoint;
  Point2 position;  // true position at `time`
  Vector2 velocity;
  double time = 0.0;
  Point2 reported;  // the latest report's position, with its noise
  // When the engine took it: `time`, or the engine's clock when checks ran ahead of the
  // report (update() applies a report at max(t, now())).
  double reported_time = 0.0;
};

/// Drives an engine through a scenario and checks it at random times.
class Harness {
 public:
  Harness(const KineticConfig& config, std::uint64_t seed) : engine_(config, 0.0), rng_(seed + seed_offset()) {}

  PointId add(Point2 p, Vector2 v, double t) {
    Aircraft a{engine_.insert(t, p, v), p, v, t, p, engine_.now()};
    aircraft_.push_back(a);
    return a.id;
  }

  /// Moves each aircraft along its (possibly changed) velocity and reports it, in a
  /// random order spread over one period, with optional position noise.
  void radar_period(double start, double period, double noise_m,
                    const std::function<Vector2(const Aircraft&, std::mt19937_64&)>& steer) {
    std::vector<std::size_t> order(aircraft_.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::shuffle(order.begin(), order.end(), rng_);
    std::normal_distribution<double> noise(0.0, noise_m);
    for (std::size_t n = 0; n < order.size(); ++n) {
      Aircraft& a = aircraft_[order[n]];
      const double t = start + period * static_cast<double>(n) / static_cast<double>(order.size());
      a.position = a.position + (t - a.time) * a.velocity;
      a.time = t;
      a.velocity = steer(a, rng_);
      const Point2 measured = noise_m > 0 ? Point2{a.position.x + noise(rng_), a.position.y + noise(rng_)} : a.position;
      a.reported = measured;
      // A report dated before the engine's now (a check ran past the period's start) is
      // applied at now: the engine takes times t ≥ now() only.
      a.reported_time = std::max(t, engine_.now());
      engine_.update(a.id, a.reported_time, measured, a.velocity);
    }
  }

  /// Advances to t and checks, without letting anything repair first, that the kinetic
  /// maintenance alone left a valid triangulation (is_valid() and an exact audit that
  /// finds nothing), then (in general position) the edge set against CGAL.
  void check_at(double t, bool compare_with_oracle = true) {
    t = std::max(t, engine_.now());  // a check dated before the period's last report: at it
    engine_.advance(t);
    // The probe's search relies on it (design §2.1, §2.3): no model lags its latest
    // report by more than τ (velocity-only updates, kept models and their deadlines).
    const double tau = engine_.config().tolerance;
    for (const Aircraft& a : aircraft_) {
      if (!engine_.contains(a.id)) continue;
      const Point2 report_now = a.reported + (engine_.now() - a.reported_time) * a.velocity;
      ASSERT_LE(geometry::norm(engine_.position_now(a.id) - report_now), tau + 1e-6 * (1.0 + tau))
          << "point " << a.id << " at t=" << t;
    }
    const auto report = engine_.triangulation().audit();
    ASSERT_TRUE(engine_.is_valid()) << "at t=" << t << ": tds " << static_cast<int>(engine_.triangulation().tds().check())
                                    << ", inverted " << report.inverted_faces << ", non-Delaunay "
                                    << report.non_delaunay_edges << " early " << engine_.statistics().events_early
                                    << " tangencies " << engine_.statistics().tangencies_ignored << " repairs "
                                    << engine_.statistics().repairs << " rebuilds " << engine_.statistics().rebuilds
                                    << " twins " << engine_.statistics().twins_created;
    EXPECT_EQ(report.violations(), 0u) << "kinetic maintenance left a defect at t=" << t
                                        << " (inverted " << report.inverted_faces << ", non-Delaunay "
                                        << report.non_delaunay_edges << ")";
    const KineticAudit audit = engine_.audit_and_repair();
    ++totals().audits;
    totals().unrepaired += audit.violations_unrepaired;
    EXPECT_EQ(audit.violations_unrepaired, 0u);
    if (!compare_with_oracle) return;
    std::vector<std::pair<std::uint32_t, Point2>> points;
    std::vector<Point2> raw;
    for (const Aircraft& a : aircraft_) {
      if (!engine_.contains(a.id) || engine_.host_of(a.id) != a.id) return;  // twins: no unique DT
      points.emplace_back(a.id, engine_.position_now(a.id));
      raw.push_back(points.back().second);
    }
    if (raw.size() < 3 || !testing::in_general_position(raw)) return;
    ++totals().oracle_comparisons;
    EXPECT_EQ(engine_.edges(), testing::cgal_delaunay_edges(points)) << "edge sets differ at t=" << t;
  }

  void finish() {
    totals().events_executed += engine_.statistics().events_executed;
    totals().kept_updates += engine_.statistics().kept_updates;
    totals().drift_reinsertions += engine_.statistics().drift_reinsertions;
  }

  KineticDelaunay& engine() { return engine_; }
  std::vector<Aircraft>& aircraft() { return aircraft_; }
  std::mt19937_64& rng() { return rng_; }

 private:
  KineticDelaunay engine_;
  std::mt19937_64 rng_;
  std::vector<Aircraft> aircraft_;
};

Vector2 keep_course(const Aircraft& a, std::mt19937_64&) { return a.velocity; }

Vector2 wander(const Aircraft& a, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> turn(-0.05, 0.05);
  const double angle = turn(rng);
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * a.velocity.x - s * a.velocity.y, s * a.velocity.x + c * a.velocity.y};
}

Vector2 random_velocity(std::mt19937_64& rng, double min_speed, double max_speed) {
  std::uniform_real_distribution<double> heading(0.0, 2.0 * std::numbers::pi);
  std::uniform_real_distribution<double> speed(min_speed, max_speed);
  const double h = heading(rng), s = speed(rng);
  return {s * std::cos(h), s * std::sin(h)};
}

struct MotionCase {
  const char* name;
  KineticConfig config;
};

std::vector<MotionCase> configurations() {
  std::vector<MotionCase> cases;
  for (double horizon : {kNever, 4.0, 0.5})
    for (double tolerance : {0.0, 100.0})
      for (bool reduce : {true, false}) {
        KineticConfig c;
        c.horizon_s = horizon;
        c.tolerance = tolerance;
        c.reduce_redundant_events = reduce;
        // Lazy certificates (kew's default) where the horizon leaves them room, the
        // eager solve elsewhere: both kinds of window in the suite.
        c.lazy_window_s = tolerance > 0.0 && horizon > 1.5 ? 1.5 : 0.0;
        // Kept models (kew's default) in half of the cases with a tolerance.
        c.keep_model_s = tolerance > 0.0 && !reduce ? 4.0 : 0.0;
        cases.push_back({"", c});
      }
  return cases;
}

std::string describe(const KineticConfig& c) {
  return "H=" + std::to_string(c.horizon_s) + " tau=" + std::to_string(c.tolerance) +
         " reduce=" + std::to_string(c.reduce_redundant_events) + " lazy=" + std::to_string(c.lazy_window_s) +
         " keep=" + std::to_string(c.keep_model_s);
}

// ---------------------------------------------------------------------------------

TEST(KineticDelaunayProperty, RandomMotionMatchesStaticDelaunayAtRandomTimes) {
  std::uint64_t seed = 1;
  for (const MotionCase& mc : configurations()) {
    SCOPED_TRACE(describe(mc.config));
    Harness h(mc.config, seed++);
    std::uniform_real_distribution<double> coordinate(0.0, 200'000.0);
    for (int k = 0; k < 300; ++k) h.add({coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 80, 260), 0.0);
    std::uniform_real_distribution<double> within(0.0, 4.0);
    for (int period = 0; period < 15; ++period) {
      const double start = 4.0 * period;
      h.radar_period(start, 4.0, 30.0, wander);
      h.check_at(start + 4.0 + within(h.rng()) * 0.25);
    }
    h.finish();
  }
}

TEST(KineticDelaunayProperty, FreeFlightWithoutUpdatesRenewsExpiredWindows) {
  // No measurement ever arrives: the model keeps moving and every event must still be
  // found through renewals of the thresholded windows (design §2.4).
  KineticConfig config;
  config.horizon_s = 2.0;
  Harness h(config, 7);
  std::uniform_real_distribution<double> coordinate(0.0, 100'000.0);
  for (int k = 0; k < 400; ++k) h.add({coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 100, 250), 0.0);
  std::uniform_real_distribution<double> step(0.5, 7.0);
  double t = 0.0;
  for (int k = 0; k < 40; ++k) {
    t += step(h.rng());
    h.check_at(t);
  }
  EXPECT_GT(h.engine().statistics().renewals, 0u);
  EXPECT_GT(h.engine().statistics().events_executed, 1000u);
  h.finish();
}

TEST(KineticDelaunayProperty, CrossingStreams) {
  for (const MotionCase& mc : configurations()) {
    SCOPED_TRACE(describe(mc.config));
    Harness h(mc.config, 11);
    std::uniform_real_distribution<double> jitter(-2000.0, 2000.0);
    // Two streams crossing at 70 degrees, at several flight levels (same 2D plane).
    for (int k = 0; k < 120; ++k) {
      h.add({-60'000.0 + 1000.0 * k + jitter(h.rng()), jitter(h.rng())}, {230.0, 0.0}, 0.0);
      h.add({jitter(h.rng()), -60'000.0 + 1000.0 * k + jitter(h.rng())}, {80.0, 216.0}, 0.0);
    }
    for (int period = 0; period < 12; ++period) {
      h.radar_period(4.0 * period, 4.0, 20.0, keep_course);
      h.check_at(4.0 * period + 4.0);
    }
    h.finish();
  }
}

TEST(KineticDelaunayProperty, AirwayOvertakesOnExactlyCollinearPaths) {
  // Aircraft on one straight airway (y = 0 exactly, and the diagonal y = x) at different
  // speeds overtake each other, passing through each other in 2D at different levels.
  for (const MotionCase& mc : configurations()) {
    SCOPED_TRACE(describe(mc.config));
    Harness h(mc.config, 13);
    std::uniform_real_distribution<double> along(-50'000.0, 50'000.0);
    std::uniform_real_distribution<double> speed(150.0, 260.0);
    for (int k = 0; k < 60; ++k) h.add({along(h.rng()), 0.0}, {speed(h.rng()), 0.0}, 0.0);
    for (int k = 0; k < 40; ++k) {
      const double s = along(h.rng());
      const double v = speed(h.rng()) / std::numbers::sqrt2;
      h.add({s, s}, {v, v}, 0.0);
    }
    std::uniform_real_distribution<double> coordinate(-80'000.0, 80'000.0);
    for (int k = 0; k < 60; ++k) h.add({coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 80, 200), 0.0);
    for (int period = 0; period < 25; ++period) {
      h.radar_period(4.0 * period, 4.0, 0.0, keep_course);
      h.check_at(4.0 * period + 3.9, /*compare_with_oracle=*/false);
    }
    h.finish();
  }
}

TEST(KineticDelaunayProperty, OnlyCollinearTraffic) {
  // Every aircraft on one line: the triangulation is a flat chain whose order changes.
  KineticConfig config;
  config.horizon_s = 4.0;
  Harness h(config, 17);
  std::uniform_real_distribution<double> along(-30'000.0, 30'000.0);
  std::uniform_real_distribution<double> speed(-250.0, 250.0);
  for (int k = 0; k < 30; ++k) h.add({along(h.rng()), 0.0}, {speed(h.rng()), 0.0}, 0.0);
  for (int period = 0; period < 30; ++period) {
    h.radar_period(4.0 * period, 4.0, 0.0, keep_course);
    h.check_at(4.0 * period + 4.0, false);
  }
  // One aircraft leaves the line: the structure becomes two-dimensional and back.
  Aircraft& odd = h.aircraft()[0];
  h.engine().update(odd.id, 125.0, {0.0, 500.0}, {0.0, -10.0});
  odd.position = odd.reported = {0.0, 500.0};
  odd.velocity = {0.0, -10.0};
  odd.time = odd.reported_time = 125.0;
  h.check_at(130.0, false);
  h.check_at(200.0, false);
  h.finish();
}

TEST(KineticDelaunayProperty, HoldingStackAtOneGroundPoint) {
  // Many aircraft at exactly one ground position (a stack at different levels), with
  // traffic passing through the stack's position.
  for (const MotionCase& mc : configurations()) {
    SCOPED_TRACE(describe(mc.config));
    Harness h(mc.config, 19);
    for (int k = 0; k < 12; ++k) h.add({10'000.0, 10'000.0}, {0.0, 0.0}, 0.0);
    for (int k = 0; k < 8; ++k) h.add({-5'000.0, 5'000.0}, {0.0, 0.0}, 0.0);
    std::uniform_real_distribution<double> coordinate(-40'000.0, 40'000.0);
    for (int k = 0; k < 80; ++k) h.add({coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 80, 220), 0.0);
    // One flight aimed exactly at the stack, arriving at t = 20 s.
    h.add({10'000.0 - 200.0 * 20.0, 10'000.0}, {200.0, 0.0}, 0.0);
    for (int period = 0; period < 15; ++period) {
      h.radar_period(4.0 * period, 4.0, 0.0, keep_course);
      h.check_at(4.0 * period + 4.0, false);
    }
    EXPECT_GE(h.engine().statistics().twins_created, 18u);
    h.finish();
  }
}

TEST(KineticDelaunayProperty, ExactDuplicatesSeparate) {
  KineticConfig config;
  config.horizon_s = 4.0;
  Harness h(config, 23);
  // Pairs inserted at identical positions with different velocities.
  std::uniform_real_distribution<double> coordinate(0.0, 50'000.0);
  for (int k = 0; k < 50; ++k) {
    const Point2 p{coordinate(h.rng()), coordinate(h.rng())};
    h.add(p, random_velocity(h.rng(), 100, 200), 0.0);
    h.add(p, random_velocity(h.rng(), 100, 200), 0.0);
  }
  EXPECT_EQ(h.engine().statistics().twins_created, 50u);
  for (int period = 0; period < 10; ++period) {
    h.radar_period(4.0 * period, 4.0, 0.0, keep_course);
    h.check_at(4.0 * period + 4.0, period > 0);
  }
  EXPECT_EQ(h.engine().statistics().twins_released, 50u);
  h.finish();
}

TEST(KineticDelaunayProperty, PassingThroughEachOtherExactly) {
  // Pairs of aircraft (at different levels) reach the same 2D point at the same time,
  // among other traffic: every certificate around a pair vanishes at that instant. The
  // engine holds one of the pair as a twin of the other while they are closer than
  // twin_release_distance_m, so the kinetic maintenance alone keeps the triangulation
  // valid (check_at audits before any repair). Even pairs fly free, so they meet
  // exactly (and check_at(8), (12), (16) fall on the meeting instants of pairs 0, 16,
  // 32); odd pairs get radar updates, which round their tracks, so they meet within
  // about 1e-11 m.
  for (const MotionCase& mc : configurations()) {
    SCOPED_TRACE(describe(mc.config));
    Harness h(mc.config, 29);
    std::uniform_real_distribution<double> coordinate(-30'000.0, 30'000.0);
    constexpr int kPairs = 40;
    std::vector<std::pair<PointId, PointId>> pairs;
    for (int k = 0; k < kPairs; ++k) {
      const Point2 meet{std::round(coordinate(h.rng())), std::round(coordinate(h.rng()))};
      const double at = 8.0 + k * 0.25;  // meeting time, exactly representable
      const Vector2 v1{200.0, 0.0}, v2{0.0, -160.0};
      if (k % 2 == 0) {
        KineticDelaunay& engine = h.engine();
        pairs.emplace_back(engine.insert(0.0, meet - at * v1, v1), engine.insert(0.0, meet - at * v2, v2));
        ASSERT_EQ(engine.position(pairs.back().first, at), engine.position(pairs.back().second, at));
      } else {
        pairs.emplace_back(h.add(meet - at * v1, v1, 0.0), h.add(meet - at * v2, v2, 0.0));
      }
    }
    for (int k = 0; k < 60; ++k) h.add({coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 80, 220), 0.0);
    for (int period = 0; period < 10; ++period) {
      h.radar_period(4.0 * period, 4.0, 0.0, keep_course);
      h.check_at(4.0 * period + 4.0, false);
    }
    // Each pair was merged before its meeting and released after it (close approaches
    // within the random traffic may add a few more).
    const KineticStatistics& stats = h.engine().statistics();
    EXPECT_GE(stats.approaches_merged, static_cast<std::uint64_t>(kPairs));
    EXPECT_EQ(stats.twins_released, stats.twins_created);
    for (const auto& [first, second] : pairs) {
      EXPECT_EQ(h.engine().host_of(first), first);
      EXPECT_EQ(h.engine().host_of(second), second);
    }
    h.finish();
  }
}

TEST(KineticDelaunayProperty, PointsEnterAndLeaveTheHull) {
  for (const MotionCase& mc : configurations()) {
    SCOPED_TRACE(describe(mc.config));
    Harness h(mc.config, 31);
    std::uniform_real_distribution<double> coordinate(-20'000.0, 20'000.0);
    // A core cloud, and aircraft flying radially through it from far outside and out again.
    for (int k = 0; k < 80; ++k) h.add({coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 0, 50), 0.0);
    for (int k = 0; k < 30; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / 30.0;
      const Vector2 dir{std::cos(angle), std::sin(angle)};
      h.add(60'000.0 * dir, -240.0 * dir, 0.0);
    }
    for (int period = 0; period < 100; ++period) {
      h.radar_period(4.0 * period, 4.0, 10.0, keep_course);
      if (period % 5 == 4) h.check_at(4.0 * period + 4.0);
    }
    h.finish();
  }
}

TEST(KineticDelaunayProperty, TracksComeAndGoAtAnyTime) {
  KineticConfig config;
  config.horizon_s = 4.0;
  config.tolerance = 50.0;
  Harness h(config, 37);
  std::uniform_real_distribution<double> coordinate(0.0, 100'000.0);
  std::vector<PointId> live;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double t = 0.0;
  for (int step = 0; step < 3000; ++step) {
    t += 0.01;
    if (live.size() < 20 || uniform(h.rng()) < 0.55) {
      live.push_back(h.engine().insert(t, {coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 50, 250)));
    } else {
      const std::size_t k = static_cast<std::size_t>(uniform(h.rng()) * static_cast<double>(live.size())) % live.size();
      h.engine().remove(live[k], t);
      live[k] = live.back();
      live.pop_back();
    }
    if (step % 300 == 299) {
      h.engine().advance(t);
      ASSERT_TRUE(h.engine().is_valid());
      EXPECT_EQ(h.engine().triangulation().audit().violations(), 0u);
    }
  }
  EXPECT_EQ(h.engine().size(), live.size());
  h.finish();
}

TEST(KineticDelaunayProperty, VelocityOnlyUpdatesKeepingRenewalsStayExact) {
  // Most velocity-only updates keep some renewals of their star (design §2.3): after
  // every radar period the whole triangulation is compared with CGAL's, with and
  // without lazy windows and §8.3, at two thresholds.
  std::uint64_t seed = 500;
  std::uint64_t kept = 0;
  for (const double horizon : {4.0, 0.5})
    for (const double lazy : {0.0, 1.5})
      for (const bool reduce : {true, false}) {
        KineticConfig config;
        config.horizon_s = horizon;
        config.lazy_window_s = lazy;
        config.reduce_redundant_events = reduce;
        config.tolerance = 100.0;
        SCOPED_TRACE(describe(config));
        Harness h(config, seed++);
        std::uniform_real_distribution<double> coordinate(0.0, 150'000.0);
        for (int k = 0; k < 300; ++k)
          h.add({coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 100, 260), 0.0);
        for (int period = 0; period < 25; ++period) {
          h.radar_period(4.0 * period, 4.0, 20.0, wander);
          h.check_at(4.0 * (period + 1));
        }
        kept += h.engine().statistics().certificates_kept;
        EXPECT_GT(h.engine().statistics().velocity_updates, 1000u);
        h.finish();
      }
  EXPECT_GT(kept, 10'000u);
}

TEST(KineticDelaunayProperty, ManyEventsAcrossTheSuiteWithNoUnrepairedViolation) {
  // Long free flight of a dense cloud to bring the suite past 10^6 executed events.
  KineticConfig config;
  config.horizon_s = 4.0;
  Harness h(config, 41);
  std::uniform_real_distribution<double> coordinate(0.0, 300'000.0);
  for (int k = 0; k < 2000; ++k) h.add({coordinate(h.rng()), coordinate(h.rng())}, random_velocity(h.rng(), 100, 260), 0.0);
  // Every 40 s each aircraft turns toward a random point of the square, so the cloud
  // keeps mixing instead of dispersing.
  auto turn_inwards = [](const Aircraft& a, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> target(0.0, 300'000.0), speed(100.0, 260.0);
    const Vector2 to = Point2{target(rng), target(rng)} - a.position;
    return (speed(rng) / geometry::norm(to)) * to;
  };
  double t = 0.0;
  while (totals().events_executed + h.engine().statistics().events_executed < 1'000'000) {
    h.radar_period(t, 4.0, 0.0, turn_inwards);
    t += 40.0;
    h.check_at(t, false);
    ASSERT_LT(t, 40'000.0) << "too few events";
  }
  h.check_at(t + 1.0);
  h.finish();
  EXPECT_GE(totals().events_executed, 1'000'000u);
  EXPECT_EQ(totals().unrepaired, 0u);
  EXPECT_GT(totals().kept_updates, 1000u);
  EXPECT_GT(totals().drift_reinsertions, 10u);
  std::printf("suite: %llu events executed, %llu audits, %llu CGAL comparisons, %llu kept updates, "
              "%llu drift reinsertions\n",
              static_cast<unsigned long long>(totals().events_executed),
              static_cast<unsigned long long>(totals().audits),
              static_cast<unsigned long long>(totals().oracle_comparisons),
              static_cast<unsigned long long>(totals().kept_updates),
              static_cast<unsigned long long>(totals().drift_reinsertions));
}

}  // namespace
}  // namespace kew::kinetic
