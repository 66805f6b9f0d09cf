// The only translation unit that includes CGAL in kew_core: CGAL's headers are heavy,
// and its predicates are reached through two small non-inline functions.
#include "kew/geometry/predicates.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace kew::geometry {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
Kernel::Point_2 to_cgal(Point2 p) { return {p.x, p.y}; }
}  // namespace

Orientation orient2d(Point2 a, Point2 b, Point2 c) {
  return static_cast<Orientation>(
      static_cast<int>(CGAL::orientation(to_cgal(a), to_cgal(b), to_cgal(c))));
}

CircleSide incircle(Point2 a, Point2 b, Point2 c, Point2 d) {
  // side_of_oriented_circle is positive for d inside a ccw circle, as is Eq. 2.4.
  return static_cast<CircleSide>(static_cast<int>(
      CGAL::side_of_oriented_circle(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d))));
}

}  // namespace kew::geometry
