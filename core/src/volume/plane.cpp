#include "plane.hpp"

#include <algorithm>
#include <cstddef>

#include "kew/geometry/predicates.hpp"

namespace kew::volume::detail {

using geometry::Orientation;
using geometry::orient2d;

double distance_to_segment(Point2 p, Point2 a, Point2 b) {
  const geometry::Vector2 ab = b - a;
  const double length2 = dot(ab, ab);
  const double u = length2 > 0.0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return norm(p - (a + u * ab));
}

int locate(Point2 p, const PlaneRing& ring, double tolerance_m) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 a = ring[i];
    const Point2 b = ring[(i + 1) % n];
    if (distance_to_segment(p, a, b) <= tolerance_m) return 0;
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < x) inside = !inside;
    }
  }
  return inside ? 1 : -1;
}

namespace {
// c on the closed segment ab, given that a, b, c are collinear.
bool within_box(Point2 a, Point2 b, Point2 c) {
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}
}  // namespace

bool segments_touch(Point2 a, Point2 b, Point2 c, Point2 d) {
  const Orientation o1 = orient2d(a, b, c);
  const Orientation o2 = orient2d(a, b, d);
  const Orientation o3 = orient2d(c, d, a);
  const Orientation o4 = orient2d(c, d, b);
  const auto on_line = Orientation::Collinear;
  if (o1 != on_line && o2 != on_line && o3 != on_line && o4 != on_line)
    return o1 != o2 && o3 != o4;  // a proper crossing, or none
  return (o1 == on_line && within_box(a, b, c)) || (o2 == on_line && within_box(a, b, d)) ||
         (o3 == on_line && within_box(c, d, a)) || (o4 == on_line && within_box(c, d, b));
}

namespace {
// Distance (m) from p to the line through a and b (a ≠ b).
double distance_to_line(Point2 p, Point2 a, Point2 b) { return std::abs(cross(b - a, p - a)) / norm(b - a); }
}  // namespace

bool self_intersecting(const PlaneRing& ring, double tolerance_m) {
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 a = ring[i];
    const Point2 b = ring[(i + 1) % n];
    // The next edge starts at b: it may touch only there, unless it folds back along ab.
    const Point2 c = ring[(i + 2) % n];
    if (distance_to_line(c, a, b) <= tolerance_m && dot(c - b, a - b) > 0.0) return true;
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // the closing edge neighbours the first
      if (segments_touch(a, b, ring[j], ring[(j + 1) % n])) return true;
    }
  }
  return false;
}

bool rings_touch(const PlaneRing& a, const PlaneRing& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (segments_touch(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
  return false;
}

bool collinear(const PlaneRing& ring, double tolerance_m) {
  std::size_t far = 1;  // the vertex farthest from the first spans the line
  for (std::size_t i = 2; i < ring.size(); ++i)
    if (norm(ring[i] - ring[0]) > norm(ring[far] - ring[0])) far = i;
  for (std::size_t i = 1; i < ring.size(); ++i)
    if (distance_to_line(ring[i], ring[0], ring[far]) > tolerance_m) return false;
  return true;
}

}  // namespace kew::volume::detail
