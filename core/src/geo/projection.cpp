#include "kew/geo/projection.hpp"

#include <cmath>
#include <stdexcept>

#include <GeographicLib/Constants.hpp>

namespace kew::geo {

namespace {
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// Plane distances are compared with the coverage radius first; only positions whose
// plane distance is within this margin of the boundary pay for a geodesic inverse.
// The plane overstates distances by at most max_scale − 1 (< 3 % within 1,500 km).
constexpr double kCoverageMargin = 0.05;
}  // namespace

Projection::Projection(GeodeticPosition reference, double coverage_radius_m)
    : reference_(reference),
      coverage_radius_m_(coverage_radius_m),
      mercator_(GeographicLib::Constants::WGS84_a(), GeographicLib::Constants::WGS84_f(), 1.0) {
  if (!std::isfinite(reference.lat_deg) || !std::isfinite(reference.lon_deg) ||
      std::abs(reference.lat_deg) > 90.0 || std::abs(reference.lon_deg) > 180.0)
    throw std::invalid_argument("projection reference outside WGS84 latitude/longitude ranges");
  if (!(coverage_radius_m > 0.0) || coverage_radius_m > 3.0e6)
    throw std::invalid_argument("coverage radius must be in (0, 3000 km]");
  double x = 0.0, gamma = 0.0, k = 1.0;
  mercator_.Forward(reference.lon_deg, reference.lat_deg, reference.lon_deg, x, northing_of_reference_,
                    gamma, k);
  // k grows monotonically with the distance from the central meridian; the worst case
  // within coverage is a point due east or west at the coverage radius.
  const auto& geodesic = GeographicLib::Geodesic::WGS84();
  double lat = 0.0, lon = 0.0, y = 0.0;
  geodesic.Direct(reference.lat_deg, reference.lon_deg, 90.0, coverage_radius_m, lat, lon);
  mercator_.Forward(reference.lon_deg, lat, lon, x, y, gamma, max_scale_);
}

PlanePosition Projection::project(GeodeticPosition position, ProjectionError& error) const {
  PlanePosition out;
  error = ProjectionError::None;
  if (!std::isfinite(position.lat_deg) || !std::isfinite(position.lon_deg)) {
    error = ProjectionError::NotFinite;
    return out;
  }
  if (std::abs(position.lat_deg) > 90.0) {
    error = ProjectionError::LatitudeRange;
    return out;
  }
  if (std::abs(position.lon_deg) > 180.0) {
    error = ProjectionError::LongitudeRange;
    return out;
  }
  double x = 0.0, y = 0.0;
  mercator_.Forward(reference_.lon_deg, position.lat_deg, position.lon_deg, x, y, out.convergence_deg,
                    out.scale);
  out.p = {x, y - northing_of_reference_};
  const double plane_distance = std::hypot(out.p.x, out.p.y);
  if (!std::isfinite(plane_distance) || plane_distance > coverage_radius_m_ * max_scale_ * (1.0 + kCoverageMargin)) {
    error = ProjectionError::OutsideCoverage;
  } else if (plane_distance > coverage_radius_m_ * (1.0 - kCoverageMargin) &&
             geodesic_distance_m(reference_, position) > coverage_radius_m_) {
    error = ProjectionError::OutsideCoverage;
  }
  return out;
}

GeodeticPosition Projection::unproject(geometry::Point2 p) const {
  GeodeticPosition out;
  mercator_.Reverse(reference_.lon_deg, p.x, p.y + northing_of_reference_, out.lat_deg, out.lon_deg);
  return out;
}

geometry::Vector2 Projection::velocity_to_plane(const PlanePosition& at, double ground_speed_mps,
                                                double track_deg) const {
  const double grid_bearing = (track_deg - at.convergence_deg) * kDegToRad;
  const double speed = ground_speed_mps * at.scale;
  return {speed * std::sin(grid_bearing), speed * std::cos(grid_bearing)};
}

void Projection::velocity_from_plane(const PlanePosition& at, geometry::Vector2 v, double& ground_speed_mps,
                                     double& track_deg) const {
  ground_speed_mps = std::hypot(v.x, v.y) / at.scale;
  double bearing = std::atan2(v.x, v.y) / kDegToRad + at.convergence_deg;
  bearing = std::fmod(bearing, 360.0);
  if (bearing < 0.0) bearing += 360.0;
  if (bearing >= 360.0) bearing = 0.0;
  track_deg = bearing;
}

double Projection::geodesic_distance_m(GeodeticPosition a, GeodeticPosition b) {
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, s12);
  return s12;
}

}  // namespace kew::geo
