#include "kew/volume/volume.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/Gnomonic.hpp>

#include "plane.hpp"

namespace kew::volume {

namespace {
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
// Vertices closer than this in the gnomonic plane (m) are one vertex.
constexpr double kSameVertex_m = 1e-3;

VolumeError check_position(LatLon p) {
  if (!std::isfinite(p.lat_deg) || !std::isfinite(p.lon_deg)) return VolumeError::NotFinite;
  if (std::abs(p.lat_deg) > 90.0) return VolumeError::LatitudeRange;
  if (std::abs(p.lon_deg) > 180.0) return VolumeError::LongitudeRange;
  return VolumeError::None;
}

VolumeError check_band(VerticalBand band) {
  if (!std::isfinite(band.floor_ft) || !std::isfinite(band.ceiling_ft)) return VolumeError::NotFinite;
  if (band.floor_ft >= band.ceiling_ft) return VolumeError::BandInverted;
  return VolumeError::None;
}

// The normalised mean of the vertices' unit vectors (on a sphere), or nothing when the
// mean vanishes (vertices spread around the globe).
std::optional<LatLon> mean_direction(const Ring& ring) {
  double x = 0.0, y = 0.0, z = 0.0;
  for (const LatLon& p : ring) {
    const double lat = p.lat_deg * kDegToRad, lon = p.lon_deg * kDegToRad;
    x += std::cos(lat) * std::cos(lon);
    y += std::cos(lat) * std::sin(lon);
    z += std::sin(lat);
  }
  const double horizontal = std::hypot(x, y);
  if (std::hypot(horizontal, z) < 1e-9 * static_cast<double>(ring.size())) return std::nullopt;
  return LatLon{std::atan2(z, horizontal) * kRadToDeg, horizontal > 0.0 ? std::atan2(y, x) * kRadToDeg : 0.0};
}

VolumeResult refused(VolumeError error, std::size_t ring = 0) {
  VolumeResult result;
  result.error = error;
  result.ring = ring;
  return result;
}
}  // namespace

const GeographicLib::Gnomonic& detail::wgs84_gnomonic() {
  static const GeographicLib::Gnomonic instance(GeographicLib::Geodesic::WGS84());
  return instance;
}

geometry::Point2 Volume::project(LatLon p) const {
  double x = 0.0, y = 0.0, azimuth = 0.0, rk = 0.0;
  detail::wgs84_gnomonic().Forward(centre_.lat_deg, centre_.lon_deg, p.lat_deg, p.lon_deg, x, y, azimuth, rk);
  return {x, y};
}

LatLon Volume::unproject(geometry::Point2 p) const {
  LatLon out;
  detail::wgs84_gnomonic().Reverse(centre_.lat_deg, centre_.lon_deg, p.x, p.y, out.lat_deg, out.lon_deg);
  return out;
}

VolumeResult Volume::polygon(const Ring& outer, const std::vector<Ring>& holes, VerticalBand band) {
  // Coordinates first, then the band, then the shape.
  for (std::size_t r = 0; r <= holes.size(); ++r)
    for (const LatLon& p : r == 0 ? outer : holes[r - 1])
      if (const VolumeError e = check_position(p); e != VolumeError::None) return refused(e, r);
  if (const VolumeError e = check_band(band); e != VolumeError::None) return refused(e);
  if (outer.size() < 3) return refused(VolumeError::TooFewVertices);
  const std::optional<LatLon> centre = mean_direction(outer);
  if (!centre) return refused(VolumeError::TooLarge);

  Volume volume;
  volume.centre_ = *centre;
  volume.band_ = band;
  const auto& geodesic = GeographicLib::Geodesic::WGS84();
  for (std::size_t r = 0; r <= holes.size(); ++r) {
    const Ring& ring = r == 0 ? outer : holes[r - 1];
    Ring kept;
    detail::PlaneRing plane;
    for (const LatLon& p : ring) {
      double distance_m = 0.0;
      const double arc_deg =
          geodesic.Inverse(centre->lat_deg, centre->lon_deg, p.lat_deg, p.lon_deg, distance_m);
      if (arc_deg > kMaxExtentDeg) return refused(VolumeError::TooLarge, r);
      volume.extent_m_ = std::max(volume.extent_m_, distance_m);
      const geometry::Point2 q = volume.project(p);
      if (!plane.empty() && norm(q - plane.back()) <= kSameVertex_m) continue;
      kept.push_back(p);
      plane.push_back(q);
    }
    while (plane.size() > 1 && norm(plane.front() - plane.back()) <= kSameVertex_m) {
      plane.pop_back();
      kept.pop_back();
    }
    if (plane.size() < 3) return refused(VolumeError::TooFewVertices, r);
    if (detail::collinear(plane, kSameVertex_m)) return refused(VolumeError::ZeroArea, r);
    if (detail::self_intersecting(plane, kSameVertex_m)) return refused(VolumeError::SelfIntersecting, r);
    volume.rings_.push_back(std::move(kept));
    volume.plane_rings_.push_back(std::move(plane));
  }
  const detail::PlaneRing& outer_plane = volume.plane_rings_[0];
  for (std::size_t h = 1; h < volume.plane_rings_.size(); ++h) {
    const detail::PlaneRing& hole = volume.plane_rings_[h];
    if (detail::rings_touch(hole, outer_plane) || detail::locate(hole[0], outer_plane, 0.0) != 1)
      return refused(VolumeError::HoleOutside, h);
    for (std::size_t other = 1; other < h; ++other) {
      const detail::PlaneRing& earlier = volume.plane_rings_[other];
      if (detail::rings_touch(hole, earlier) || detail::locate(hole[0], earlier, 0.0) != -1 ||
          detail::locate(earlier[0], hole, 0.0) != -1)
        return refused(VolumeError::HolesOverlap, h);
    }
  }
  VolumeResult result;
  result.volume = std::move(volume);
  return result;
}

VolumeResult Volume::circle(LatLon centre, double radius_m, VerticalBand band) {
  if (const VolumeError e = check_position(centre); e != VolumeError::None) return refused(e);
  if (!std::isfinite(radius_m)) return refused(VolumeError::NotFinite);
  if (const VolumeError e = check_band(band); e != VolumeError::None) return refused(e);
  if (!(radius_m > 0.0)) return refused(VolumeError::RadiusNotPositive);
  if (radius_m > kMaxRadius_m) return refused(VolumeError::TooLarge);
  Volume volume;
  volume.is_circle_ = true;
  volume.centre_ = centre;
  volume.extent_m_ = radius_m;
  volume.band_ = band;
  VolumeResult result;
  result.volume = std::move(volume);
  return result;
}

bool Volume::contains_horizontally(LatLon p) const {
  if (is_circle_) {
    double distance_m = 0.0;
    GeographicLib::Geodesic::WGS84().Inverse(centre_.lat_deg, centre_.lon_deg, p.lat_deg, p.lon_deg,
                                             distance_m);
    return distance_m <= extent_m_ + kBoundaryTolerance_m;
  }
  const geometry::Point2 q = project(p);
  if (!is_finite(q)) return false;
  const int in_outer = detail::locate(q, plane_rings_[0], kBoundaryTolerance_m);
  if (in_outer < 0) return false;
  for (std::size_t h = 1; h < plane_rings_.size(); ++h)
    if (detail::locate(q, plane_rings_[h], kBoundaryTolerance_m) > 0) return false;
  return true;
}

bool Volume::contains(LatLon p, double alt_ft) const {
  return band_.floor_ft <= alt_ft && alt_ft <= band_.ceiling_ft && contains_horizontally(p);
}

}  // namespace kew::volume
