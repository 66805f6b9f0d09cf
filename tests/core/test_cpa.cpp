// Hand-computed CPA cases (design §4.4): S_h = 9260 m, S_v = 304.8 m, T = 120 s, the
// vertical prediction plainly linear (T_v = T, no altimetry tolerance) unless a case says
// otherwise.
#include "kew/probe/cpa.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kew::probe {
namespace {

Kinematics at(double x, double y, double vx, double vy, double alt_m = 10000.0, double vz = 0.0) {
  return {{x, y}, {vx, vy}, alt_m, vz};
}

SeparationMinima linear_minima() {
  SeparationMinima m;
  m.vertical_lookahead_s = m.lookahead_s;
  m.altimetry_tolerance_m = 0.0;
  return m;
}
const SeparationMinima kMinima = linear_minima();

TEST(Cpa, AVerticalConvergenceCountsOnlyWithinTheVerticalLookahead) {
  // The vertical crossing below begins at 69.52 s: a conflict when T_v is above that,
  // none when it is below (the climb may level off before).
  SeparationMinima m = kMinima;
  const Kinematics level = at(0, 0, 200, 0, 10000), climbing = at(0, 0, 200, 0, 9000, 10);
  m.vertical_lookahead_s = 70.0;
  EXPECT_TRUE(evaluate_pair(level, climbing, m).in_conflict);
  EXPECT_NEAR(evaluate_pair(level, climbing, m).t_los_s, 69.52, 1e-9);
  m.vertical_lookahead_s = 69.0;
  EXPECT_FALSE(evaluate_pair(level, climbing, m).in_conflict);
  EXPECT_FALSE(in_conflict(level, climbing, m));
  // Vertically within S_v now and diverging: trusted for the whole look-ahead, whatever
  // T_v. 100 m apart, separating at 10 m/s: within S_v until 20.48 s; head-on 20 km apart
  // at 2 × 250 m/s, horizontally within S_h from 21.48 s: clear. Closer: a conflict.
  m.vertical_lookahead_s = 0.0;
  EXPECT_FALSE(in_conflict(at(0, 0, 250, 0, 10000), at(20000, 0, -250, 0, 10100, 10), m));
  const ConflictGeometry g = evaluate_pair(at(0, 0, 250, 0, 10000), at(15000, 0, -250, 0, 10100, 10), m);
  EXPECT_TRUE(g.in_conflict);
  EXPECT_NEAR(g.t_los_s, (15000.0 - 9260.0) / 500.0, 1e-9);
  // Level pairs are unaffected.
  EXPECT_TRUE(in_conflict(at(0, 0, 250, 0, 10000), at(60000, 0, -250, 0, 10100), m));
}

TEST(Cpa, AConvergenceToTheAdjacentLevelIsNoConflict) {
  // 400 m (1,312 ft) below, climbing at 5 m/s on the same track: within S_v from 19.04 s,
  // below S_v − 60.96 m (800 ft) from 31.23 s. With T_v = 30 s that is too late: the climb
  // may level off at the adjacent level (975 ft apart). With T_v = 32 s: a conflict from
  // 19.04 s, the figures of the linear prediction.
  SeparationMinima m = kMinima;
  m.altimetry_tolerance_m = 60.96;
  const Kinematics level = at(0, 0, 200, 0, 10000), climbing = at(0, 0, 200, 0, 9600, 5);
  m.vertical_lookahead_s = 30.0;
  EXPECT_FALSE(in_conflict(level, climbing, m));
  m.vertical_lookahead_s = 32.0;
  const ConflictGeometry g = evaluate_pair(level, climbing, m);
  EXPECT_TRUE(g.in_conflict);
  EXPECT_NEAR(g.t_los_s, (400.0 - 304.8) / 5.0, 1e-9);
  EXPECT_NEAR(g.t_end_s, 120.0, 1e-9);
}

TEST(Cpa, ExactlyTheVerticalMinimumApartIsSeparated) {
  // Altitudes converted from feet as the pipeline converts them: FL350 − FL340 reads a
  // few 1e-14 m under 304.8 m. Overhead each other, level or slowly diverging: separated,
  // with the linear model and with the defaults. Converging at 100 ft/min: a conflict
  // that starts now with the linear model (not a loss now), none with the defaults (the
  // real loss, 200 ft further, is 120 s away, beyond T_v).
  const double fl340 = 34000.0 * 0.3048, fl350 = 35000.0 * 0.3048;
  ASSERT_LT(fl350 - fl340, 304.8);
  const SeparationMinima defaults;
  for (const SeparationMinima& m : {kMinima, defaults}) {
    EXPECT_FALSE(in_conflict(at(0, 0, 200, 0, fl340), at(0, 0, -200, 0, fl350), m));
    EXPECT_FALSE(in_conflict(at(0, 0, 200, 0, fl340), at(0, 0, -200, 0, fl350, 0.3251), m));
    EXPECT_FALSE(in_conflict(at(0, 0, 200, 0, fl340, -0.3251), at(0, 0, -200, 0, fl350), m));
  }
  const ConflictGeometry g = evaluate_pair(at(0, 0, 200, 0, fl340), at(0, 0, -200, 0, fl350, -0.508), kMinima);
  EXPECT_TRUE(g.in_conflict);
  EXPECT_FALSE(g.lost_now);
  EXPECT_EQ(g.t_los_s, 0.0);
  EXPECT_FALSE(in_conflict(at(0, 0, 200, 0, fl340), at(0, 0, -200, 0, fl350, -0.508), defaults));
}

TEST(Cpa, HeadOnLosesSeparationWhenTheGapCloses) {
  // 60 km apart, closing at 2 × 250 m/s: loss when the gap is 9260 m, after
  // (60000 − 9260) / 500 = 101.48 s; CPA at 120 s (clamped: they would meet at 120 s).
  const ConflictGeometry g = evaluate_pair(at(0, 0, 250, 0), at(60000, 0, -250, 0), kMinima);
  EXPECT_TRUE(g.in_conflict);
  EXPECT_FALSE(g.lost_now);
  EXPECT_NEAR(g.t_los_s, 101.48, 1e-9);
  EXPECT_NEAR(g.t_cpa_s, 120.0, 1e-9);
  EXPECT_NEAR(g.cpa_h_m, 0.0, 1e-6);
  EXPECT_NEAR(g.sep_h_m, 60000.0, 1e-9);
  EXPECT_NEAR(g.t_end_s, 120.0, 1e-9);
}

TEST(Cpa, HeadOnBeyondTheLookaheadIsClear) {
  // 130 km apart closing at 500 m/s: the gap is 70 km after 120 s.
  const ConflictGeometry g = evaluate_pair(at(0, 0, 250, 0), at(130000, 0, -250, 0), kMinima);
  EXPECT_FALSE(g.in_conflict);
  EXPECT_NEAR(g.cpa_h_m, 70000.0, 1e-6);
  EXPECT_NEAR(g.t_cpa_s, 120.0, 1e-12);
}

TEST(Cpa, SlowOvertakeBeyondTheLookaheadIsClear) {
  // Same airway and level, 20 km behind, 50 m/s faster: the gap is 14 km at T.
  const ConflictGeometry g = evaluate_pair(at(0, 0, 200, 0), at(-20000, 0, 250, 0), kMinima);
  EXPECT_FALSE(g.in_conflict);
  EXPECT_NEAR(g.t_cpa_s, 120.0, 1e-9);
  EXPECT_NEAR(g.cpa_h_m, 14000.0, 1e-6);
}

TEST(Cpa, OvertakeWithinTheLookahead) {
  // 15 km behind, 100 m/s faster: loss after (15000 − 9260)/100 = 57.4 s: a warning.
  const ConflictGeometry g = evaluate_pair(at(0, 0, 200, 0), at(-15000, 0, 300, 0), kMinima);
  EXPECT_TRUE(g.in_conflict);
  EXPECT_NEAR(g.t_los_s, 57.4, 1e-9);
  EXPECT_NEAR(g.t_cpa_s, 120.0, 1e-9);  // still closing at T
  EXPECT_NEAR(g.cpa_h_m, 15000.0 - 12000.0, 1e-6);
}

TEST(Cpa, ParallelAtConstantDistanceIsClearOrLost) {
  // Same velocity: the relative motion is zero, the distance never changes.
  const ConflictGeometry clear = evaluate_pair(at(0, 0, 200, 0), at(0, 10000, 200, 0), kMinima);
  EXPECT_FALSE(clear.in_conflict);
  EXPECT_EQ(clear.t_cpa_s, 0.0);
  EXPECT_NEAR(clear.cpa_h_m, 10000.0, 1e-9);
  const ConflictGeometry lost = evaluate_pair(at(0, 0, 200, 0), at(0, 5000, 200, 0), kMinima);
  EXPECT_TRUE(lost.in_conflict);
  EXPECT_TRUE(lost.lost_now);
  EXPECT_EQ(lost.t_los_s, 0.0);
  EXPECT_EQ(lost.t_end_s, 120.0);
}

TEST(Cpa, VerticalCrossingOverTheSamePoint) {
  // Same ground track and speed (horizontal distance 0 throughout); one climbs at
  // 10 m/s from 1000 m below: vertical distance < 304.8 m from (1000 − 304.8)/10 =
  // 69.52 s to (1000 + 304.8)/10 = 130.48 s, clipped to T.
  const ConflictGeometry g = evaluate_pair(at(0, 0, 200, 0, 10000), at(0, 0, 200, 0, 9000, 10), kMinima);
  EXPECT_TRUE(g.in_conflict);
  EXPECT_NEAR(g.t_los_s, 69.52, 1e-9);
  EXPECT_NEAR(g.t_end_s, 120.0, 1e-12);
  EXPECT_NEAR(g.sep_v_m, 1000.0, 1e-9);
}

TEST(Cpa, VerticalCrossingWhenHorizontallyApartIsClear) {
  // The vertical window (69.52 s, 130.48 s) and the horizontal one (the pair is within
  // 9260 m only before 20 s on diverging tracks) do not overlap.
  const ConflictGeometry g = evaluate_pair(at(0, 0, 0, 0, 10000), at(5000, 0, 200, 0, 9000, 10), kMinima);
  EXPECT_FALSE(g.in_conflict);
}

TEST(Cpa, AlreadyInLoss) {
  const ConflictGeometry g = evaluate_pair(at(0, 0, 200, 0, 10000), at(3000, 4000, 150, 0, 10100), kMinima);
  EXPECT_TRUE(g.in_conflict);
  EXPECT_TRUE(g.lost_now);
  EXPECT_EQ(g.t_los_s, 0.0);
  EXPECT_NEAR(g.sep_h_m, 5000.0, 1e-9);
  EXPECT_NEAR(g.sep_v_m, 100.0, 1e-9);
}

TEST(Cpa, DivergingAfterCloseApproachIsClear) {
  // 10 km apart and separating: the closest approach was in the past.
  const ConflictGeometry g = evaluate_pair(at(0, 0, -200, 0), at(10000, 0, 200, 0), kMinima);
  EXPECT_FALSE(g.in_conflict);
  EXPECT_EQ(g.t_cpa_s, 0.0);
  EXPECT_NEAR(g.cpa_h_m, 10000.0, 1e-9);
}

TEST(Cpa, CrossingAtRightAngles) {
  // A flies east from (−30 km, 0), B north from (0, −30 km), both 250 m/s: they meet
  // at the origin at 120 s; their distance is √2·|30000 − 250 t|, below 9260 m from
  // t = (30000 − 9260/√2)/250 = 93.810... s.
  const ConflictGeometry g = evaluate_pair(at(-30000, 0, 250, 0), at(0, -30000, 0, 250), kMinima);
  EXPECT_TRUE(g.in_conflict);
  EXPECT_NEAR(g.t_los_s, (30000.0 - 9260.0 / std::sqrt(2.0)) / 250.0, 1e-9);
  EXPECT_NEAR(g.t_cpa_s, 120.0, 1e-9);
  EXPECT_NEAR(g.cpa_h_m, 0.0, 1e-6);
}

TEST(Cpa, SymmetricUnderSwap) {
  const Kinematics a = at(1234, -5678, 210, 35, 10500, 5);
  const Kinematics b = at(-4321, 8765, -180, -60, 10300, -3);
  const ConflictGeometry ab = evaluate_pair(a, b, kMinima);
  const ConflictGeometry ba = evaluate_pair(b, a, kMinima);
  EXPECT_EQ(ab.in_conflict, ba.in_conflict);
  EXPECT_NEAR(ab.t_los_s, ba.t_los_s, 1e-9);
  EXPECT_NEAR(ab.cpa_h_m, ba.cpa_h_m, 1e-9);
}

}  // namespace
}  // namespace kew::probe
