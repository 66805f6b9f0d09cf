#pragma once
// Volumes of the area proximity warning (APW): a horizontal area on WGS84 and a band of
// altitudes. The area is a polygon (an outer ring and any number of holes, every edge the
// shortest geodesic between its two vertices) or a geodesic circle (every point at most
// `radius_m` from the centre along a geodesic). The band is [floor_ft, ceiling_ft] in the
// altitude reference of the tracks it is compared with.
//
// A volume is computed on in the gnomonic projection centred at the volume
// (GeographicLib::Gnomonic, Karney 2013, "Algorithms for geodesics", §8): geodesics through
// the centre are straight there, others deviate from their chord by about f·(r/2a)³·r
// (GeographicLib's Gnomonic.hpp), 0.2 mm for r = 100 km, 1.6 m for r = 1,000 km. The
// projection covers less than a hemisphere, so every vertex must lie within
// kMaxExtentDeg of the centre: the centre of a polygon is the normalised mean of the unit
// vectors of its outer vertices, which is well defined across the antimeridian and at a
// pole, and a polygon around a pole (containing it) is an ordinary polygon there.
//
// A volume is built only through Volume::polygon() and Volume::circle(), which refuse
// invalid input with a VolumeError (named by kVolumeErrorNames), never by an exception.

#include <cstddef>
#include <optional>
#include <vector>

#include "kew/geometry/vector2.hpp"
#include "kew/util/name_table.hpp"

namespace kew::volume {

struct LatLon {
  double lat_deg = 0.0;  ///< WGS84 latitude, degrees in [-90, 90]
  double lon_deg = 0.0;  ///< longitude, degrees in [-180, 180]
};

/// A ring of vertices in order (either sense); closing the ring by repeating the first
/// vertex is allowed and ignored.
using Ring = std::vector<LatLon>;

struct VerticalBand {
  double floor_ft = 0.0;    ///< lowest altitude inside (ft), finite
  double ceiling_ft = 0.0;  ///< highest altitude inside (ft), finite, > floor_ft
};

/// Why a volume was refused.
enum class VolumeError {
  None,
  NotFinite,          ///< a latitude, longitude, radius or band limit is NaN or infinite
  LatitudeRange,      ///< |lat| > 90
  LongitudeRange,     ///< lon outside [-180, 180]
  TooFewVertices,     ///< a ring has fewer than 3 distinct vertices (1 mm apart)
  ZeroArea,           ///< a ring's vertices all lie on one geodesic
  SelfIntersecting,   ///< two edges of one ring cross, touch or overlap
  HoleOutside,        ///< a hole is not strictly inside the outer ring (touching counts)
  HolesOverlap,       ///< two holes cross, touch or one contains the other
  TooLarge,           ///< a vertex is farther than kMaxExtentDeg from the centre, or the radius above kMaxRadius_m
  RadiusNotPositive,  ///< a circle's radius is ≤ 0
  BandInverted,       ///< floor_ft ≥ ceiling_ft
};

inline constexpr util::NameTable<VolumeError, 12> kVolumeErrorNames({{
    {VolumeError::None, "none"},
    {VolumeError::NotFinite, "not_finite"},
    {VolumeError::LatitudeRange, "latitude_range"},
    {VolumeError::LongitudeRange, "longitude_range"},
    {VolumeError::TooFewVertices, "too_few_vertices"},
    {VolumeError::ZeroArea, "zero_area"},
    {VolumeError::SelfIntersecting, "self_intersecting"},
    {VolumeError::HoleOutside, "hole_outside"},
    {VolumeError::HolesOverlap, "holes_overlap"},
    {VolumeError::TooLarge, "too_large"},
    {VolumeError::RadiusNotPositive, "radius_not_positive"},
    {VolumeError::BandInverted, "band_inverted"},
}});

/// Largest arc (degrees) from a polygon's centre to any of its vertices: the gnomonic
/// projection must hold the polygon and the part of a path that can reach it.
inline constexpr double kMaxExtentDeg = 80.0;
/// Largest circle radius (m), about 80° of arc.
inline constexpr double kMaxRadius_m = 8.9e6;
/// A point this close to the boundary (m) is on it, and the boundary is inside.
inline constexpr double kBoundaryTolerance_m = 0.01;

struct VolumeResult;

class Volume {
 public:
  /// A polygon: `outer` and `holes` as rings of [lat, lon] (degrees). Holes must lie
  /// strictly inside the outer ring and apart from each other; their area is outside
  /// the volume, their boundary inside it.
  static VolumeResult polygon(const Ring& outer, const std::vector<Ring>& holes, VerticalBand band);

  /// A geodesic circle: `centre` (degrees), `radius_m` in (0, kMaxRadius_m].
  static VolumeResult circle(LatLon centre, double radius_m, VerticalBand band);

  bool is_circle() const { return is_circle_; }

  /// The centre of the projection: the circle's centre, or the polygon's (see above).
  LatLon centre() const { return centre_; }

  /// The circle's radius, or the polygon's extent: the largest geodesic distance from
  /// centre() to a vertex (m). No point of the area is farther from centre().
  double extent_m() const { return extent_m_; }

  VerticalBand band() const { return band_; }

  /// The rings as given, without repeated vertices: [0] outer, then the holes. Empty for
  /// a circle.
  const std::vector<Ring>& rings() const { return rings_; }

  /// The same rings in the gnomonic plane of centre() (m).
  const std::vector<std::vector<geometry::Point2>>& plane_rings() const { return plane_rings_; }

  /// Gnomonic coordinates (m, x east, y north at the centre) of `p`; NaN beyond the
  /// horizon (more than 90° of arc from the centre).
  geometry::Point2 project(LatLon p) const;

  /// The position of gnomonic coordinates `p` (m).
  LatLon unproject(geometry::Point2 p) const;

  /// True when `p` is in the area: inside the outer ring and outside every hole, or
  /// within kBoundaryTolerance_m of a boundary. A polygon's edges are taken as straight
  /// in the gnomonic plane here (see the deviation above).
  bool contains_horizontally(LatLon p) const;

  /// contains_horizontally() and floor_ft ≤ alt_ft ≤ ceiling_ft.
  bool contains(LatLon p, double alt_ft) const;

 private:
  Volume() = default;

  bool is_circle_ = false;
  LatLon centre_;
  double extent_m_ = 0.0;
  VerticalBand band_;
  std::vector<Ring> rings_;
  std::vector<std::vector<geometry::Point2>> plane_rings_;
};

/// What Volume::polygon() and Volume::circle() return: a volume, or why not.
struct VolumeResult {
  VolumeError error = VolumeError::None;
  std::size_t ring = 0;  ///< the ring at fault: 0 the outer ring, i + 1 hole i
  std::optional<Volume> volume;
};

}  // namespace kew::volume
