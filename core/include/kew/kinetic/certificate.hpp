#pragma once
// Certificate polynomials of linearly moving points (thesis Eq. 6.1, 7.1), in time
// local to `now`: the variable is τ = t − now in seconds. Coordinates are taken
// relative to one of the points, so the coefficients depend on the configuration's
// size rather than on its distance from the projection origin.

#include "kew/kinetic/polynomial.hpp"
#include "kew/triangulation/delaunay.hpp"

namespace kew::kinetic {

using triangulation::Trajectory;

/// incircle(a, b, c, d)(now + τ): positive while d is inside the circle of the
/// counter-clockwise triangle abc. Degree ≤ 4. Units: m⁴.
Polynomial incircle_polynomial(const Trajectory& a, const Trajectory& b, const Trajectory& c, const Trajectory& d,
                               double now);

/// orient2d(a, b, c)(now + τ): positive while abc turns left. Degree ≤ 2. Units: m².
Polynomial orientation_polynomial(const Trajectory& a, const Trajectory& b, const Trajectory& c, double now);

/// (b − a)·(c − a) at now + τ. Degree ≤ 2. Units: m².
Polynomial dot_polynomial(const Trajectory& a, const Trajectory& b, const Trajectory& c, double now);

}  // namespace kew::kinetic
