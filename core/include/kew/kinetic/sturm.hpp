#pragma once
// Real-root isolation for certificate polynomials (degree ≤ 4) with Sturm sequences
// (thesis §7.4.3, Table 8.1, Alg. 4). The engine only ever asks one question, "when does
// this certificate first become violated?", so the design answers it by counting roots
// before computing any, and by computing at most the one root that is the answer.
//
// Time is the engine's local time in seconds (design §4.1): t = 0 is "now".
//
// Tolerance model. Coefficients are doubles, so a polynomial that "should" have a double
// root (a tangency, Lemma 6) usually has, as stored, two very close roots or a very narrow
// complex pair. Decisions are therefore made up to rounding, in this order:
//  1. A leading coefficient whose term is below kNegligibleLeadingTermTolerance of the
//     others (on a disk of at least 1 s holding their roots) is rounding residue of a
//     cancelled term: it is dropped, losing only a root beyond ~1e10 s.
//  2. A remainder coefficient below kSturmRelativeTolerance times the magnitude of the terms
//     that cancelled to produce it is zero: the chain stops, its last element is the gcd.
//  3. Such a gcd is confirmed on f itself. A linear one (one double root, the tangency the
//     engine meets) is accepted when, at the critical point r of f next to it,
//     |f(r)| ≤ kDoubleRootBackwardTolerance · Σ|c_i||r|^i, even if the chain's remainder
//     was larger (up to 1e-6 of its scale): the chain amplifies rounding, f(r) does not.
// In effect, two real roots closer than ~1e-5 of the polynomial's root scale may be read as
// one double root (no crossing); 1e-4 apart they practically never are. In stress tests
// with 2.6 million polynomials built from exact multiple roots (every row of Table 8.1,
// coefficients scaled by 1e-12..1e20, roots in [-50, 50] or [0, 1000], at least 1 % of the
// range apart) every multiplicity was recovered.

#include <array>
#include <vector>

#include "kew/kinetic/polynomial.hpp"

namespace kew::kinetic {

/// A remainder coefficient below this fraction of the magnitude of the terms that produced
/// it (its cancellation scale) is rounding noise and treated as zero. Chosen from stress
/// tests: 1e-11 misses ~1e-4 of rounded triple and double-double roots, 1e-9 merges a
/// quarter of the pairs of distinct roots 3e-5 (relative) apart, 2e-10 neither.
inline constexpr double kSturmRelativeTolerance = 2e-10;

/// |f(r)| ≤ kDoubleRootBackwardTolerance · Σ|c_i||r|^i at a critical point r of f means f has
/// a double root at r up to the rounding of its coefficients (≈ 500 ulps).
inline constexpr double kDoubleRootBackwardTolerance = 1e-13;

/// A leading coefficient whose term stays below this fraction of the others on the disk
/// holding their roots is dropped: it only places a root ~1e10 times farther out than the
/// rest, and is in practice the rounding residue of a term that cancels exactly.
inline constexpr double kNegligibleLeadingTermTolerance = 1e-10;

/// Roots in (lo, lo + kStartToleranceSeconds] are treated as roots exactly at lo by
/// first_positive_crossing: a certificate rebuilt at an event time has a root at 0 that
/// rounding may push a few femtoseconds into the future, and that root must not be
/// reported as a new event nor make the certificate look violated.
inline constexpr double kStartToleranceSeconds = 1e-9;

/// Sturm sequence of a polynomial of degree ≤ 4 (thesis Eq. 7.8), built with a relative
/// tolerance so that remainders that vanish up to rounding are treated as zero.
///
/// Each stored element is a positive multiple of the textbook element (scaled by a power
/// of two so that its largest |coefficient| is in [1, 2)), which leaves every sign, and so
/// every count, unchanged.
/// The variable is the caller's t (seconds). No heap allocation.
class SturmSequence {
 public:
  static constexpr int kMaxSize = Polynomial::kMaxDegree + 1;

  /// p: any polynomial of degree ≤ 4 with finite coefficients (any magnitude).
  /// The zero polynomial gives a one-element sequence {0} that counts no roots;
  /// a nonzero constant gives {c}.
  explicit SturmSequence(const Polynomial& p);

  /// Number of polynomials m (1..5).
  int size() const { return size_; }
  /// f_{i+1} for i in [0, size()): operator[](0) is f (normalised), operator[](1) is f'.
  const Polynomial& operator[](int i) const;
  /// f_m, the gcd of f and f' up to a constant: its roots are exactly the multiple roots
  /// of f, each with multiplicity decreased by one.
  const Polynomial& last() const { return (*this)[size_ - 1]; }

  /// Degree of f (-1 for the zero polynomial), after dropping negligible leading
  /// coefficients (see the tolerance model above): may be less than p.degree().
  int degree() const { return degrees_[0]; }
  /// Degree of f_m: 0 when every root of f (real or complex) is simple (and for a nonzero
  /// constant), -1 for f = 0.
  int gcd_degree() const { return degrees_[size_ - 1]; }
  /// Every real root of f lies in the open interval (-root_bound(), root_bound()); seconds.
  /// Fujiwara's bound rounded up to a power of two.
  double root_bound() const { return root_bound_; }

  /// Number of sign changes V(x) in the sequence evaluated at x (zeros ignored); x in
  /// seconds, may be ±infinity. Non-increasing in x; it drops by one at each distinct root.
  int sign_changes(double x) const;
  /// Number of distinct real roots in the half-open interval (a, b] (seconds; a, b may be
  /// infinite). 0 when a ≥ b.
  int count_distinct_roots(double a, double b) const;

  /// Sign (-1, 0, +1) of the leading coefficient of f.
  int leading_sign() const { return leading_sign_; }

 private:
  void compute_changes_at_infinity();

  std::array<Polynomial, kMaxSize> elements_{};
  std::array<int, kMaxSize> degrees_{-1, -1, -1, -1, -1};
  // f_i / f_m, filled only when gcd_degree() > 0: counted on near multiple roots, where
  // every f_i vanishes (see sign_changes).
  std::array<std::array<double, Polynomial::kMaxDegree + 1>, kMaxSize> reduced_{};
  std::array<int, kMaxSize> reduced_degrees_{};
  int size_ = 1;
  int changes_at_plus_infinity_ = 0;
  int changes_at_minus_infinity_ = 0;
  int leading_sign_ = 0;
  double root_bound_ = 1.0;
};

/// A distinct real root: t in seconds, multiplicity in 1..4.
struct Root {
  double t;
  int multiplicity;
};

/// All distinct real roots of p in (a, b] (seconds; a, b may be infinite) with their
/// multiplicities, ascending. Empty for the zero polynomial and for constants.
/// Used by tests and diagnostics; the engine uses first_positive_crossing.
std::vector<Root> real_roots(const Polynomial& p, double a, double b);

/// Multiset of the multiplicities of all real roots of p, sorted descending, derived as
/// in Table 8.1 from the Sturm sequence and the roots of f_m (e.g. {2,1} for
/// (t-1)^2 (t-3), {} for (t^2+1)^2). Empty for the zero polynomial and for constants.
std::vector<int> real_root_multiplicities(const Polynomial& p);

/// Whether p < 0 on all of [−reach, reach] (reach ≥ 0, seconds), proved by the bound
/// first_positive_crossing tries first: |c_0| > Σ_{i≥1} |c_i|·reach^i (with a margin for the
/// rounding of the bound) and c_0 < 0. False when the bound cannot decide, whatever p is.
bool certainly_negative(const Polynomial& p, double reach);

/// Result of first_positive_crossing; times in seconds.
struct Crossing {
  bool found = false;              // an odd-multiplicity root in (lo, hi] where p goes from < 0 to > 0
  double time = 0.0;               // its time when found
  bool violated_at_start = false;  // p > 0 immediately after lo (already violated): found = false then
  int tangencies = 0;              // even-multiplicity roots met in (lo, time] (or (lo, hi] if none found)
  int roots_counted = 0;           // distinct roots counted by the Sturm sequence on (lo, hi]
};

/// The first time in (lo, hi] at which p changes sign from negative to positive at a root
/// of odd multiplicity (the certificate becomes violated). lo is finite (usually 0 = now),
/// hi > lo may be +infinity; seconds.
///
/// - The zero polynomial never crosses and is never violated.
/// - Even-multiplicity roots are tangencies (thesis Lemma 6): counted, never crossings.
/// - Odd roots where p goes from positive to negative are not crossings.
/// - Roots in (lo, lo + start_tolerance] count as roots at lo. violated_at_start tells
///   whether p > 0 just after them; a root at lo where p goes + → - is simply ignored.
/// - Counts roots with the Sturm sequence first and returns as soon as the answer is
///   known: no root is computed when (lo, hi] holds none, or when p is already violated,
///   and at most one root is located otherwise (all of them, in closed form, when p has
///   multiple roots: Table 8.1 / Alg. 4).
/// - Before even building the sequence, for finite hi, a certified bound may prove that p
///   has no root on (lo, hi] (|c_0| > Σ_{i≥1} |c_i| R^i with R = max(|lo|, |hi|)); the
///   answer is then the sign of p(0) and roots_counted is 0. This settles most
///   certificates of a short horizon in a few multiplications.
/// No heap allocation.
Crossing first_positive_crossing(const Polynomial& p, double lo, double hi,
                                 double start_tolerance = kStartToleranceSeconds);

}  // namespace kew::kinetic
