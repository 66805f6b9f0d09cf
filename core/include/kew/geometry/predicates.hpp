#pragma once
// Exact static predicates on double coordinates: a floating-point filter with an
// exact fallback (CGAL's Epick kernel), so the sign returned is always the sign
// of the exact real determinant of the given doubles.

#include "kew/geometry/vector2.hpp"

namespace kew::geometry {

enum class Orientation : signed char { Clockwise = -1, Collinear = 0, CounterClockwise = 1 };

/// Where d lies relative to the circle through a, b, c, for a counter-clockwise
/// triangle abc (the sign flips for a clockwise one, as the determinant does).
enum class CircleSide : signed char { Outside = -1, On = 0, Inside = 1 };

/// Sign of det[b-a, c-a]: counter-clockwise when c is left of the directed line a→b.
Orientation orient2d(Point2 a, Point2 b, Point2 c);

/// Sign of the incircle determinant of (a,b,c,d) (thesis Eq. 2.4): Inside when d is
/// strictly inside the circumcircle of the counter-clockwise triangle abc.
CircleSide incircle(Point2 a, Point2 b, Point2 c, Point2 d);

inline int sign(Orientation o) { return static_cast<int>(o); }
inline int sign(CircleSide s) { return static_cast<int>(s); }

}  // namespace kew::geometry
