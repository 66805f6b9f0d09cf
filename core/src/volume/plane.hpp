#pragma once
// Helpers of kew_volume (private to its sources): rings in the gnomonic plane.

#include <vector>

#include "kew/geometry/vector2.hpp"

namespace GeographicLib {
class Gnomonic;
}

namespace kew::volume::detail {

/// The gnomonic projection on WGS84 (one instance, shared by the sources).
const GeographicLib::Gnomonic& wgs84_gnomonic();

using geometry::Point2;
using PlaneRing = std::vector<Point2>;

/// Distance (m) from p to the closed segment ab.
double distance_to_segment(Point2 p, Point2 a, Point2 b);

/// Where p lies relative to `ring` (closed implicitly): +1 inside, −1 outside, 0 within
/// `tolerance_m` (≥ 0) of an edge. Crossing number on a ray towards +x.
int locate(Point2 p, const PlaneRing& ring, double tolerance_m);

/// True when the closed segments ab and cd share a point (exact predicates).
bool segments_touch(Point2 a, Point2 b, Point2 c, Point2 d);

/// True when two edges of `ring` cross, touch (other than neighbours at their shared
/// vertex) or overlap (neighbours folding back on each other, within `tolerance_m`).
bool self_intersecting(const PlaneRing& ring, double tolerance_m);

/// True when an edge of `a` touches an edge of `b`.
bool rings_touch(const PlaneRing& a, const PlaneRing& b);

/// True when every vertex of `ring` lies within `tolerance_m` of one line.
bool collinear(const PlaneRing& ring, double tolerance_m);

}  // namespace kew::volume::detail
