#pragma once
// WGS84 → plane projection for the kinetic engine and the probe (design §4.2).
//
// kew uses GeographicLib's transverse Mercator (Krüger series, accurate to nanometres
// within 3,900 km of the central meridian) with the central meridian through the
// reference point and the origin moved to the reference point. It is conformal, so
// near any point the plane is the Earth scaled by one number k (the point scale) and
// rotated by the meridian convergence γ: a velocity maps exactly by that rotation and
// scale, and a distance d between nearby points appears as ≈ k·d. k = 1 on the central
// meridian and grows with the east–west distance x from it, k ≈ 1 + x²/(2R²): about 1.028 at
// the default coverage radius of 1,500 km. The probe therefore compares plane distances
// with S_h scaled by the pair's k (pair_scale()), and alert figures are recomputed on
// the ellipsoid with GeographicLib::Geodesic.

#include <optional>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/TransverseMercator.hpp>

#include "kew/geometry/vector2.hpp"

namespace kew::geo {

struct GeodeticPosition {
  double lat_deg = 0.0;  ///< WGS84 latitude, degrees in [-90, 90]
  double lon_deg = 0.0;  ///< longitude, degrees in [-180, 180]
};

struct PlanePosition {
  geometry::Point2 p;         ///< metres east (x) and north (y) of the reference point
  double scale = 1.0;         ///< point scale k (plane length / ellipsoid length), ≥ 1
  double convergence_deg = 0; ///< γ: bearing of grid north clockwise from true north
};

/// Why project() refused a position.
enum class ProjectionError {
  None,
  NotFinite,          ///< NaN or infinite latitude or longitude
  LatitudeRange,      ///< |lat| > 90
  LongitudeRange,     ///< lon outside [-180, 180]
  OutsideCoverage,    ///< geodesic distance from the reference above the coverage radius
};

class Projection {
 public:
  /// `reference`: the centre (tangent meridian and plane origin). `coverage_radius_m`:
  /// positions farther than this (geodesic distance, metres, > 0, ≤ 3,000 km) are
  /// refused.
  Projection(GeodeticPosition reference, double coverage_radius_m);

  /// Plane position, scale and convergence of a geodetic position, or the reason it is
  /// refused (`error` set, the rest unspecified).
  PlanePosition project(GeodeticPosition position, ProjectionError& error) const;

  /// Inverse of project(): the geodetic position of a plane point (metres).
  GeodeticPosition unproject(geometry::Point2 p) const;

  /// Plane velocity (m/s) of a ground velocity at `at`: ground speed (m/s, ≥ 0) along
  /// the true track (degrees clockwise from north), rotated by −γ and scaled by k.
  geometry::Vector2 velocity_to_plane(const PlanePosition& at, double ground_speed_mps,
                                      double track_deg) const;

  /// Ground speed (m/s) and true track (degrees in [0, 360)) of a plane velocity at `at`.
  void velocity_from_plane(const PlanePosition& at, geometry::Vector2 v, double& ground_speed_mps,
                           double& track_deg) const;

  /// Scale to apply to ellipsoid lengths near two plane points (mean of their k).
  static double pair_scale(double k1, double k2) { return 0.5 * (k1 + k2); }

  /// Largest point scale anywhere within the coverage radius (k at x = radius).
  double max_scale() const { return max_scale_; }

  /// Geodesic distance between two geodetic positions on WGS84, metres.
  static double geodesic_distance_m(GeodeticPosition a, GeodeticPosition b);

  GeodeticPosition reference() const { return reference_; }
  double coverage_radius_m() const { return coverage_radius_m_; }

 private:
  GeodeticPosition reference_;
  double coverage_radius_m_;
  double northing_of_reference_ = 0.0;
  double max_scale_ = 1.0;
  GeographicLib::TransverseMercator mercator_;
};

}  // namespace kew::geo
