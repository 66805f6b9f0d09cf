#include "kew/kinetic/sturm.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

namespace kew::kinetic {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kMaxCoefficients = Polynomial::kMaxDegree + 1;

// Each bisection step halves the interval; 200 halvings exhaust any double interval, so the
// cap only stops on a cluster the sequence counts as several roots that doubles cannot split.
constexpr int kMaxIsolationSteps = 200;
// Bisection alone needs ~60 steps from an isolating interval to full precision.
constexpr int kMaxRefinementSteps = 100;
// Polishing starts from closed forms already accurate to ~1e-8 relative: Newton needs 2-3.
constexpr int kMaxPolishSteps = 8;
// Below this a root time is exact for every purpose of the engine (seconds).
constexpr double kRootAbsoluteToleranceSeconds = 1e-15;
// Root bounds are powers of two; beyond 2^1000 evaluating the polynomial overflows anyway.
constexpr int kMaxRootBoundExponent = 1000;
// A remainder coefficient this close to its cancellation scale is indistinguishable from 0.
constexpr double kNoiseTolerance = 64.0 * std::numeric_limits<double>::epsilon();
// A constant remainder after a linear element below this fraction of its cancellation scale
// is worth testing for a double root (see double_root_backward_error); above it, no.
constexpr double kCandidateTolerance = 1e-6;
// The time scale below which "far" means nothing to the engine (see leading_term_is_negligible).
constexpr double kUnitTimeSeconds = 1.0;
// Within this relative distance of zero, f_m's value no longer tells its sign, so the
// sequence itself is unreliable there and the reduced one is used (see sign_changes).
constexpr double kNearMultipleRootTolerance = 1e-8;
// Horner on degree ≤ 4 errs by at most ~2·4 ulps of Σ |c_i| |x|^i; twice that is noise.
constexpr double kEvaluationNoise = 16.0 * std::numeric_limits<double>::epsilon();

// Factor on a bound computed in a handful of floating-point operations, covering their rounding.
constexpr double kExclusionMargin = 1.0 + 1e-12;

using Coefficients = std::array<double, kMaxCoefficients>;

int sign_of(double v) { return (v > 0.0) - (v < 0.0); }

double coefficient_at(const Coefficients& c, int i) { return c[static_cast<unsigned>(i)]; }
double& coefficient_at(Coefficients& c, int i) { return c[static_cast<unsigned>(i)]; }

// Horner on the first degree + 1 coefficients only: the hot loops know the degree already.
double evaluate(const Polynomial& p, int degree, double x) {
  if (degree < 0) return 0.0;
  double value = p.coefficient(degree);
  for (int i = degree - 1; i >= 0; --i) value = value * x + p.coefficient(i);
  return value;
}

struct ValueAndSlope {
  double value;
  double slope;
};

ValueAndSlope evaluate_with_slope(const Polynomial& p, int degree, double x) {
  if (degree < 0) return {0.0, 0.0};
  double value = p.coefficient(degree);
  double slope = 0.0;
  for (int i = degree - 1; i >= 0; --i) {
    slope = slope * x + value;
    value = value * x + p.coefficient(i);
  }
  return {value, slope};
}

Polynomial to_polynomial(const Coefficients& c) {
  Polynomial p;
  for (int i = 0; i < kMaxCoefficients; ++i) p.set_coefficient(i, coefficient_at(c, i));
  return p;
}

int ceil_div(int numerator, int positive_denominator) {
  return numerator >= 0 ? (numerator + positive_denominator - 1) / positive_denominator
                        : -((-numerator) / positive_denominator);
}

// floor(log2 |v|) for finite nonzero v, read from the bits: std::ilogb is a libm call and
// this runs several times per certificate.
int binary_exponent(double v) {
  const int biased = static_cast<int>((std::bit_cast<std::uint64_t>(v) >> 52) & 0x7ffU);
  return biased != 0 ? biased - 1023 : std::ilogb(v);  // subnormals are rare: libm is fine
}

// 2^e exactly. Multiplying by it rescales without rounding, so normalisation never
// perturbs a coefficient and costs no division.
double power_of_two(int e) {
  if (e < -1022 || e > 1023) return std::ldexp(1.0, e);
  return std::bit_cast<double>(static_cast<std::uint64_t>(e + 1023) << 52);
}

// Scales c[0..degree] by a power of two so that its largest |coefficient| is in [1, 2).
void normalise(Coefficients& c, int degree) {
  double largest = 0.0;
  for (int i = 0; i <= degree; ++i) largest = std::max(largest, std::abs(coefficient_at(c, i)));
  const double factor = power_of_two(-binary_exponent(largest));
  for (int i = 0; i <= degree; ++i) coefficient_at(c, i) *= factor;
}

// Fujiwara's bound 2·max_i |c_i/c_n|^(1/(n-i)) rounded up to a power of two, from exponents
// only: no pow() on the hot path, and a power of two keeps the bisection midpoints exact.
double root_bound_of(const Coefficients& c, int degree) {
  if (degree <= 0) return 1.0;
  const int lead_exponent = binary_exponent(coefficient_at(c, degree));
  bool any_lower = false;
  int largest_exponent = std::numeric_limits<int>::min();
  for (int i = 0; i < degree; ++i) {
    if (coefficient_at(c, i) == 0.0) continue;
    any_lower = true;
    // |c_i / c_n| < 2^(e_i + 1 - e_n), so its (n-i)-th root is below 2^k.
    const int k = ceil_div(binary_exponent(coefficient_at(c, i)) + 1 - lead_exponent, degree - i);
    largest_exponent = std::max(largest_exponent, k);
  }
  if (!any_lower) return 1.0;  // c·t^n: the only root is 0
  // Fujiwara's factor 2 gives +1; one more doubling keeps clear of rounding at the bound.
  return power_of_two(std::min(largest_exponent + 2, kMaxRootBoundExponent));
}

// -rem(a, b) for deg b < deg a, as the next element of a Sturm sequence. The rounding error
// of each remainder coefficient is a few ulps of the terms summed to produce it (the
// coefficient of a and the products quotient × b), not of the result, so a coefficient
// below `tolerance` times that cancellation scale is noise. Trailing noise is dropped.
// Returns the degree of the result (normalised, see normalise()), or -1 when the whole
// remainder is noise: b divides a up to rounding.
int negated_remainder(const Coefficients& a, int a_degree, const Coefficients& b, int b_degree,
                      double tolerance, Coefficients& out) {
  Coefficients r = a;
  Coefficients scale{};
  for (int i = 0; i <= a_degree; ++i) coefficient_at(scale, i) = std::abs(coefficient_at(a, i));
  // One division per remainder: divisions are the latency chain of this whole function.
  const double inverse_b_lead = 1.0 / coefficient_at(b, b_degree);
  for (int shift = a_degree - b_degree; shift >= 0; --shift) {
    const int top = b_degree + shift;
    const double quotient = coefficient_at(r, top) * inverse_b_lead;
    for (int j = 0; j < b_degree; ++j) {
      const double term = quotient * coefficient_at(b, j);
      coefficient_at(r, j + shift) -= term;
      coefficient_at(scale, j + shift) += std::abs(term);
    }
    coefficient_at(r, top) = 0.0;  // eliminated by construction of the quotient
  }

  int degree = b_degree - 1;
  while (degree >= 0 && std::abs(coefficient_at(r, degree)) <= tolerance * coefficient_at(scale, degree))
    --degree;
  if (degree < 0) return -1;

  out.fill(0.0);
  for (int i = 0; i <= degree; ++i) coefficient_at(out, i) = -coefficient_at(r, i);
  normalise(out, degree);
  return degree;
}

double evaluate(const Coefficients& c, int degree, double x) {
  if (degree < 0) return 0.0;
  double value = coefficient_at(c, degree);
  for (int i = degree - 1; i >= 0; --i) value = value * x + coefficient_at(c, i);
  return value;
}

// Sign of c(x), or 0 when |c(x)| is within the rounding error of Horner's scheme
// (a few ulps of Σ |c_i| |x|^i per step).
template <typename Coefficient>
int sign_beyond_rounding_of(Coefficient coefficient, int degree, double x) {
  double value = 0.0;
  double magnitude = 0.0;
  for (int i = degree; i >= 0; --i) {
    value = value * x + coefficient(i);
    magnitude = magnitude * std::abs(x) + std::abs(coefficient(i));
  }
  if (std::abs(value) <= kEvaluationNoise * magnitude) return 0;
  return sign_of(value);
}

int sign_beyond_rounding(const Coefficients& c, int degree, double x) {
  return sign_beyond_rounding_of([&c](int i) { return coefficient_at(c, i); }, degree, x);
}

int sign_beyond_rounding(const Polynomial& p, int degree, double x) {
  return sign_beyond_rounding_of([&p](int i) { return p.coefficient(i); }, degree, x);
}

// Σ |c_i| |x|^i: the size of the terms summed in c(x), which is what rounding is relative to.
double magnitude_of_terms(const Coefficients& c, int degree, double x) {
  double value = 0.0;
  for (int i = degree; i >= 0; --i) value = value * std::abs(x) + std::abs(coefficient_at(c, i));
  return value;
}

// A leading coefficient is negligible when, on the disk of radius B ≥ 1 s holding every
// root of the lower-degree part, its term is below kNegligibleLeadingTermTolerance of the
// others: its only effect is a root beyond ~B / tolerance ≥ 1e10 s. Such coefficients are
// what cancellation leaves of terms that are exactly zero (e.g. the t^3 and t^4 terms of an
// incircle certificate when only one point moves), and the far root they create would
// wreck the remainder chain (a quotient of 1e18 cancels every digit of the remainder).
bool leading_term_is_negligible(const Coefficients& c, int degree) {
  // The bound is at least one second: relative to roots near 0 every root is "far", and a
  // root at 3 s next to one at 1e-12 s is exactly the kind the engine must not lose.
  const double bound = std::max(root_bound_of(c, degree - 1), kUnitTimeSeconds);
  const double inverse_bound = 1.0 / bound;  // exact: a power of two
  // Both sides divided by B^(degree-1) so that nothing overflows for large bounds.
  double others = 0.0;
  double weight = 1.0;
  for (int i = degree - 1; i >= 0; --i) {
    others += std::abs(coefficient_at(c, i)) * weight;
    weight *= inverse_bound;
  }
  return std::abs(coefficient_at(c, degree)) * bound <= kNegligibleLeadingTermTolerance * others;
}

// Backward error of "f has a double root near `estimate`": Newton on f' from the estimate
// finds the critical point r, and |f(r)| relative to the size of its terms says how far f
// is from having a double root there. Better conditioned than the chain's last remainder,
// which amplifies rounding: a double root 40 times farther from 0 than the other roots
// leaves a remainder of ~1e-9 of its scale, yet f(r) is ~1e-16 of its terms.
double double_root_backward_error(const Coefficients& f, int degree, double estimate) {
  Coefficients derivative{};
  for (int i = 1; i <= degree; ++i)
    coefficient_at(derivative, i - 1) = static_cast<double>(i) * coefficient_at(f, i);
  double x = estimate;
  for (int iteration = 0; iteration < 2 * kMaxPolishSteps; ++iteration) {
    double value = coefficient_at(derivative, degree - 1);
    double slope = 0.0;
    for (int i = degree - 2; i >= 0; --i) {
      slope = slope * x + value;
      value = value * x + coefficient_at(derivative, i);
    }
    if (value == 0.0 || slope == 0.0) break;
    const double step = value / slope;
    x -= step;
    if (!std::isfinite(x)) return kInfinity;
    if (std::abs(step) <= 4.0 * kEpsilon * std::abs(x)) break;
  }
  const double magnitude = magnitude_of_terms(f, degree, x);
  return magnitude > 0.0 ? std::abs(evaluate(f, degree, x)) / magnitude : 0.0;
}

// Quotient of a by b (deg b ≤ deg a), remainder dropped: used only where b divides a up
// to rounding. Normalised.
void quotient_of(const Coefficients& a, int a_degree, const Coefficients& b, int b_degree, Coefficients& q) {
  Coefficients r = a;
  q.fill(0.0);
  const double inverse_b_lead = 1.0 / coefficient_at(b, b_degree);
  for (int shift = a_degree - b_degree; shift >= 0; --shift) {
    const double term = coefficient_at(r, b_degree + shift) * inverse_b_lead;
    coefficient_at(q, shift) = term;
    for (int j = 0; j < b_degree; ++j) coefficient_at(r, j + shift) -= term * coefficient_at(b, j);
  }
  normalise(q, a_degree - b_degree);
}

}  // namespace

SturmSequence::SturmSequence(const Polynomial& p) {
  int degree = p.degree();
  degrees_[0] = degree;
  size_ = 1;
  if (degree < 0) return;  // zero polynomial: {0}, no sign ever, no root counted

  // Normalising keeps every element near 1 whatever the units (1e20 m^4 or 1e-9): no
  // overflow in evaluation, and the tolerance is purely relative.
  Coefficients f{};
  for (int i = 0; i <= degree; ++i) coefficient_at(f, i) = p.coefficient(i);
  normalise(f, degree);
  while (degree > 0 && leading_term_is_negligible(f, degree)) {
    coefficient_at(f, degree) = 0.0;
    --degree;
  }
  normalise(f, degree);
  elements_[0] = to_polynomial(f);
  degrees_[0] = degree;
  leading_sign_ = sign_of(coefficient_at(f, degree));
  root_bound_ = root_bound_of(f, degree);
  if (degree == 0) {
    compute_changes_at_infinity();
    return;
  }

  // Elements are built in place, each from the two before it: no copies on the hot path.
  std::array<Coefficients, kMaxSize> chain;
  chain[0] = f;
  Coefficients& derivative = chain[1];
  derivative.fill(0.0);
  for (int i = 1; i <= degree; ++i)
    coefficient_at(derivative, i - 1) = static_cast<double>(i) * coefficient_at(f, i);
  normalise(derivative, degree - 1);
  elements_[1] = to_polynomial(derivative);
  degrees_[1] = degree - 1;
  size_ = 2;

  while (degrees_[static_cast<unsigned>(size_ - 1)] > 0) {
    const unsigned previous = static_cast<unsigned>(size_ - 2);
    const unsigned current = static_cast<unsigned>(size_ - 1);
    const unsigned next = static_cast<unsigned>(size_);
    // A linear current element is the gcd exactly when f has a double root at its root,
    // which a backward-error test on f decides more reliably than the remainder; the
    // remainder then only has to be small enough to make the test worth running.
    const bool linear = degrees_[current] == 1;
    int next_degree = negated_remainder(chain[previous], degrees_[previous], chain[current], degrees_[current],
                                        linear ? kCandidateTolerance : kSturmRelativeTolerance, chain[next]);
    if (next_degree < 0) {
      // current looks like gcd(f, f'). A small remainder can also come from the chain's own
      // ill-conditioning, so confirm on f itself before believing it.
      Coefficients unused;
      bool confirmed = false;
      if (linear) {
        // Either f is a double root up to a few hundred ulps, or the chain and f agree
        // at the chain's own tolerance (clusters left by rounding a triple root).
        const double backward = double_root_backward_error(
            f, degree, -coefficient_at(chain[current], 0) / coefficient_at(chain[current], 1));
        confirmed = backward <= kDoubleRootBackwardTolerance ||
                    (backward <= kSturmRelativeTolerance &&
                     negated_remainder(chain[previous], degrees_[previous], chain[current], degrees_[current],
                                       kSturmRelativeTolerance, unused) < 0);
      } else {
        confirmed = negated_remainder(f, degree, chain[current], degrees_[current], kSturmRelativeTolerance, unused) < 0;
      }
      if (confirmed) break;
      // Not a gcd: the small remainder is real. Keep all of it that is above pure noise.
      next_degree = negated_remainder(chain[previous], degrees_[previous], chain[current], degrees_[current],
                                      kNoiseTolerance, chain[next]);
      if (next_degree < 0) break;  // indistinguishable from zero after all
    }
    elements_[next] = to_polynomial(chain[next]);
    degrees_[next] = next_degree;
    ++size_;
  }

  // With a gcd h of degree ≥ 1 every element vanishes at the multiple roots, where the
  // sign count would see only zeros. Counting on f_i / h instead (a proper Sturm sequence
  // with the same count everywhere else) keeps V right at and around those roots.
  const int gcd = gcd_degree();
  if (gcd > 0) {
    const unsigned last = static_cast<unsigned>(size_ - 1);
    for (unsigned i = 0; i < last; ++i) {
      quotient_of(chain[i], degrees_[i], chain[last], gcd, reduced_[i]);
      reduced_degrees_[i] = degrees_[i] - gcd;
    }
    reduced_[last].fill(0.0);
    reduced_[last][0] = 1.0;
    reduced_degrees_[last] = 0;
  }
  compute_changes_at_infinity();
}

// Beyond every root the signs are those of the leading coefficients (times (-1)^degree
// towards -infinity); fixed once here so that infinite bounds cost nothing later.
void SturmSequence::compute_changes_at_infinity() {
  int previous_plus = 0;
  int previous_minus = 0;
  const bool reduced = gcd_degree() > 0;
  for (int i = 0; i < size_; ++i) {
    const unsigned index = static_cast<unsigned>(i);
    const int element_degree = reduced ? reduced_degrees_[index] : degrees_[index];
    const int plus = sign_of(reduced ? coefficient_at(reduced_[index], element_degree)
                                     : elements_[index].coefficient(element_degree));
    const int minus = (element_degree % 2 == 0) ? plus : -plus;
    if (previous_plus != 0 && plus != previous_plus) ++changes_at_plus_infinity_;
    if (previous_minus != 0 && minus != previous_minus) ++changes_at_minus_infinity_;
    previous_plus = plus;
    previous_minus = minus;
  }
}

const Polynomial& SturmSequence::operator[](int i) const {
  assert(i >= 0 && i < size_);
  return elements_[static_cast<unsigned>(i)];
}

int SturmSequence::sign_changes(double x) const {
  assert(!std::isnan(x));
  // No root of f lies beyond the bound and V only changes at roots of f; this also keeps
  // Horner away from overflow at huge |x|.
  if (x >= root_bound_) return changes_at_plus_infinity_;
  if (x <= -root_bound_) return changes_at_minus_infinity_;
  // Near a multiple root every element is a multiple of f_m and is rounding noise there;
  // f_i / f_m is not. Elsewhere the elements themselves are better: they are not the
  // result of a division, so an exact root evaluates to exactly zero.
  bool reduced = false;
  if (gcd_degree() > 0) {
    const unsigned last = static_cast<unsigned>(size_ - 1);
    const Polynomial& gcd = elements_[last];
    double value = 0.0;
    double magnitude = 0.0;
    for (int i = degrees_[last]; i >= 0; --i) {
      value = value * x + gcd.coefficient(i);
      magnitude = magnitude * std::abs(x) + std::abs(gcd.coefficient(i));
    }
    reduced = std::abs(value) <= kNearMultipleRootTolerance * magnitude;
  }
  // f itself within rounding of zero counts as zero: x is then taken as the root, V(x)
  // equals V just after x, and (a, b] includes a root at b and excludes one at a instead of
  // assigning it to a side by the last bit. The other elements need no such care: where
  // one vanishes its neighbours have opposite signs, so its own sign never matters.
  int previous = reduced ? sign_beyond_rounding(reduced_[0], reduced_degrees_[0], x)
                         : sign_beyond_rounding(elements_[0], degrees_[0], x);
  int changes = 0;
  for (int i = 1; i < size_; ++i) {
    const unsigned index = static_cast<unsigned>(i);
    const double value = reduced ? evaluate(reduced_[index], reduced_degrees_[index], x)
                                 : evaluate(elements_[index], degrees_[index], x);
    const int s = sign_of(value);
    if (s == 0) continue;
    if (previous != 0 && s != previous) ++changes;
    previous = s;
  }
  return changes;
}

int SturmSequence::count_distinct_roots(double a, double b) const {
  if (!(a < b)) return 0;
  // V is non-increasing in exact arithmetic; rounding right at a root must not make a
  // count negative.
  return std::max(0, sign_changes(a) - sign_changes(b));
}

namespace {

// Sign of f just after a point where the sequence has `changes` sign changes, when every
// real root is simple: each of the V(x) - V(+inf) roots beyond x flips the sign once, and
// beyond all roots f has the sign of its leading coefficient. Exact with respect to the
// sequence: no evaluation of f next to a root.
int sign_after_if_square_free(const SturmSequence& sequence, int changes) {
  const int roots_beyond = changes - sequence.sign_changes(kInfinity);
  return (roots_beyond % 2 == 0) ? sequence.leading_sign() : -sequence.leading_sign();
}

// Sign of f on (lo, hi] known to hold no root: far from any root is where a single
// evaluation is trustworthy.
int sign_on_root_free_interval(const SturmSequence& sequence, double lo, double hi) {
  if (!std::isfinite(hi) || hi >= sequence.root_bound()) return sequence.leading_sign();
  return sign_of(evaluate(sequence[0], sequence.degree(), 0.5 * lo + 0.5 * hi));
}

// Safeguarded Newton (Newton inside a bracket, bisection when Newton leaves it or stalls)
// for the single simple root in (a, b]; f has sign `sign_left` on (a, root).
double refine_simple_root(const Polynomial& f, int degree, double a, double b, int sign_left) {
  double x = 0.5 * a + 0.5 * b;
  double step_before_last = b - a;
  double last_step = step_before_last;
  for (int iteration = 0; iteration < kMaxRefinementSteps; ++iteration) {
    const ValueAndSlope at_x = evaluate_with_slope(f, degree, x);
    const int s = sign_of(at_x.value);
    if (s == 0) return x;
    if (s == sign_left)
      a = x;
    else
      b = x;
    const double tolerance = std::max(kRootAbsoluteToleranceSeconds, 4.0 * kEpsilon * std::abs(x));
    if (b - a <= tolerance) return x;
    double next = 0.0;
    bool newton_usable = false;
    if (at_x.slope != 0.0) {
      next = x - at_x.value / at_x.slope;
      // Newton must stay inside the bracket and at least halve the step every other
      // iteration, otherwise bisection guarantees progress.
      newton_usable = next > a && next < b &&
                      std::abs(2.0 * at_x.value) <= std::abs(step_before_last * at_x.slope);
    }
    step_before_last = last_step;
    if (newton_usable) {
      last_step = x - next;
      x = next;
    } else {
      last_step = 0.5 * (b - a);
      x = a + last_step;
    }
    if (std::abs(last_step) <= tolerance) return x;
  }
  return x;
}

struct LocatedRoot {
  double t;
  double isolating_right;        // (.., isolating_right] holds this root and no later one
  int changes_at_isolating_right;
};

// Smallest root in (a, b], given V(a) - V(b) ≥ 1, treating roots as simple. Bisects on
// Sturm counts until the root is alone, then refines it; nothing else is computed.
LocatedRoot locate_first_root(const SturmSequence& sequence, double a, int changes_at_a, double b,
                              int changes_at_b) {
  // Clamping to the root bound changes no count, and makes infinite ends finite.
  double left = std::max(a, -sequence.root_bound());
  double right = std::min(b, sequence.root_bound());
  int changes_left = changes_at_a;
  int changes_right = changes_at_b;
  for (int step = 0; changes_left - changes_right > 1 && step < kMaxIsolationSteps; ++step) {
    const double middle = 0.5 * left + 0.5 * right;
    if (!(middle > left && middle < right)) break;
    const int changes_middle = sequence.sign_changes(middle);
    if (changes_left - changes_middle >= 1) {
      right = middle;
      changes_right = changes_middle;
    } else {
      left = middle;
      changes_left = changes_middle;
    }
  }
  const int sign_left = sign_after_if_square_free(sequence, changes_left);
  const double t = refine_simple_root(sequence[0], sequence.degree(), left, right, sign_left);
  return {t, right, changes_right};
}

// Newton on q from a closed-form estimate x, kept only while |q| decreases and within
// max_move of the estimate, so it can neither wander to a neighbouring root nor make the
// estimate worse.
double polish(const Polynomial& q, double x, double max_move) {
  const int degree = q.degree();
  const double start = x;
  double value = evaluate(q, degree, x);
  for (int iteration = 0; iteration < kMaxPolishSteps && value != 0.0; ++iteration) {
    const ValueAndSlope at_x = evaluate_with_slope(q, degree, x);
    if (at_x.slope == 0.0) break;
    const double next = x - at_x.value / at_x.slope;
    if (!std::isfinite(next) || std::abs(next - start) > max_move) break;
    const double next_value = evaluate(q, degree, next);
    if (!(std::abs(next_value) < std::abs(value))) break;
    const bool converged = std::abs(next - x) <= 4.0 * kEpsilon * std::abs(next);
    x = next;
    value = next_value;
    if (converged) break;
  }
  return x;
}

// Real roots of a x^2 + b x + c without cancellation; a negative discriminant is clamped
// to zero because callers only ask when the Sturm count says the roots are real.
int quadratic_roots(double a, double b, double c, double& first, double& second) {
  if (a == 0.0) {
    if (b == 0.0) return 0;
    first = second = -c / b;
    return 1;
  }
  const double discriminant = std::max(0.0, b * b - 4.0 * a * c);
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  if (q == 0.0) {
    first = second = 0.0;
    return 2;
  }
  first = q / a;
  second = c / q;
  if (first > second) std::swap(first, second);
  return 2;
}

// All real roots with multiplicities, fixed size.
struct RootSet {
  std::array<Root, Polynomial::kMaxDegree> roots{};
  int count = 0;
  bool consistent = false;  // false: the sequence's gcd and counts contradict Table 8.1

  void add(double t, int multiplicity) {
    roots[static_cast<unsigned>(count)] = Root{t, multiplicity};
    ++count;
  }
  // Insertion sort: at most four elements.
  void sort() {
    for (int i = 1; i < count; ++i)
      for (int j = i; j > 0 && roots[static_cast<unsigned>(j)].t < roots[static_cast<unsigned>(j - 1)].t; --j)
        std::swap(roots[static_cast<unsigned>(j)], roots[static_cast<unsigned>(j - 1)]);
  }
};

double distance_to_nearest(const RootSet& set, double t) {
  double nearest = kInfinity;
  for (int i = 0; i < set.count; ++i) nearest = std::min(nearest, std::abs(set.roots[static_cast<unsigned>(i)].t - t));
  return nearest;
}

// Table 8.1 with Alg. 4's deflation, for f with multiple roots (gcd degree ≥ 1): the roots
// of f_m give the multiple roots and their multiplicities, the Sturm count over the whole
// line says how many distinct real roots f has, and the quotient of f by the multiple
// factors (degree ≤ 2) gives the simple ones in closed form. Each root is then polished on
// the derivative in which it is simple. Rare in practice (tangencies), so it computes all.
RootSet roots_from_gcd(const SturmSequence& sequence) {
  RootSet set;
  const Polynomial& f = sequence[0];
  const Polynomial& gcd = sequence.last();
  const int n = sequence.degree();
  const int g = sequence.gcd_degree();
  const int distinct = sequence.count_distinct_roots(-kInfinity, kInfinity);
  const Polynomial f1 = f.derivative();
  const double scale = sequence.root_bound();
  auto c = [&f](int i) { return f.coefficient(i); };

  if (g == n - 1) {
    // f = c (t - r)^n: r is the mean of the roots, read off the two top coefficients.
    if (distinct != 1) return set;
    set.add(-c(n - 1) / (static_cast<double>(n) * c(n)), n);
  } else if (n == 3 && g == 1) {
    // {2, 1}: f = (t - r)^2 (f3 t + b), so the simple root follows from Vieta.
    if (distinct != 2) return set;
    const double double_root = polish(f1, -gcd.coefficient(0) / gcd.coefficient(1), scale);
    const double simple_root = -c(2) / c(3) - 2.0 * double_root;
    set.add(double_root, 2);
    set.add(polish(f, simple_root, 0.5 * distance_to_nearest(set, simple_root)), 1);
  } else if (n == 4 && g == 1) {
    // {2} or {2, 1, 1}: deflate by (t - r)^2, the quotient is quadratic.
    if (distinct != 1 && distinct != 3) return set;
    const double r = polish(f1, -gcd.coefficient(0) / gcd.coefficient(1), scale);
    set.add(r, 2);
    if (distinct == 3) {
      const double qa = c(4);
      const double qb = c(3) + 2.0 * r * qa;
      const double qc = c(2) + 2.0 * r * qb - r * r * qa;
      double first = 0.0;
      double second = 0.0;
      if (quadratic_roots(qa, qb, qc, first, second) != 2) return set;
      const double first_move = 0.5 * std::min(std::abs(first - r), std::abs(second - first));
      const double second_move = 0.5 * std::min(std::abs(second - r), std::abs(second - first));
      set.add(polish(f, first, first_move), 1);
      set.add(polish(f, second, second_move), 1);
    }
  } else if (n == 4 && g == 2) {
    // {2, 2}, {3, 1}, or a double complex pair; f_m tells which by its own Sturm sequence.
    if (distinct == 0) {
      set.consistent = true;
      return set;
    }
    if (distinct != 2) return set;
    const SturmSequence gcd_sequence(gcd);
    if (gcd_sequence.gcd_degree() == 1) {
      // f_m = (t - a)^2: a triple root of f (a simple root of f''), plus one simple root.
      const double triple_root = polish(f1.derivative(), -gcd.coefficient(1) / (2.0 * gcd.coefficient(2)), scale);
      const double simple_root = -c(3) / c(4) - 3.0 * triple_root;
      set.add(triple_root, 3);
      set.add(polish(f, simple_root, 0.5 * distance_to_nearest(set, simple_root)), 1);
    } else if (gcd_sequence.count_distinct_roots(-kInfinity, kInfinity) == 2) {
      double first = 0.0;
      double second = 0.0;
      if (quadratic_roots(gcd.coefficient(2), gcd.coefficient(1), gcd.coefficient(0), first, second) != 2)
        return set;
      const double move = 0.5 * (second - first);
      set.add(polish(f1, first, move), 2);
      set.add(polish(f1, second, move), 2);
    } else {
      return set;
    }
  } else {
    return set;
  }
  set.sort();
  for (int i = 1; i < set.count; ++i)
    if (!(set.roots[static_cast<unsigned>(i - 1)].t < set.roots[static_cast<unsigned>(i)].t)) return set;
  set.consistent = true;
  return set;
}

// Square-free reading of the sequence: every distinct root is simple. Exact when the gcd
// is a constant; also the fallback when the gcd contradicts Table 8.1 (rounding on the
// edge of the tolerance), where it at least stays consistent with the Sturm counts.
template <typename Visit>
void for_each_root_as_simple(const SturmSequence& sequence, double a, double b, Visit&& visit) {
  int changes_left = sequence.sign_changes(a);
  const int changes_right = sequence.sign_changes(b);
  double left = a;
  while (changes_left - changes_right > 0) {
    const LocatedRoot root = locate_first_root(sequence, left, changes_left, b, changes_right);
    visit(root.t);
    if (!(root.isolating_right > left)) break;
    left = root.isolating_right;
    changes_left = root.changes_at_isolating_right;
  }
}

}  // namespace

std::vector<Root> real_roots(const Polynomial& p, double a, double b) {
  std::vector<Root> roots;
  if (p.degree() <= 0 || !(a < b)) return roots;
  const SturmSequence sequence(p);
  if (sequence.gcd_degree() > 0) {
    const RootSet set = roots_from_gcd(sequence);
    if (set.consistent) {
      for (int i = 0; i < set.count; ++i) {
        const Root& root = set.roots[static_cast<unsigned>(i)];
        if (root.t > a && root.t <= b) roots.push_back(root);
      }
      return roots;
    }
  }
  for_each_root_as_simple(sequence, a, b, [&roots](double t) { roots.push_back(Root{t, 1}); });
  return roots;
}

std::vector<int> real_root_multiplicities(const Polynomial& p) {
  std::vector<int> multiplicities;
  if (p.degree() <= 0) return multiplicities;
  const SturmSequence sequence(p);
  if (sequence.gcd_degree() > 0) {
    const RootSet set = roots_from_gcd(sequence);
    if (set.consistent) {
      for (int i = 0; i < set.count; ++i) multiplicities.push_back(set.roots[static_cast<unsigned>(i)].multiplicity);
      std::sort(multiplicities.begin(), multiplicities.end(), std::greater<>());
      return multiplicities;
    }
  }
  multiplicities.assign(static_cast<unsigned>(sequence.count_distinct_roots(-kInfinity, kInfinity)), 1);
  return multiplicities;
}

namespace {
/// The sign p keeps on all of [−reach, reach] when the bound |c_0| > Σ_{i≥1} |c_i|·reach^i
/// proves it has no root there (for |t| ≤ reach, |p(t) − p(0)| is at most the sum);
/// 0 when the bound cannot decide. The margin covers the rounding of the bound (a few ulps).
int certified_sign(const Polynomial& p, double reach) {
  const int degree = p.degree();
  double power = 1.0;
  double excursion = 0.0;
  for (int i = 1; i <= degree; ++i) {
    power *= reach;
    excursion += std::abs(p.coefficient(i)) * power;
  }
  if (!(std::abs(p.coefficient(0)) > excursion * kExclusionMargin)) return 0;
  return p.coefficient(0) > 0.0 ? 1 : -1;
}
}  // namespace

bool certainly_negative(const Polynomial& p, double reach) { return certified_sign(p, reach) < 0; }

Crossing first_positive_crossing(const Polynomial& p, double lo, double hi, double start_tolerance) {
  assert(std::isfinite(lo) && !std::isnan(hi));
  Crossing result;
  if (!(hi > lo)) return result;
  const int degree = p.degree();
  if (degree <= 0) {
    result.violated_at_start = degree == 0 && p.coefficient(0) > 0.0;
    return result;
  }

  // Certified exclusion before any Sturm work: for |t| ≤ R, |f(t) − f(0)| ≤ Σ_{i≥1} |c_i| R^i,
  // so when |c_0| beats that bound f has no root at all on [−R, R] ⊇ (lo, hi] and keeps the
  // sign of c_0. With a short horizon this settles most certificates in a few multiplies.
  // The margin covers the rounding of the bound itself (a few ulps).
  if (std::isfinite(hi)) {
    const int sign = certified_sign(p, std::max(std::abs(lo), std::abs(hi)));
    if (sign != 0) {
      result.violated_at_start = sign > 0;
      return result;
    }
  }

  const SturmSequence sequence(p);
  const int changes_at_lo = sequence.sign_changes(lo);
  const int changes_at_hi = sequence.sign_changes(hi);
  result.roots_counted = std::max(0, changes_at_lo - changes_at_hi);
  const bool has_multiple_roots = sequence.gcd_degree() > 0;

  if (result.roots_counted == 0) {
    result.violated_at_start = (has_multiple_roots ? sign_on_root_free_interval(sequence, lo, hi)
                                                   : sign_after_if_square_free(sequence, changes_at_lo)) > 0;
    return result;
  }

  const double window_end = std::min(lo + std::max(start_tolerance, 0.0), hi);

  if (has_multiple_roots) {
    const RootSet set = roots_from_gcd(sequence);
    if (set.consistent) {
      // Walk the roots from +infinity, where f has its leading sign, back to the window:
      // the sign after each root follows from the parity of the multiplicities alone.
      int sign = sequence.leading_sign();
      for (int i = set.count - 1; i >= 0 && set.roots[static_cast<unsigned>(i)].t > window_end; --i)
        if (set.roots[static_cast<unsigned>(i)].multiplicity % 2 == 1) sign = -sign;
      result.violated_at_start = sign > 0;
      for (int i = 0; i < set.count; ++i) {
        const Root& root = set.roots[static_cast<unsigned>(i)];
        if (root.t <= lo) continue;
        if (root.t > hi) break;
        if (root.multiplicity % 2 == 0) {
          ++result.tangencies;
          continue;
        }
        if (root.t <= window_end || result.violated_at_start) continue;
        if (sign < 0) {
          result.found = true;
          result.time = root.t;
          break;
        }
        sign = -sign;
      }
      return result;
    }
  }

  const int changes_at_window_end = window_end > lo ? sequence.sign_changes(window_end) : changes_at_lo;
  if (sign_after_if_square_free(sequence, changes_at_window_end) > 0) {
    result.violated_at_start = true;
    return result;
  }
  if (changes_at_window_end - changes_at_hi <= 0) return result;
  // Negative after the window and every root simple: the next root is the crossing.
  const LocatedRoot first = locate_first_root(sequence, window_end, changes_at_window_end, hi, changes_at_hi);
  result.found = true;
  result.time = first.t;
  return result;
}

}  // namespace kew::kinetic
