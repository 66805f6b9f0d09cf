#include "kew/volume/entry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>
#include <GeographicLib/Gnomonic.hpp>

#include "kew/util/units.hpp"
#include "plane.hpp"

namespace kew::volume {

namespace {
using geometry::Point2;
using geometry::Vector2;
using GeographicLib::GeodesicLine;

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
// The path is cut into pieces of at most this length (m); each is taken as a chord in
// the volume's gnomonic plane, where a piece that cannot reach the volume is skipped.
constexpr double kPiece_m = 200e3;
// Chord intersections (and vertices near a chord) within this of a piece or an edge
// (plane m) are refined: a spare candidate costs a refinement, a missing one an entry.
constexpr double kSlack_m = 100.0;
// Half the span (m) of the two points that stand for an edge near a crossing.
constexpr double kEdgeStep_m = 1000.0;
// Refinement stops when a crossing moves less than this (m).
constexpr double kConverged_m = 1e-6;
constexpr int kMaxIterations = 12;
// Bisections of the circle stop at this bracket (m along the path).
constexpr double kBisection_m = 1e-4;
// Candidate times closer than this (s) are one.
constexpr double kSameTime_s = 1e-9;

const GeographicLib::Geodesic& wgs84() { return GeographicLib::Geodesic::WGS84(); }

struct PathPoint {
  LatLon p;
  double azimuth_deg = 0.0;  // of the path at p
};

PathPoint point_on(const GeodesicLine& path, double s) {
  PathPoint out;
  path.Position(s, out.p.lat_deg, out.p.lon_deg, out.azimuth_deg);
  return out;
}

// `p` in the gnomonic plane centred at `at` (m).
Point2 local(LatLon at, LatLon p) {
  double x = 0.0, y = 0.0, azimuth = 0.0, rk = 0.0;
  detail::wgs84_gnomonic().Forward(at.lat_deg, at.lon_deg, p.lat_deg, p.lon_deg, x, y, azimuth, rk);
  return {x, y};
}

Vector2 direction(double azimuth_deg) {
  return {std::sin(azimuth_deg * kDegToRad), std::cos(azimuth_deg * kDegToRad)};
}

struct Candidate {
  double s = 0.0;            // along the path (m)
  bool on_boundary = false;  // the path is on the boundary there
};

// The crossing of the path with the geodesic `edge` (length `edge_m`), refined from the
// estimates s and sigma (m along each) in a gnomonic plane centred on the path, where
// the path is exactly straight and the edge nearly so near the crossing.
Candidate refine_crossing(const GeodesicLine& path, const GeodesicLine& edge, double edge_m, double s,
                          double sigma) {
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const PathPoint at = point_on(path, s);
    const Vector2 d = direction(at.azimuth_deg);
    LatLon e1, e2;
    edge.Position(sigma - kEdgeStep_m, e1.lat_deg, e1.lon_deg);
    edge.Position(sigma + kEdgeStep_m, e2.lat_deg, e2.lon_deg);
    const Point2 a = local(at.p, e1);
    const Vector2 w = local(at.p, e2) - a;
    const double denominator = cross(d, w);
    if (!is_finite(a) || !is_finite(w) || std::abs(denominator) <= 1e-12 * norm(w)) break;
    const double u = cross(a, w) / denominator;
    const double moved = -kEdgeStep_m + 2.0 * kEdgeStep_m * cross(a, d) / denominator;
    s += u;
    sigma += moved;
    if (std::abs(u) < kConverged_m && std::abs(moved) < kConverged_m)
      return {s, -kBoundaryTolerance_m <= sigma && sigma <= edge_m + kBoundaryTolerance_m};
  }
  return {s, false};
}

// Where the path passes closest to `vertex`, refined from the estimate s (m).
Candidate foot_of(const GeodesicLine& path, LatLon vertex, double s) {
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const PathPoint at = point_on(path, s);
    const Vector2 d = direction(at.azimuth_deg);
    const Point2 q = local(at.p, vertex);
    if (!is_finite(q)) break;
    const double u = dot(q, d);
    s += u;
    if (std::abs(u) < kConverged_m) return {s, std::abs(cross(d, q)) <= kBoundaryTolerance_m};
  }
  return {s, false};
}

// Candidate split points of a polygon along the path [0, length_m].
std::vector<Candidate> polygon_candidates(const Volume& volume, const GeodesicLine& path, double length_m) {
  std::vector<Candidate> out;
  const auto& rings = volume.rings();
  const auto& plane = volume.plane_rings();
  const LatLon c = volume.centre();
  const auto pieces = static_cast<std::size_t>(std::max(1.0, std::ceil(length_m / kPiece_m)));
  for (std::size_t k = 0; k < pieces; ++k) {
    const double s_a = length_m * static_cast<double>(k) / static_cast<double>(pieces);
    const double s_b = length_m * static_cast<double>(k + 1) / static_cast<double>(pieces);
    const PathPoint mid = point_on(path, 0.5 * (s_a + s_b));
    double centre_m = 0.0;
    wgs84().Inverse(c.lat_deg, c.lon_deg, mid.p.lat_deg, mid.p.lon_deg, centre_m);
    if (centre_m - 0.5 * (s_b - s_a) > volume.extent_m() + 1000.0) continue;  // cannot reach
    const Point2 pa = volume.project(point_on(path, s_a).p);
    const Point2 pb = volume.project(point_on(path, s_b).p);
    const Vector2 chord = pb - pa;
    const double chord_m = norm(chord);
    if (!is_finite(pa) || !is_finite(pb) || chord_m == 0.0) continue;
    for (std::size_t r = 0; r < plane.size(); ++r) {
      const std::size_t n = plane[r].size();
      for (std::size_t i = 0; i < n; ++i) {
        const Point2 a = plane[r][i];
        const Vector2 w = plane[r][(i + 1) % n] - a;
        const double edge_plane_m = norm(w);
        // The vertex a: the path may pass through it or touch it.
        if (detail::distance_to_segment(a, pa, pb) <= kSlack_m) {
          const double u = dot(a - pa, chord) / (chord_m * chord_m);
          out.push_back(foot_of(path, rings[r][i], s_a + u * (s_b - s_a)));
        }
        const double denominator = cross(chord, w);
        if (std::abs(denominator) <= 1e-12 * chord_m * edge_plane_m) continue;  // parallel chords
        const double u = cross(a - pa, w) / denominator;
        const double v = cross(a - pa, chord) / denominator;
        if (u < -kSlack_m / chord_m || u > 1.0 + kSlack_m / chord_m || v < -kSlack_m / edge_plane_m ||
            v > 1.0 + kSlack_m / edge_plane_m)
          continue;
        const LatLon from = rings[r][i], to = rings[r][(i + 1) % n];
        const GeodesicLine edge = wgs84().InverseLine(from.lat_deg, from.lon_deg, to.lat_deg, to.lon_deg);
        const double edge_m = edge.Distance();
        out.push_back(refine_crossing(path, edge, edge_m, s_a + u * (s_b - s_a), v * edge_m));
      }
    }
  }
  return out;
}

// Geodesic distance (m) from `centre` to the path at s, and its rate of change along
// the path (dimensionless, cosine of the angle between the path and the radial).
double distance_from(LatLon centre, const GeodesicLine& path, double s, double* slope = nullptr) {
  const PathPoint at = point_on(path, s);
  double distance_m = 0.0, azimuth1 = 0.0, azimuth2 = 0.0;
  wgs84().Inverse(centre.lat_deg, centre.lon_deg, at.p.lat_deg, at.p.lon_deg, distance_m, azimuth1, azimuth2);
  if (slope) *slope = std::cos((at.azimuth_deg - azimuth2) * kDegToRad);
  return distance_m;
}

// Narrows [neg, pos], f(neg) ≤ 0 < f(pos) (either order), to kBisection_m around a root
// of f, or to a point where −tol_f ≤ f ≤ 0: false position with the Illinois correction
// (a few evaluations for a smooth f, each a geodesic problem), and every third step a
// bisection, so that the bracket at least halves every three steps whatever f does.
template <class F>
Interval narrow(F&& f, double neg, double f_neg, double pos, double f_pos, double tol_f) {
  int last = 0;  // the end moved last: −1 neg, +1 pos
  for (int step = 0; std::abs(pos - neg) > kBisection_m; ++step) {
    double m = step % 3 == 2 ? 0.5 * (neg + pos) : neg - f_neg * (pos - neg) / (f_pos - f_neg);
    if (!(m > std::min(neg, pos) && m < std::max(neg, pos))) m = 0.5 * (neg + pos);
    const double fm = f(m);
    if (fm <= 0.0) {
      neg = m;
      f_neg = fm;
      if (last == -1) f_pos *= 0.5;
      last = -1;
      if (fm >= -tol_f) return {m, m};
    } else {
      pos = m;
      f_pos = fm;
      if (last == 1) f_neg *= 0.5;
      last = 1;
    }
  }
  return {neg, pos};
}

// The stretch of the path [0, length_m] (m along it) within `radius_m` of `centre`. On
// the path (at most 16.7° of arc, the circle at most 80°) the distance decreases to one
// minimum and then increases, so the stretch is one interval around the minimum.
std::optional<Interval> circle_span(LatLon centre, double radius_m, const GeodesicLine& path, double length_m) {
  const double reach_m = radius_m + kBoundaryTolerance_m;
  double slope = 0.0;
  const double d0 = distance_from(centre, path, 0.0, &slope);
  if (d0 - length_m > reach_m) return std::nullopt;
  double s_min = 0.0;
  if (slope < 0.0) {
    const double slope0 = slope;
    distance_from(centre, path, length_m, &slope);
    if (slope <= 0.0) {
      s_min = length_m;
    } else {
      // The distance's minimum: where its slope along the path changes sign.
      const auto slope_at = [&](double s) {
        double g = 0.0;
        distance_from(centre, path, s, &g);
        return g;
      };
      const Interval at = narrow(slope_at, 0.0, slope0, length_m, slope, 1e-9);
      s_min = 0.5 * (at.begin_s + at.end_s);
    }
  }
  const double d_min = distance_from(centre, path, s_min);
  if (d_min > reach_m) return std::nullopt;
  if (d_min >= radius_m) return Interval{s_min, s_min};  // a tangent touch
  // The crossings of distance = radius between an outside end and the inside minimum,
  // each the inside end of its final bracket.
  const auto beyond = [&](double s) { return distance_from(centre, path, s) - radius_m; };
  const auto root = [&](double outside, double f_outside) {
    return narrow(beyond, s_min, d_min - radius_m, outside, f_outside, 1e-5).begin_s;
  };
  const double begin = d0 <= radius_m ? 0.0 : root(0.0, d0 - radius_m);
  const double d_end = distance_from(centre, path, length_m);
  const double end = d_end <= radius_m ? length_m : root(length_m, d_end - radius_m);
  return Interval{begin, end};
}

// Sorted disjoint closed intervals from split times with the state at each and between.
std::vector<Interval> intervals_from(const std::vector<double>& times, const std::vector<bool>& at,
                                     const std::vector<bool>& between) {
  std::vector<Interval> out;
  const auto add = [&out](double begin, double end) {
    if (!out.empty() && begin <= out.back().end_s)
      out.back().end_s = std::max(out.back().end_s, end);
    else
      out.push_back({begin, end});
  };
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (at[i]) add(times[i], times[i]);
    if (i + 1 < times.size() && between[i]) add(times[i], times[i + 1]);
  }
  return out;
}
}  // namespace

MotionError validate(const Motion& m, double horizon_s) {
  if (!std::isfinite(m.start.lat_deg) || !std::isfinite(m.start.lon_deg) || !std::isfinite(m.alt_ft) ||
      !std::isfinite(m.track_deg) || !std::isfinite(m.gs_kt) || !std::isfinite(m.vr_fpm) ||
      (m.sel_ft && !std::isfinite(*m.sel_ft)) || !std::isfinite(horizon_s))
    return MotionError::NotFinite;
  if (std::abs(m.start.lat_deg) > 90.0) return MotionError::LatitudeRange;
  if (std::abs(m.start.lon_deg) > 180.0) return MotionError::LongitudeRange;
  if (m.gs_kt < 0.0 || m.gs_kt > kMaxGroundSpeed_kt) return MotionError::SpeedRange;
  if (horizon_s < 0.0 || horizon_s > kMaxHorizon_s) return MotionError::HorizonRange;
  return MotionError::None;
}

double ground_speed_mps(const Motion& motion) { return motion.gs_kt * units::kMpsPerKnot; }

LatLon position_at(const Motion& motion, double t_s) {
  LatLon out;
  wgs84().Direct(motion.start.lat_deg, motion.start.lon_deg, motion.track_deg, ground_speed_mps(motion) * t_s,
                 out.lat_deg, out.lon_deg);
  return out;
}

std::optional<double> level_off_s(const Motion& motion) {
  if (!motion.sel_ft || motion.vr_fpm == 0.0) return std::nullopt;
  const double t = units::kSecondsPerMinute * (*motion.sel_ft - motion.alt_ft) / motion.vr_fpm;
  return t > 0.0 ? std::optional<double>(t) : std::nullopt;
}

double altitude_at(const Motion& motion, double t_s) {
  const std::optional<double> stop = level_off_s(motion);
  if (stop && t_s >= *stop) return *motion.sel_ft;
  return motion.alt_ft + motion.vr_fpm * t_s / units::kSecondsPerMinute;
}

std::optional<Interval> vertical_interval(const Motion& motion, VerticalBand band, double horizon_s) {
  const auto in_band = [&band](double z) { return band.floor_ft <= z && z <= band.ceiling_ft; };
  if (motion.vr_fpm == 0.0)
    return in_band(motion.alt_ft) ? std::optional<Interval>(Interval{0.0, horizon_s}) : std::nullopt;
  const std::optional<double> stop = level_off_s(motion);
  const double linear_end = stop ? std::min(*stop, horizon_s) : horizon_s;
  // The linear part: the times of the floor and the ceiling, ordered, within [0, linear_end].
  const double t_floor = units::kSecondsPerMinute * (band.floor_ft - motion.alt_ft) / motion.vr_fpm;
  const double t_ceiling = units::kSecondsPerMinute * (band.ceiling_ft - motion.alt_ft) / motion.vr_fpm;
  std::optional<Interval> out;
  const double begin = std::max(0.0, std::min(t_floor, t_ceiling));
  const double end = std::min(linear_end, std::max(t_floor, t_ceiling));
  if (begin <= end) out = Interval{begin, end};
  // The level part after the stop.
  if (stop && *stop < horizon_s && in_band(*motion.sel_ft)) {
    if (out)
      out->end_s = horizon_s;
    else
      out = Interval{*stop, horizon_s};
  }
  return out;
}

namespace {

using Unit = std::array<double, 3>;

Unit unit_vector(double lat_deg, double lon_deg) {
  const double lat = lat_deg * (M_PI / 180.0), lon = lon_deg * (M_PI / 180.0);
  return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}
double dot(const Unit& a, const Unit& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Unit cross(const Unit& a, const Unit& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double angle_between(const Unit& a, const Unit& b) { return std::atan2(std::sqrt(dot(cross(a, b), cross(a, b))), dot(a, b)); }

// The sphere's radius for the reach test (m): WGS84's mean radius R1.
constexpr double kSphereRadius_m = 6371008.8;

}  // namespace

bool within_reach(const Volume& volume, const Motion& motion, double length_m) {
  // On a sphere of the mean radius, with geodetic latitudes as spherical ones: distances
  // differ from the ellipsoid's by less than 0.6 % (Karney 2013, §1), and the great circle
  // from the start strays from the geodesic by less than that of its length, so a path
  // whose spherical distance from the centre exceeds the extent by 1 % of both, and 200 m,
  // cannot enter. A few trigonometric calls instead of GeographicLib's iterations: most
  // candidates of the index are refused here.
  const Unit start = unit_vector(motion.start.lat_deg, motion.start.lon_deg);
  const Unit centre = unit_vector(volume.centre().lat_deg, volume.centre().lon_deg);
  const double lat = motion.start.lat_deg * (M_PI / 180.0), lon = motion.start.lon_deg * (M_PI / 180.0);
  const double bearing = motion.track_deg * (M_PI / 180.0);
  const Unit north = {-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat)};
  const Unit east = {-std::sin(lon), std::cos(lon), 0.0};
  const double arc = std::min(length_m / kSphereRadius_m, M_PI);
  Unit end;
  for (int i = 0; i < 3; ++i)
    end[i] = start[i] * std::cos(arc) + (std::cos(bearing) * north[i] + std::sin(bearing) * east[i]) * std::sin(arc);
  double nearest = std::min(angle_between(centre, start), angle_between(centre, end));
  Unit normal = cross(start, end);
  const double norm = std::sqrt(dot(normal, normal));
  if (norm > 1e-12 && arc < M_PI) {
    for (double& x : normal) x /= norm;
    // The centre's foot on the path's great circle lies on the arc when it is after the
    // start and before the end.
    const double off = dot(centre, normal);
    Unit foot = {centre[0] - off * normal[0], centre[1] - off * normal[1], centre[2] - off * normal[2]};
    if (dot(cross(start, foot), normal) >= 0.0 && dot(cross(foot, end), normal) >= 0.0)
      nearest = std::min(nearest, std::abs(std::asin(std::clamp(off, -1.0, 1.0))));
  }
  const double slack_m = 0.01 * (volume.extent_m() + length_m) + 200.0;
  return nearest * kSphereRadius_m <= volume.extent_m() + slack_m;
}

std::vector<Interval> horizontal_intervals(const Volume& volume, const Motion& motion, double horizon_s) {
  const double speed = ground_speed_mps(motion);
  const double length_m = speed * horizon_s;
  if (!within_reach(volume, motion, length_m)) return {};
  if (length_m == 0.0) {
    if (volume.contains_horizontally(motion.start)) return {Interval{0.0, horizon_s}};
    return {};
  }
  const GeodesicLine path = wgs84().Line(motion.start.lat_deg, motion.start.lon_deg, motion.track_deg);
  if (volume.is_circle()) {
    const std::optional<Interval> span = circle_span(volume.centre(), volume.extent_m(), path, length_m);
    if (!span) return {};
    return {Interval{span->begin_s / speed, span->end_s / speed}};
  }
  std::vector<Candidate> candidates = polygon_candidates(volume, path, length_m);
  candidates.push_back({0.0, false});
  candidates.push_back({length_m, false});
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.s < b.s; });
  std::vector<double> times;
  std::vector<bool> at, between;
  for (const Candidate& c : candidates) {
    if (c.s < -kBoundaryTolerance_m || c.s > length_m + kBoundaryTolerance_m) continue;
    const double t = std::clamp(c.s, 0.0, length_m) / speed;
    if (!times.empty() && t - times.back() <= kSameTime_s) {
      at.back() = at.back() || c.on_boundary;
      continue;
    }
    times.push_back(t);
    at.push_back(c.on_boundary);
  }
  times.back() = horizon_s;
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!at[i]) at[i] = volume.contains_horizontally(point_on(path, times[i] * speed).p);
    if (i + 1 < times.size())
      between.push_back(volume.contains_horizontally(point_on(path, 0.5 * (times[i] + times[i + 1]) * speed).p));
  }
  return intervals_from(times, at, between);
}

Entry entry(const Volume& volume, const Motion& motion, double horizon_s, double from_s) {
  Entry out;
  out.error = validate(motion, horizon_s);
  if (out.error == MotionError::None && !(from_s >= 0.0 && from_s <= horizon_s)) out.error = MotionError::HorizonRange;
  if (out.error != MotionError::None) return out;
  const std::optional<Interval> vertical = vertical_interval(motion, volume.band(), horizon_s);
  if (!vertical) return out;
  for (const Interval& h : horizontal_intervals(volume, motion, horizon_s)) {
    const double begin = std::max({h.begin_s, vertical->begin_s, from_s});
    const double end = std::min(h.end_s, vertical->end_s);
    if (begin > end) continue;
    out.entry_s = begin;
    out.inside_now = begin == from_s;
    if (end < horizon_s) out.exit_s = end;
    break;
  }
  return out;
}

}  // namespace kew::volume
