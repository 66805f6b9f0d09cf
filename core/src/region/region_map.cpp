#include "kew/region/region_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <fmt/format.h>

#include "kew/geometry/predicates.hpp"

namespace kew::region {

namespace {

using geometry::Orientation;
using geometry::orient2d;
using geometry::Point2;

constexpr double kPi = 3.14159265358979323846;

// Longitude as x, latitude as y: edges are straight in this plane (the GeoJSON rule).
Point2 plane(const geo::GeodeticPosition& v) { return {v.lon_deg, v.lat_deg}; }

bool between(double x, double a, double b) { return std::min(a, b) <= x && x <= std::max(a, b); }

// p lies on the closed segment [a, b] (exactly, for these doubles).
bool on_segment(Point2 p, Point2 a, Point2 b) {
  return between(p.x, a.x, b.x) && between(p.y, a.y, b.y) && orient2d(a, b, p) == Orientation::Collinear;
}

// The closed segments [a, b] and [c, d] share a point.
bool segments_meet(Point2 a, Point2 b, Point2 c, Point2 d) {
  if (std::max(a.x, b.x) < std::min(c.x, d.x) || std::max(c.x, d.x) < std::min(a.x, b.x) ||
      std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y))
    return false;
  const int o1 = geometry::sign(orient2d(a, b, c)), o2 = geometry::sign(orient2d(a, b, d));
  const int o3 = geometry::sign(orient2d(c, d, a)), o4 = geometry::sign(orient2d(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && on_segment(c, a, b)) || (o2 == 0 && on_segment(d, a, b)) || (o3 == 0 && on_segment(a, c, d)) ||
         (o4 == 0 && on_segment(b, c, d));
}

std::string position_problem(const geo::GeodeticPosition& v, const std::string& what) {
  if (!std::isfinite(v.lat_deg) || !std::isfinite(v.lon_deg)) return what + " is not a finite latitude and longitude";
  if (std::abs(v.lat_deg) > 90.0) return fmt::format("{} has latitude {}, outside [-90, 90]", what, v.lat_deg);
  if (std::abs(v.lon_deg) > 180.0) return fmt::format("{} has longitude {}, outside [-180, 180]", what, v.lon_deg);
  return {};
}

std::string polygon_problem(const std::vector<geo::GeodeticPosition>& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return fmt::format("polygon has {} vertices, fewer than 3", n);
  if (n > RegionMap::kMaxPolygonVertices)
    return fmt::format("polygon has {} vertices, more than {}", n, RegionMap::kMaxPolygonVertices);
  double lon_min = 180.0, lon_max = -180.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::string p = position_problem(polygon[i], fmt::format("polygon vertex {}", i + 1)); !p.empty()) return p;
    lon_min = std::min(lon_min, polygon[i].lon_deg);
    lon_max = std::max(lon_max, polygon[i].lon_deg);
  }
  if (lon_max - lon_min > 180.0)
    return fmt::format("polygon spans {}° of longitude ({} to {}), more than 180°: a polygon may not cross the "
                       "antimeridian (split it in two)",
                       lon_max - lon_min, lon_min, lon_max);
  std::vector<Point2> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = plane(polygon[i]);
  const auto next = [n](std::size_t i) { return (i + 1) % n; };
  for (std::size_t i = 0; i < n; ++i)
    if (v[i].x == v[next(i)].x && v[i].y == v[next(i)].y)
      return fmt::format("polygon vertex {} repeats vertex {}", next(i) + 1, i + 1);
  // Consecutive edges a→b→c fold back when c lies on [a, b] or a on [b, c] (this also
  // refuses a polygon whose vertices are all on one line).
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 a = v[i], b = v[next(i)], c = v[next(next(i))];
    if (on_segment(c, a, b) || on_segment(a, b, c))
      return fmt::format("polygon folds back on itself at vertex {} (its edges overlap)", next(i) + 1);
  }
  // Edge i runs from vertex i to vertex i + 1; non-adjacent edges may not meet.
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing vertex
      if (segments_meet(v[i], v[next(i)], v[j], v[next(j)]))
        return fmt::format("polygon edges {} (vertex {} to {}) and {} (vertex {} to {}) meet: the polygon "
                           "intersects itself",
                           i + 1, i + 1, next(i) + 1, j + 1, j + 1, next(j) + 1);
    }
  return {};
}

std::string parameters_problem(const RegionParameters& p) {
  const auto positive = [](const std::optional<double>& x) { return !x || (std::isfinite(*x) && *x > 0.0); };
  const auto non_negative = [](const std::optional<double>& x) { return !x || (std::isfinite(*x) && *x >= 0.0); };
  if (!positive(p.horizontal_m)) return fmt::format("horizontal_m = {} must be above 0", *p.horizontal_m);
  if (!positive(p.vertical_m)) return fmt::format("vertical_m = {} must be above 0", *p.vertical_m);
  if (!non_negative(p.lookahead_s)) return fmt::format("lookahead_s = {} must be at least 0", *p.lookahead_s);
  if (!non_negative(p.warning_s)) return fmt::format("warning_s = {} must be at least 0", *p.warning_s);
  if (p.confirm && *p.confirm < 1) return fmt::format("confirm = {} must be at least 1", *p.confirm);
  if (p.clear && *p.clear < 1) return fmt::format("clear = {} must be at least 1", *p.clear);
  return {};
}

bool sets_any(const RegionParameters& p) {
  return p.horizontal_m || p.vertical_m || p.lookahead_s || p.warning_s || p.confirm || p.clear;
}

// Crossing number in (lon, lat) with the boundary inside. An edge counts when it
// straddles the horizontal line through p (one end at or below p, the other above) and
// crosses it east of p.
bool polygon_holds(const std::vector<geo::GeodeticPosition>& polygon, Point2 p) {
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Point2 a = plane(polygon[j]), b = plane(polygon[i]);
    const bool straddles = (a.y <= p.y) != (b.y <= p.y);
    const bool near = between(p.x, a.x, b.x) && between(p.y, a.y, b.y);
    if (!straddles && !near) continue;
    const Orientation o = orient2d(a, b, p);
    if (o == Orientation::Collinear && near) return true;  // on the edge
    if (straddles && (o == Orientation::CounterClockwise) == (a.y <= p.y) && o != Orientation::Collinear)
      inside = !inside;
  }
  return inside;
}

// Degrees of latitude or longitude the bounding boxes are widened by, so that rounding
// in the geodesic Direct problem can never leave out a point the Inverse test takes
// (about 0.1 m; GeographicLib is accurate to nanometres).
constexpr double kBoxMargin = 1e-6;

}  // namespace

std::string RegionMap::problem(const Region& r) {
  if (r.name.empty()) return "name is empty";
  if (!r.polygon.empty()) {
    if (std::string p = polygon_problem(r.polygon); !p.empty()) return p;
    if (r.radius_m != 0.0)
      return fmt::format("radius_m = {} is set with a polygon: a region is a polygon or a circle", r.radius_m);
  } else {
    if (std::string p = position_problem(r.center, "center"); !p.empty()) return p;
    if (!(std::isfinite(r.radius_m) && r.radius_m > 0.0))
      return fmt::format("radius_m = {} must be above 0 (a circle; or give a polygon)", r.radius_m);
  }
  if (!(r.floor_ft < r.ceiling_ft))
    return fmt::format("floor_ft = {} must be below ceiling_ft = {}", r.floor_ft, r.ceiling_ft);
  if (std::string p = parameters_problem(r.parameters); !p.empty()) return p;
  if (r.inhibit && sets_any(r.parameters)) return "an inhibition volume (inhibit) sets no parameters";
  return {};
}

std::string RegionMap::first_problem(const std::vector<Region>& regions) {
  for (std::size_t i = 0; i < regions.size(); ++i) {
    if (std::string p = problem(regions[i]); !p.empty())
      return fmt::format("region {} (\"{}\"): {}", i + 1, regions[i].name, p);
    for (std::size_t j = 0; j < i; ++j)
      if (regions[j].name == regions[i].name)
        return fmt::format("regions {} and {} are both named \"{}\"", j + 1, i + 1, regions[i].name);
  }
  return {};
}

bool RegionMap::holds(const Region& r, double lat_deg, double lon_deg, double alt_ft) {
  if (!(r.floor_ft <= alt_ft && alt_ft < r.ceiling_ft)) return false;
  if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg)) return false;
  if (!r.polygon.empty()) return polygon_holds(r.polygon, {lon_deg, lat_deg});
  double distance = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(r.center.lat_deg, r.center.lon_deg, lat_deg, lon_deg, distance);
  return distance <= r.radius_m;
}

RegionMap::RegionMap(std::vector<Region> regions) : regions_(std::move(regions)) {
  if (std::string p = first_problem(regions_); !p.empty()) throw std::invalid_argument(p);
  const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
  boxes_.reserve(regions_.size());
  for (const Region& r : regions_) {
    Box box{90.0, -90.0, 180.0, -180.0};
    if (!r.polygon.empty()) {
      // Edges are straight in (lon, lat): the vertices bound the polygon exactly.
      for (const geo::GeodeticPosition& v : r.polygon) {
        box.lat_min = std::min(box.lat_min, v.lat_deg);
        box.lat_max = std::max(box.lat_max, v.lat_deg);
        box.lon_min = std::min(box.lon_min, v.lon_deg);
        box.lon_max = std::max(box.lon_max, v.lon_deg);
      }
      boxes_.push_back(box);
      continue;
    }
    // Circle. The nearest point of a parallel is along the meridian, so the circle's
    // latitudes are those reached due north and due south (or a pole, when the circle
    // holds it).
    const geo::GeodeticPosition c = r.center;
    double s_north = 0.0, s_south = 0.0, lat = 0.0, lon = 0.0;
    geodesic.Inverse(c.lat_deg, c.lon_deg, 90.0, c.lon_deg, s_north);
    geodesic.Inverse(c.lat_deg, c.lon_deg, -90.0, c.lon_deg, s_south);
    bool all_longitudes = false;
    if (r.radius_m >= s_north) {
      box.lat_max = 90.0;
      all_longitudes = true;
    } else {
      geodesic.Direct(c.lat_deg, c.lon_deg, 0.0, r.radius_m, lat, lon);
      box.lat_max = std::min(90.0, lat + kBoxMargin);
    }
    if (r.radius_m >= s_south) {
      box.lat_min = -90.0;
      all_longitudes = true;
    } else {
      geodesic.Direct(c.lat_deg, c.lon_deg, 180.0, r.radius_m, lat, lon);
      box.lat_min = std::max(-90.0, lat - kBoxMargin);
    }
    // Along any path from the centre, ds ≥ p(φ)·|dλ| with p the radius of the parallel,
    // smallest at the latitude of the band farthest from the equator: a point within
    // radius_m is at most radius_m / p_min radians of longitude away.
    if (!all_longitudes) {
      const double phi = std::max(std::abs(box.lat_min), std::abs(box.lat_max)) * kPi / 180.0;
      const double a = GeographicLib::Constants::WGS84_a(), f = GeographicLib::Constants::WGS84_f();
      const double e2 = f * (2.0 - f);
      const double p_min = a * std::cos(phi) / std::sqrt(1.0 - e2 * std::sin(phi) * std::sin(phi));
      const double half_width = p_min > 0.0 ? r.radius_m / p_min * 180.0 / kPi + kBoxMargin : 360.0;
      box.lon_min = c.lon_deg - half_width;
      box.lon_max = c.lon_deg + half_width;
      // A circle across the antimeridian keeps every longitude (its box would wrap).
      all_longitudes = box.lon_min < -180.0 || box.lon_max > 180.0;
    }
    if (all_longitudes) {
      box.lon_min = -180.0;
      box.lon_max = 180.0;
    }
    boxes_.push_back(box);
  }
}

std::size_t RegionMap::locate(double lat_deg, double lon_deg, double alt_ft) const {
  for (std::size_t i = 0; i < regions_.size(); ++i) {
    const Region& r = regions_[i];
    const Box& b = boxes_[i];
    if (!(r.floor_ft <= alt_ft && alt_ft < r.ceiling_ft)) continue;
    if (!(b.lat_min <= lat_deg && lat_deg <= b.lat_max && b.lon_min <= lon_deg && lon_deg <= b.lon_max)) continue;
    if (holds(r, lat_deg, lon_deg, alt_ft)) return i;
  }
  return kNone;
}

}  // namespace kew::region
