#include "kew/kinetic/certificate.hpp"

#include <cmath>
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

Polynomial lifted_determinant(const RelativeLinear& u, const RelativeLinear& v, const RelativeLinear& w,
                              bool magnitudes) {
  const Polynomial u2 = u.x * u.x + u.y * u.y;
  const Polynomial v2 = v.x * v.x + v.y * v.y;
  const Polynomial w2 = w.x * w.x + w.y * w.y;
  if (magnitudes) {
    // Every term counted with its absolute value: a bound on the rounding error scale.
    return u2 * (v.x * w.y + w.x * v.y) + v2 * (w.x * u.y + u.x * w.y) + w2 * (u.x * v.y + v.x * u.y);
  }
  const Polynomial vw = v.x * w.y - w.x * v.y;  // degree ≤ 2
  const Polynomial wu = w.x * u.y - u.x * w.y;
  const Polynomial uv = u.x * v.y - v.x * u.y;
  return u2 * vw + v2 * wu + w2 * uv;
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
