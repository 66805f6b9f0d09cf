// Sturm-sequence root isolation (thesis §7.4.3, Table 8.1, Alg. 4) and the engine's question
// "when does this certificate first become violated?" (Lemma 6: only odd roots are events).

#include "kew/kinetic/sturm.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace kew::kinetic {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Polynomial linear_factor(double root) { return Polynomial{-root, 1.0}; }

// (t - re)^2 + im^2: the complex pair re ± i·im.
Polynomial complex_pair(double re, double im) { return Polynomial{re * re + im * im, -2.0 * re, 1.0}; }

Polynomial power(const Polynomial& p, int n) {
  Polynomial result{1.0};
  for (int i = 0; i < n; ++i) result = result * p;
  return result;
}

Polynomial expanded(double scale, std::initializer_list<Polynomial> factors) {
  Polynomial result{scale};
  for (const Polynomial& f : factors) result = result * f;
  return result;
}

// What Table 8.1 and the roots promise for one polynomial, checked through every entry point.
struct TableRow {
  Polynomial p;
  std::vector<int> gcd_multiplicities;  // column 2: real root multiplicities of f_m
  std::vector<int> multiplicities;      // column 3: real root multiplicities of f
  std::vector<Root> roots;              // ascending
};

void check_row(const TableRow& row, double tolerance = 1e-9) {
  const SturmSequence sequence(row.p);
  EXPECT_EQ(real_root_multiplicities(sequence.last()), row.gcd_multiplicities) << "f_m column";
  EXPECT_EQ(real_root_multiplicities(row.p), row.multiplicities) << "f column";
  EXPECT_EQ(sequence.count_distinct_roots(-kInf, kInf), static_cast<int>(row.roots.size()));

  const std::vector<Root> roots = real_roots(row.p, -kInf, kInf);
  ASSERT_EQ(roots.size(), row.roots.size());
  for (std::size_t i = 0; i < roots.size(); ++i) {
    EXPECT_NEAR(roots[i].t, row.roots[i].t, tolerance * std::max(1.0, std::abs(row.roots[i].t))) << "root " << i;
    EXPECT_EQ(roots[i].multiplicity, row.roots[i].multiplicity) << "root " << i;
  }
  // Half-open intervals around each root: (r - 0.25, r] holds it, (r, r + 0.25] does not.
  for (const Root& r : row.roots) {
    EXPECT_EQ(sequence.count_distinct_roots(r.t - 0.25, r.t + 0.25), 1) << "around " << r.t;
    EXPECT_EQ(sequence.count_distinct_roots(r.t - 0.25, r.t), 1) << "up to " << r.t;
    EXPECT_EQ(sequence.count_distinct_roots(r.t, r.t + 0.25), 0) << "after " << r.t;
  }
}

// ---------------------------------------------------------------------------------------
// Table 8.1, degree 3

TEST(SturmTable, Degree3TripleRoot) {
  // f_m = (t-2)^2 has a double root, so f has a triple root.
  check_row({power(linear_factor(2.0), 3), {2}, {3}, {{2.0, 3}}});
  EXPECT_EQ(SturmSequence(power(linear_factor(2.0), 3)).gcd_degree(), 2);
}

TEST(SturmTable, Degree3DoubleAndSimpleRoot) {
  check_row({expanded(1.0, {linear_factor(1.0), linear_factor(1.0), linear_factor(3.0)}), {1}, {2, 1},
             {{1.0, 2}, {3.0, 1}}});
}

TEST(SturmTable, Degree3OneRealRootAndComplexPair) {
  check_row({expanded(-2.5, {linear_factor(2.0), complex_pair(1.0, 2.0)}), {}, {1}, {{2.0, 1}}});
}

TEST(SturmTable, Degree3ThreeSimpleRoots) {
  check_row({expanded(0.5, {linear_factor(-1.0), linear_factor(2.0), linear_factor(4.0)}), {}, {1, 1, 1},
             {{-1.0, 1}, {2.0, 1}, {4.0, 1}}});
}

// ---------------------------------------------------------------------------------------
// Table 8.1, degree 4

TEST(SturmTable, Degree4QuadrupleRoot) {
  check_row({3.0 * power(linear_factor(1.5), 4), {3}, {4}, {{1.5, 4}}});
  EXPECT_EQ(SturmSequence(power(linear_factor(1.5), 4)).gcd_degree(), 3);
}

TEST(SturmTable, Degree4TripleAndSimpleRoot) {
  check_row({expanded(1.0, {power(linear_factor(1.0), 3), linear_factor(-2.0)}), {2}, {3, 1},
             {{-2.0, 1}, {1.0, 3}}});
}

TEST(SturmTable, Degree4TwoDoubleRoots) {
  check_row({expanded(-1.0, {power(linear_factor(1.0), 2), power(linear_factor(4.0), 2)}), {1, 1}, {2, 2},
             {{1.0, 2}, {4.0, 2}}});
}

TEST(SturmTable, Degree4DoubleRootAndComplexPair) {
  check_row({expanded(1.0, {power(linear_factor(3.0), 2), complex_pair(-1.0, 1.0)}), {1}, {2}, {{3.0, 2}}});
}

TEST(SturmTable, Degree4DoubleAndTwoSimpleRoots) {
  // The brief's example: exact double root expanded in double.
  check_row({expanded(1.0, {power(linear_factor(2.0), 2), linear_factor(-1.0), linear_factor(5.0)}), {1},
             {2, 1, 1}, {{-1.0, 1}, {2.0, 2}, {5.0, 1}}});
}

TEST(SturmTable, Degree4NoRealRoot) {
  check_row({expanded(1.0, {complex_pair(1.0, 1.0), complex_pair(-2.0, 2.0)}), {}, {}, {}});
  // A double complex pair: f_m = (t-1)^2 + 1 has no real root either.
  const Polynomial double_pair = power(complex_pair(1.0, 1.0), 2);
  check_row({double_pair, {}, {}, {}});
  EXPECT_EQ(SturmSequence(double_pair).gcd_degree(), 2);
}

TEST(SturmTable, Degree4TwoSimpleRootsAndComplexPair) {
  check_row({expanded(2.0, {linear_factor(1.0), linear_factor(3.0), complex_pair(0.0, 1.0)}), {}, {1, 1},
             {{1.0, 1}, {3.0, 1}}});
}

TEST(SturmTable, Degree4FourSimpleRoots) {
  check_row({expanded(1.0, {linear_factor(-3.0), linear_factor(-1.0), linear_factor(2.0), linear_factor(6.0)}), {},
             {1, 1, 1, 1}, {{-3.0, 1}, {-1.0, 1}, {2.0, 1}, {6.0, 1}}});
}

// ---------------------------------------------------------------------------------------
// The sequence itself and lower degrees

TEST(SturmSequence, GenericQuarticHasFiveElementsStartingWithFAndDerivative) {
  const Polynomial p = expanded(7.0, {linear_factor(-3.0), linear_factor(-1.0), linear_factor(2.0), linear_factor(6.0)});
  const SturmSequence sequence(p);
  EXPECT_EQ(sequence.size(), 5);
  EXPECT_EQ(sequence.degree(), 4);
  EXPECT_EQ(sequence.gcd_degree(), 0);
  for (int i = 0; i < sequence.size(); ++i) EXPECT_EQ(sequence[i].degree(), 4 - i);
  // Positive multiples of f and f': same signs everywhere.
  for (double t : {-5.0, -2.0, 0.0, 1.0, 3.0, 10.0}) {
    EXPECT_EQ(std::signbit(sequence[0](t)), std::signbit(p(t))) << t;
    EXPECT_EQ(std::signbit(sequence[1](t)), std::signbit(p.derivative()(t))) << t;
  }
  EXPECT_EQ(sequence.sign_changes(-kInf) - sequence.sign_changes(kInf), 4);
  EXPECT_EQ(sequence.count_distinct_roots(5.0, 5.0), 0);
  EXPECT_EQ(sequence.count_distinct_roots(6.0, -4.0), 0);
  for (const Root& r : real_roots(p, -kInf, kInf)) EXPECT_LT(std::abs(r.t), sequence.root_bound());
}

TEST(SturmSequence, RootsExactlyAtIntervalEnds) {
  const Polynomial p = expanded(1.0, {linear_factor(1.0), linear_factor(2.0), linear_factor(3.0), linear_factor(4.0)});
  const SturmSequence sequence(p);
  EXPECT_EQ(sequence.count_distinct_roots(0.0, 2.0), 2);  // 1 and 2, b included
  EXPECT_EQ(sequence.count_distinct_roots(2.0, 3.0), 1);  // 3 only, a excluded
  EXPECT_EQ(sequence.count_distinct_roots(1.0, 4.0), 3);
  EXPECT_EQ(sequence.count_distinct_roots(4.0, kInf), 0);
  EXPECT_EQ(sequence.count_distinct_roots(-kInf, 1.0), 1);
  const std::vector<Root> roots = real_roots(p, 2.0, 4.0);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0].t, 3.0, 1e-12);
  EXPECT_NEAR(roots[1].t, 4.0, 1e-12);
}

TEST(SturmLowDegree, Linear) {
  const Polynomial p{-3.0, 2.0};
  EXPECT_EQ(SturmSequence(p).size(), 2);
  EXPECT_EQ(real_root_multiplicities(p), std::vector<int>{1});
  const std::vector<Root> roots = real_roots(p, -kInf, kInf);
  ASSERT_EQ(roots.size(), 1u);
  EXPECT_NEAR(roots[0].t, 1.5, 1e-12);

  const Crossing rising = first_positive_crossing(p, 0.0, kInf);
  EXPECT_TRUE(rising.found);
  EXPECT_FALSE(rising.violated_at_start);
  EXPECT_NEAR(rising.time, 1.5, 1e-12);
  EXPECT_EQ(rising.roots_counted, 1);

  const Crossing falling = first_positive_crossing(-1.0 * p, 0.0, kInf);
  EXPECT_FALSE(falling.found);
  EXPECT_TRUE(falling.violated_at_start);
}

TEST(SturmLowDegree, LinearWithExplicitLeadingZeros) {
  const Polynomial p{-6.0, 1.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(SturmSequence(p).degree(), 1);
  const Crossing c = first_positive_crossing(p, 0.0, 10.0);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 6.0, 1e-12);
}

TEST(SturmLowDegree, Quadratic) {
  const Polynomial two_roots = expanded(-1.0, {linear_factor(1.0), linear_factor(4.0)});
  EXPECT_EQ(real_root_multiplicities(two_roots), (std::vector<int>{1, 1}));
  const Crossing c = first_positive_crossing(two_roots, 0.0, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 1.0, 1e-12);
  EXPECT_EQ(c.roots_counted, 2);

  const Polynomial touching = power(linear_factor(2.0), 2);
  EXPECT_EQ(real_root_multiplicities(touching), std::vector<int>{2});
  const std::vector<Root> roots = real_roots(touching, -kInf, kInf);
  ASSERT_EQ(roots.size(), 1u);
  EXPECT_NEAR(roots[0].t, 2.0, 1e-12);
  EXPECT_EQ(roots[0].multiplicity, 2);

  EXPECT_TRUE(real_roots(complex_pair(1.0, 0.5), -kInf, kInf).empty());
  EXPECT_TRUE(real_root_multiplicities(complex_pair(1.0, 0.5)).empty());
}

TEST(SturmLowDegree, ConstantAndZero) {
  const Polynomial positive{5.0};
  EXPECT_EQ(SturmSequence(positive).size(), 1);
  EXPECT_TRUE(real_roots(positive, -kInf, kInf).empty());
  EXPECT_TRUE(real_root_multiplicities(positive).empty());
  EXPECT_TRUE(first_positive_crossing(positive, 0.0, kInf).violated_at_start);
  EXPECT_FALSE(first_positive_crossing(Polynomial{-5.0}, 0.0, kInf).violated_at_start);

  const Polynomial zero;
  const SturmSequence sequence(zero);
  EXPECT_EQ(sequence.size(), 1);
  EXPECT_EQ(sequence.degree(), -1);
  EXPECT_EQ(sequence.count_distinct_roots(-kInf, kInf), 0);
  EXPECT_TRUE(real_roots(zero, -kInf, kInf).empty());
  EXPECT_TRUE(real_root_multiplicities(zero).empty());
  const Crossing c = first_positive_crossing(zero, 0.0, kInf);
  EXPECT_FALSE(c.found);
  EXPECT_FALSE(c.violated_at_start);
  EXPECT_EQ(c.roots_counted, 0);
}

TEST(SturmSequence, NegligibleLeadingTermIsRoundingResidue) {
  // A t^3 coefficient 1e-30 of the others only adds a root near -1e30 s: dropped.
  const Polynomial residue{2.0, -3.0, 1.0, 1e-30};
  EXPECT_EQ(SturmSequence(residue).degree(), 2);
  const std::vector<Root> roots = real_roots(residue, -kInf, kInf);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0].t, 1.0, 1e-12);
  EXPECT_NEAR(roots[1].t, 2.0, 1e-12);

  // Relative to a root at 1e-12 s a root at 3 s is "far", but it is a real event: kept.
  const Polynomial near_zero = expanded(1.0, {linear_factor(1e-12), linear_factor(3.0)});
  EXPECT_EQ(SturmSequence(near_zero).degree(), 2);
  EXPECT_EQ(real_roots(near_zero, -kInf, kInf).size(), 2u);

  // A genuinely far root (2e5 s next to roots of a few seconds) is kept too.
  const Polynomial far = expanded(1.0, {linear_factor(1.0), linear_factor(2.0), linear_factor(2.0e5)});
  EXPECT_EQ(SturmSequence(far).degree(), 3);
  EXPECT_EQ(real_roots(far, -kInf, kInf).size(), 3u);
}

TEST(SturmSequence, CloseRootsStayDistinctUntilRoundingMergesThem) {
  // 10 ms apart at 10 s (1e-3 relative): two simple roots, a crossing at the first.
  const Polynomial close = expanded(-1.0, {linear_factor(10.0), linear_factor(10.01), complex_pair(3.0, 4.0)});
  EXPECT_EQ(real_root_multiplicities(close), (std::vector<int>{1, 1}));
  const Crossing c = first_positive_crossing(close, 0.0, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 10.0, 1e-9);
  EXPECT_EQ(first_positive_crossing(close, 10.005, kInf).violated_at_start, true);

  // 1 ns apart at 10 s: below what the coefficients resolve, read as one tangency.
  const Polynomial merged = expanded(-1.0, {linear_factor(10.0), linear_factor(10.0 + 1e-9), complex_pair(3.0, 4.0)});
  EXPECT_EQ(real_root_multiplicities(merged), std::vector<int>{2});
  const Crossing d = first_positive_crossing(merged, 0.0, kInf);
  EXPECT_FALSE(d.found);
  EXPECT_EQ(d.tangencies, 1);
}

// ---------------------------------------------------------------------------------------
// first_positive_crossing: Lemma 6 and the direction of the sign change

TEST(FirstPositiveCrossing, DoubleRootIsATangencyNotACrossing) {
  // (t-2)^2 (t+1)(t-5): negative on (0, 2), touches 0 at 2, crosses upwards at 5.
  const Polynomial p = expanded(1.0, {power(linear_factor(2.0), 2), linear_factor(-1.0), linear_factor(5.0)});
  const Crossing before_crossing = first_positive_crossing(p, 0.0, 4.0);
  EXPECT_FALSE(before_crossing.found);
  EXPECT_FALSE(before_crossing.violated_at_start);
  EXPECT_EQ(before_crossing.tangencies, 1);
  EXPECT_EQ(before_crossing.roots_counted, 1);

  const Crossing c = first_positive_crossing(p, 0.0, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 5.0, 1e-9);
  EXPECT_EQ(c.tangencies, 1);
  EXPECT_EQ(c.roots_counted, 2);
}

TEST(FirstPositiveCrossing, PureTangencyNeverCrosses) {
  const Polynomial p = expanded(-1.0, {power(linear_factor(2.0), 2), complex_pair(0.0, 1.0)});
  const Crossing c = first_positive_crossing(p, 0.0, kInf);
  EXPECT_FALSE(c.found);
  EXPECT_FALSE(c.violated_at_start);
  EXPECT_EQ(c.tangencies, 1);
}

TEST(FirstPositiveCrossing, TwoDoubleRootsAreTwoTangencies) {
  const Polynomial p = expanded(-1.0, {power(linear_factor(1.0), 2), power(linear_factor(4.0), 2)});
  const Crossing c = first_positive_crossing(p, 0.0, kInf);
  EXPECT_FALSE(c.found);
  EXPECT_EQ(c.tangencies, 2);
}

TEST(FirstPositiveCrossing, TripleRootIsACrossing) {
  const Polynomial rising = power(linear_factor(2.0), 3);
  const Crossing c = first_positive_crossing(rising, 0.0, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 2.0, 1e-12);
  EXPECT_EQ(c.tangencies, 0);

  // Falling through a triple root: violated from the start, then not.
  EXPECT_TRUE(first_positive_crossing(-1.0 * rising, 0.0, kInf).violated_at_start);
}

TEST(FirstPositiveCrossing, DoubleAndSimpleRootCrossesOnlyAtTheSimpleRoot) {
  // (t-1)^2 (t-3): touches at 1, crosses at 3.
  const Polynomial p = expanded(1.0, {power(linear_factor(1.0), 2), linear_factor(3.0)});
  const Crossing c = first_positive_crossing(p, 0.0, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 3.0, 1e-12);
  EXPECT_EQ(c.tangencies, 1);

  // (t-3)^2 (t-1): crosses at 1, then touches at 3 while positive.
  const Polynomial q = expanded(1.0, {power(linear_factor(3.0), 2), linear_factor(1.0)});
  const Crossing d = first_positive_crossing(q, 0.0, kInf);
  EXPECT_TRUE(d.found);
  EXPECT_NEAR(d.time, 1.0, 1e-12);
  EXPECT_EQ(d.tangencies, 0);
  const Crossing e = first_positive_crossing(q, 2.0, kInf);
  EXPECT_FALSE(e.found);
  EXPECT_TRUE(e.violated_at_start);
}

TEST(FirstPositiveCrossing, DirectionMatters) {
  // (t-1)(t-3) is positive on (0, 1): already violated; root 1 goes + to -, root 3 - to +.
  const Polynomial p = expanded(1.0, {linear_factor(1.0), linear_factor(3.0)});
  const Crossing at_zero = first_positive_crossing(p, 0.0, kInf);
  EXPECT_TRUE(at_zero.violated_at_start);
  EXPECT_FALSE(at_zero.found);
  const Crossing between = first_positive_crossing(p, 2.0, kInf);
  EXPECT_FALSE(between.violated_at_start);
  EXPECT_TRUE(between.found);
  EXPECT_NEAR(between.time, 3.0, 1e-12);

  // -(t-1)(t-3): negative first, crosses upwards at 1; from 2 on it is violated until 3.
  const Crossing negated = first_positive_crossing(-1.0 * p, 0.0, kInf);
  EXPECT_TRUE(negated.found);
  EXPECT_NEAR(negated.time, 1.0, 1e-12);
  const Crossing negated_between = first_positive_crossing(-1.0 * p, 2.0, kInf);
  EXPECT_TRUE(negated_between.violated_at_start);
  EXPECT_FALSE(negated_between.found);
  // On (1.5, 2.5] the only root would be a + to - one: nothing at all.
  const Crossing none = first_positive_crossing(-1.0 * p, 1.5, 2.5);
  EXPECT_TRUE(none.violated_at_start);
  EXPECT_EQ(none.roots_counted, 0);
  // A root going + to - inside (lo, hi] after a negative start cannot exist, but one at
  // the very end of a positive stretch is still not a crossing.
  const Crossing falling_at_hi = first_positive_crossing(-1.0 * p, 2.0, 3.0);
  EXPECT_FALSE(falling_at_hi.found);
}

TEST(FirstPositiveCrossing, RootExactlyAtLo) {
  // t(t-3): positive before 0, negative after: the root at lo is ignored, the crossing is 3.
  const Polynomial falling_at_lo = expanded(1.0, {linear_factor(0.0), linear_factor(3.0)});
  const Crossing c = first_positive_crossing(falling_at_lo, 0.0, kInf);
  EXPECT_FALSE(c.violated_at_start);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 3.0, 1e-12);

  // -t(t-3): negative before 0, positive after: violated at start, no crossing reported.
  const Crossing d = first_positive_crossing(-1.0 * falling_at_lo, 0.0, kInf);
  EXPECT_TRUE(d.violated_at_start);
  EXPECT_FALSE(d.found);
}

TEST(FirstPositiveCrossing, RootsWithinStartToleranceCountAsAtLo) {
  // A certificate rebuilt at an event time: its root at 0 landed a picosecond late.
  const Polynomial falling_late = expanded(1.0, {linear_factor(1e-12), linear_factor(3.0)});
  const Crossing c = first_positive_crossing(falling_late, 0.0, kInf);
  EXPECT_FALSE(c.violated_at_start);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 3.0, 1e-12);

  const Crossing d = first_positive_crossing(-1.0 * falling_late, 0.0, kInf);
  EXPECT_TRUE(d.violated_at_start);
  EXPECT_FALSE(d.found);

  // With no tolerance the same root is an ordinary root after lo.
  const Crossing strict = first_positive_crossing(falling_late, 0.0, kInf, 0.0);
  EXPECT_TRUE(strict.violated_at_start);
  const Crossing strict_rising = first_positive_crossing(-1.0 * falling_late, 0.0, kInf, 0.0);
  EXPECT_TRUE(strict_rising.found);
  EXPECT_NEAR(strict_rising.time, 1e-12, 1e-20);

  // A root clearly after the window is an event as usual.
  const Crossing later = first_positive_crossing(expanded(-1.0, {linear_factor(1e-6), linear_factor(3.0)}), 0.0, kInf);
  EXPECT_TRUE(later.found);
  EXPECT_NEAR(later.time, 1e-6, 1e-18);
}

TEST(FirstPositiveCrossing, IntervalRestriction) {
  const Polynomial p = expanded(1.0, {linear_factor(1.0), linear_factor(2.0), linear_factor(3.0), linear_factor(4.0)});
  // Negative on (1, 2), positive on (2, 3), negative on (3, 4).
  const Crossing c = first_positive_crossing(p, 1.5, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 2.0, 1e-12);

  const Crossing short_of_it = first_positive_crossing(p, 1.5, 1.9);
  EXPECT_FALSE(short_of_it.found);
  EXPECT_FALSE(short_of_it.violated_at_start);
  EXPECT_EQ(short_of_it.roots_counted, 0);

  const Crossing root_at_hi = first_positive_crossing(p, 1.5, 2.0);
  EXPECT_TRUE(root_at_hi.found);
  EXPECT_NEAR(root_at_hi.time, 2.0, 1e-12);

  const Crossing from_root = first_positive_crossing(p, 2.0, 10.0);  // root 2 is at lo: excluded
  EXPECT_TRUE(from_root.violated_at_start);
  EXPECT_EQ(from_root.roots_counted, 2);

  const Crossing last_interval = first_positive_crossing(p, 3.5, 10.0);
  EXPECT_TRUE(last_interval.found);
  EXPECT_NEAR(last_interval.time, 4.0, 1e-12);
  EXPECT_EQ(last_interval.roots_counted, 1);

  EXPECT_FALSE(first_positive_crossing(p, 4.5, kInf).found);
  EXPECT_FALSE(first_positive_crossing(p, 3.0, 2.0).found);  // empty interval
}

TEST(FirstPositiveCrossing, InfiniteHorizonFindsFarRoots) {
  const Polynomial p = expanded(-1e-3, {linear_factor(2.0e5), linear_factor(3.0e5), complex_pair(10.0, 5.0)});
  const Crossing c = first_positive_crossing(p, 0.0, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 2.0e5, 1e-6);
  EXPECT_FALSE(first_positive_crossing(p, 0.0, 1.0e5).found);
}

// ---------------------------------------------------------------------------------------
// Realistic magnitudes

TEST(SturmScaling, RootsAt3p5And40ScaledBy1e18) {
  const Polynomial p = expanded(-1e18, {linear_factor(3.5), linear_factor(40.0), complex_pair(10.0, 20.0)});
  EXPECT_GT(std::abs(p.coefficient(0)), 1e20);
  const std::vector<Root> roots = real_roots(p, -kInf, kInf);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0].t, 3.5, 1e-12);
  EXPECT_NEAR(roots[1].t, 40.0, 1e-11);

  const Crossing c = first_positive_crossing(p, 0.0, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 3.5, 1e-12);
  EXPECT_FALSE(first_positive_crossing(p, 0.0, 3.4).found);
  EXPECT_TRUE(first_positive_crossing(p, 10.0, 60.0).violated_at_start);

  // Same roots with tiny coefficients.
  const Polynomial tiny = 1e-36 * p;
  const Crossing d = first_positive_crossing(tiny, 0.0, kInf);
  EXPECT_TRUE(d.found);
  EXPECT_NEAR(d.time, 3.5, 1e-12);
}

TEST(SturmScaling, ScaledDoubleRootIsStillATangency) {
  const Polynomial p = expanded(1e18, {power(linear_factor(3.5), 2), linear_factor(40.0), linear_factor(-7.0)});
  EXPECT_EQ(real_root_multiplicities(p), (std::vector<int>{2, 1, 1}));
  const Crossing c = first_positive_crossing(p, 0.0, kInf);
  EXPECT_TRUE(c.found);
  EXPECT_NEAR(c.time, 40.0, 1e-9);
  EXPECT_EQ(c.tangencies, 1);
}

// Points moving in metres and seconds, far from the origin, as the engine sees them.
struct Moving {
  double x, y, vx, vy;
};

// incircle(a, b, c, d)(t): the determinant of the rows (p - d, |p - d|^2) for p = a, b, c,
// expanded as a polynomial in t (degree ≤ 4).
Polynomial incircle_polynomial_of(const Moving& a, const Moving& b, const Moving& c, const Moving& d) {
  auto dx = [&d](const Moving& p) { return Polynomial{p.x - d.x, p.vx - d.vx}; };
  auto dy = [&d](const Moving& p) { return Polynomial{p.y - d.y, p.vy - d.vy}; };
  auto lifted = [&](const Moving& p) { return dx(p) * dx(p) + dy(p) * dy(p); };
  auto minor = [&](const Moving& p, const Moving& q) { return dx(p) * dy(q) - dy(p) * dx(q); };
  return lifted(a) * minor(b, c) - lifted(b) * minor(a, c) + lifted(c) * minor(a, b);
}

TEST(SturmScaling, IncircleOfAPointEnteringACircle) {
  // A counter-clockwise triangle on a 10 km circle around (300 km, 200 km); d starts 12 km
  // west of the centre and flies east at 200 m/s: it enters at t = 10 s and leaves at 110 s.
  // All four share a drift of (250, -100) m/s, which changes nothing relative.
  const double cx = 3.0e5;
  const double cy = 2.0e5;
  const double r = 1.0e4;
  const Moving a{cx + r, cy, 250.0, -100.0};
  const Moving b{cx + r * std::cos(2.0), cy + r * std::sin(2.0), 250.0, -100.0};
  const Moving c{cx + r * std::cos(4.0), cy + r * std::sin(4.0), 250.0, -100.0};
  const Moving d{cx - 1.2e4, cy, 450.0, -100.0};
  const Polynomial p = incircle_polynomial_of(a, b, c, d);
  EXPECT_GT(p.max_abs_coefficient(), 1e15);

  const Crossing entering = first_positive_crossing(p, 0.0, kInf);
  EXPECT_TRUE(entering.found);
  EXPECT_NEAR(entering.time, 10.0, 1e-7);
  EXPECT_FALSE(first_positive_crossing(p, 0.0, 9.9).found);
  EXPECT_TRUE(first_positive_crossing(p, 20.0, 200.0).violated_at_start);

  const std::vector<Root> roots = real_roots(p, 0.0, kInf);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0].t, 10.0, 1e-7);
  EXPECT_NEAR(roots[1].t, 110.0, 1e-6);
}

TEST(SturmScaling, IncircleOfAPointGrazingACircleIsATangency) {
  // Thesis Fig. 7.3: d flies east along the tangent at the top of the circle and touches
  // it at t = 20 s. The certificate has a double root there, and must not fail.
  const double cx = 3.0e5;
  const double cy = 2.0e5;
  const double r = 1.0e4;
  const Moving a{cx + r, cy, 0.0, 0.0};
  const Moving b{cx + r * std::cos(2.0), cy + r * std::sin(2.0), 0.0, 0.0};
  const Moving c{cx + r * std::cos(4.0), cy + r * std::sin(4.0), 0.0, 0.0};
  const Moving d{cx - 5000.0, cy + r, 250.0, 0.0};
  const Polynomial p = incircle_polynomial_of(a, b, c, d);

  const Crossing grazing = first_positive_crossing(p, 0.0, kInf);
  EXPECT_FALSE(grazing.found);
  EXPECT_FALSE(grazing.violated_at_start);
  EXPECT_EQ(grazing.tangencies, 1);
  const std::vector<Root> roots = real_roots(p, -kInf, kInf);
  ASSERT_EQ(roots.size(), 1u);
  EXPECT_NEAR(roots[0].t, 20.0, 1e-6);
  EXPECT_EQ(roots[0].multiplicity, 2);
}

// ---------------------------------------------------------------------------------------
// Property: polynomials built from random simple real roots and random complex pairs

TEST(SturmProperty, RandomRootsAreRecoveredAndTheFirstUpwardCrossingIsFound) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> root_at(-50.0, 50.0);
  std::uniform_real_distribution<double> imaginary(0.5, 30.0);
  std::uniform_real_distribution<double> exponent(-12.0, 20.0);
  std::uniform_int_distribution<int> real_count_of(0, 4);
  std::bernoulli_distribution flip(0.5);

  for (int trial = 0; trial < 5000; ++trial) {
    const int real_count = real_count_of(rng);
    std::vector<double> roots;
    while (static_cast<int>(roots.size()) < real_count) {
      const double candidate = root_at(rng);
      // Keep roots apart: closer than ~1e-5 of their range they may legitimately merge.
      if (std::all_of(roots.begin(), roots.end(), [&](double r) { return std::abs(r - candidate) > 0.5; }))
        roots.push_back(candidate);
    }
    std::sort(roots.begin(), roots.end());
    Polynomial p{(flip(rng) ? -1.0 : 1.0) * std::pow(10.0, exponent(rng))};
    for (double r : roots) p = p * linear_factor(r);
    while (p.degree() + 2 <= Polynomial::kMaxDegree && flip(rng)) p = p * complex_pair(root_at(rng), imaginary(rng));
    SCOPED_TRACE(testing::Message() << "trial " << trial << " degree " << p.degree());

    const std::vector<Root> found = real_roots(p, -kInf, kInf);
    ASSERT_EQ(found.size(), roots.size());
    for (std::size_t i = 0; i < roots.size(); ++i) {
      EXPECT_NEAR(found[i].t, roots[i], 1e-8 * std::max(1.0, std::abs(roots[i])));
      EXPECT_EQ(found[i].multiplicity, 1);
    }

    // Expected answer from the construction: the sign just after lo is the leading sign
    // flipped once per root beyond lo; the first crossing is the first root where the sign
    // goes from - to +, i.e. the first root after lo when starting negative.
    std::uniform_real_distribution<double> lo_at(-60.0, 60.0);
    double lo = lo_at(rng);
    while (std::any_of(roots.begin(), roots.end(), [&](double r) { return std::abs(r - lo) < 1e-3; })) lo = lo_at(rng);
    const double hi = flip(rng) ? kInf : lo + std::uniform_real_distribution<double>(0.0, 60.0)(rng);
    int sign = p.coefficient(p.degree()) > 0.0 ? 1 : -1;
    int roots_in_interval = 0;
    for (double r : roots) {
      if (r > lo) sign = -sign;
      if (r > lo && r <= hi) ++roots_in_interval;
    }
    const auto first_after = std::upper_bound(roots.begin(), roots.end(), lo);
    const bool expect_violated = sign > 0;
    const bool expect_found = !expect_violated && first_after != roots.end() && *first_after <= hi;

    const Crossing c = first_positive_crossing(p, lo, hi);
    EXPECT_EQ(c.violated_at_start, expect_violated);
    EXPECT_EQ(c.found, expect_found);
    if (expect_found && c.found) {
      EXPECT_NEAR(c.time, *first_after, 1e-8 * std::max(1.0, std::abs(*first_after)));
    }
    EXPECT_EQ(c.tangencies, 0);
    EXPECT_EQ(c.roots_counted, roots_in_interval);
  }
}

TEST(SturmProperty, RandomDoubleRootsAreTangencies) {
  // A double root at d plus two simple roots or a complex pair: the double root never
  // produces a crossing, whatever the scale.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> root_at(0.0, 1000.0);
  std::uniform_real_distribution<double> exponent(-12.0, 20.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double double_root = root_at(rng);
    // Negative on both sides of the double root: -(t-d)^2 · (positive quadratic).
    const Polynomial p = expanded(-std::pow(10.0, exponent(rng)), {power(linear_factor(double_root), 2),
                                                     complex_pair(root_at(rng), 50.0 + root_at(rng))});
    SCOPED_TRACE(testing::Message() << "trial " << trial << " double root " << double_root);
    const Crossing c = first_positive_crossing(p, 0.0, kInf);
    EXPECT_FALSE(c.found);
    EXPECT_FALSE(c.violated_at_start);
    EXPECT_EQ(c.tangencies, 1);
  }
}

}  // namespace
}  // namespace kew::kinetic
