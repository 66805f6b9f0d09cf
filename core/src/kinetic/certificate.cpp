#include "kew/kinetic/certificate.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace kew::kinetic {
namespace {

/// Coordinates of q − base as linear polynomials in τ.
struct RelativeLinear {
  Polynomial x;
  Polynomial y;
};

RelativeLinear relative(const Trajectory& base, const Trajectory& q, double now) {
  // Positions at now are the same doubles the exact predicates see.
  const auto pb = base.at(now);
  const auto pq = q.at(now);
  return {Polynomial{pq.x - pb.x, q.velocity.x - base.velocity.x},
          Polynomial{pq.y - pb.y, q.velocity.y - base.velocity.y}};
}

Polynomial absolute(const Polynomial& p) {
  Polynomial r;
  for (int k = 0; k <= Polynomial::kMaxDegree; ++k) r.set_coefficient(k, std::abs(p.coefficient(k)));
  return r;
}

RelativeLinear absolute(const RelativeLinear& r) { return {absolute(r.x), absolute(r.y)}; }

/// Zeroes the coefficients that are rounding noise: a coefficient no larger than a few
/// ulps of the sum of the magnitudes of the terms that produced it carries no sign.
/// Without this, an exactly-zero leading coefficient computed as 3e-5 adds a spurious
/// root near 1e15 s that ruins the root isolation of the real ones.
Polynomial without_noise(Polynomial p, const Polynomial& magnitude) {
  constexpr double kNoiseUlps = 64.0 * std::numeric_limits<double>::epsilon();
  for (int k = 0; k <= Polynomial::kMaxDegree; ++k)
    if (std::abs(p.coefficient(k)) <= kNoiseUlps * magnitude.coefficient(k)) p.set_coefficient(k, 0.0);
  return p;
}

/// Coefficients {c0, c1, c2} of a polynomial of degree ≤ 2. The certificate is built
/// from these with the operations written out: the general Polynomial product spent
/// most of its time finding degrees, and this function was a fifth of the engine's.
/// Terms are summed in the order Polynomial's product sums them, so the values are the
/// same doubles.
struct Quadratic {
  double c0, c1, c2;
};

Quadratic times(const Polynomial& a, const Polynomial& b) {  // both of degree ≤ 1
  const double a0 = a.coefficient(0), a1 = a.coefficient(1);
  const double b0 = b.coefficient(0), b1 = b.coefficient(1);
  return {a0 * b0, a0 * b1 + a1 * b0, a1 * b1};
}

Quadratic operator+(const Quadratic& a, const Quadratic& b) { return {a.c0 + b.c0, a.c1 + b.c1, a.c2 + b.c2}; }
Quadratic operator-(const Quadratic& a, const Quadratic& b) { return {a.c0 - b.c0, a.c1 - b.c1, a.c2 - b.c2}; }

/// a·b + c·d + e·f, each product of degree ≤ 4, summed left to right.
Polynomial sum_of_products(const Quadratic& a, const Quadratic& b, const Quadratic& c, const Quadratic& d,
                           const Quadratic& e, const Quadratic& f) {
  const auto product = [](const Quadratic& x, const Quadratic& y) {
    return std::array<double, 5>{x.c0 * y.c0, x.c0 * y.c1 + x.c1 * y.c0, x.c0 * y.c2 + x.c1 * y.c1 + x.c2 * y.c0,
                                 x.c1 * y.c2 + x.c2 * y.c1, x.c2 * y.c2};
  };
  const auto p = product(a, b), q = product(c, d), r = product(e, f);
  Polynomial out;
  for (int k = 0; k <= Polynomial::kMaxDegree; ++k) {
    const auto i = static_cast<std::size_t>(k);
    out.set_coefficient(k, p[i] + q[i] + r[i]);
  }
  return out;
}

Polynomial lifted_determinant(const RelativeLinear& u, const RelativeLinear& v, const RelativeLinear& w,
                              bool magnitudes) {
  const Quadratic u2 = times(u.x, u.x) + times(u.y, u.y);
  const Quadratic v2 = times(v.x, v.x) + times(v.y, v.y);
  const Quadratic w2 = times(w.x, w.x) + times(w.y, w.y);
  if (magnitudes) {
    // Every term counted with its absolute value: a bound on the rounding error scale.
    return sum_of_products(u2, times(v.x, w.y) + times(w.x, v.y), v2, times(w.x, u.y) + times(u.x, w.y), w2,
                           times(u.x, v.y) + times(v.x, u.y));
  }
  return sum_of_products(u2, times(v.x, w.y) - times(w.x, v.y), v2, times(w.x, u.y) - times(u.x, w.y), w2,
                         times(u.x, v.y) - times(v.x, u.y));
}

}  // namespace

Polynomial incircle_polynomial(const Trajectory& a, const Trajectory& b, const Trajectory& c, const Trajectory& d,
                               double now) {
  // Rows a−d, b−d, c−d of the 3×3 lifted determinant.
  const RelativeLinear u = relative(d, a, now);
  const RelativeLinear v = relative(d, b, now);
  const RelativeLinear w = relative(d, c, now);
  return without_noise(lifted_determinant(u, v, w, false),
                       lifted_determinant(absolute(u), absolute(v), absolute(w), true));
}

Polynomial orientation_polynomial(const Trajectory& a, const Trajectory& b, const Trajectory& c, double now) {
  const RelativeLinear u = relative(a, b, now);
  const RelativeLinear v = relative(a, c, now);
  const RelativeLinear au = absolute(u), av = absolute(v);
  return without_noise(u.x * v.y - u.y * v.x, au.x * av.y + au.y * av.x);
}

Polynomial dot_polynomial(const Trajectory& a, const Trajectory& b, const Trajectory& c, double now) {
  const RelativeLinear u = relative(a, b, now);
  const RelativeLinear v = relative(a, c, now);
  const RelativeLinear au = absolute(u), av = absolute(v);
  return without_noise(u.x * v.x + u.y * v.y, au.x * av.x + au.y * av.y);
}

}  // namespace kew::kinetic
