#pragma once
// Planar points and vectors of the projected plane. Units: metres (positions),
// metres per second (velocities), unless a caller documents otherwise.

#include <cmath>

namespace kew::geometry {

struct Vector2 {
  double x = 0.0;
  double y = 0.0;

  friend constexpr Vector2 operator+(Vector2 a, Vector2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vector2 operator-(Vector2 a, Vector2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vector2 operator*(double s, Vector2 a) { return {s * a.x, s * a.y}; }
  friend constexpr bool operator==(Vector2 a, Vector2 b) = default;
};

/// A position in the plane (metres). Kept distinct from Vector2 only by name.
using Point2 = Vector2;

constexpr double dot(Vector2 a, Vector2 b) { return a.x * b.x + a.y * b.y; }
constexpr double cross(Vector2 a, Vector2 b) { return a.x * b.y - a.y * b.x; }
inline double norm(Vector2 a) { return std::hypot(a.x, a.y); }
inline bool is_finite(Vector2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }

}  // namespace kew::geometry
