#pragma once
// Parameter regions and inhibition volumes (design §4.8): airspace where the separation
// in use is not the default one (a terminal area's 3 NM) or where no alert may open (an
// aerodrome's circuit). A region is a horizontal shape on the WGS84 ellipsoid (a polygon
// or a circle) between two altitudes, with the parameters that apply inside it.
//
// Geometry is kept apart from the rule that picks a pair's parameters (the Pipeline):
// RegionMap only answers "which region holds this position".

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "kew/geo/projection.hpp"

namespace kew::region {

/// The parameters a region sets; an absent one is the default configuration's.
struct RegionParameters {
  std::optional<double> horizontal_m;    ///< S_h (m, > 0)
  std::optional<double> vertical_m;      ///< S_v (m, > 0)
  std::optional<double> lookahead_s;     ///< T (s, ≥ 0)
  std::optional<double> warning_s;       ///< t_los at or below this is a warning (s, ≥ 0)
  std::optional<int> confirm;            ///< evaluations in conflict to open (≥ 1)
  std::optional<int> clear;              ///< clear evaluations to end (≥ 1)
};

struct Region {
  std::string name;  ///< unique, non-empty; named in alerts
  /// Polygon vertices in order (either orientation, ≥ 3, not closed: the last joins the
  /// first). Edges are straight lines in longitude–latitude (the GeoJSON convention);
  /// a polygon may not cross the antimeridian. Empty for a circle.
  std::vector<geo::GeodeticPosition> polygon;
  /// Circle: centre and radius (geodesic distance on WGS84, m, > 0). Used when polygon
  /// is empty.
  geo::GeodeticPosition center;
  double radius_m = 0.0;
  /// Altitude band (ft): a position is inside when floor_ft ≤ altitude < ceiling_ft.
  double floor_ft = -1.0e9;
  double ceiling_ft = 1.0e9;
  /// No alert opens for a pair with an aircraft inside (design §4.8).
  bool inhibit = false;
  RegionParameters parameters;
};

/// The regions in the order given; the first that holds a position is that position's.
///
/// Where a position is "in" a region (design §4.8):
/// - altitude: floor_ft ≤ altitude < ceiling_ft, so two regions stacked at one altitude
///   never both hold a position;
/// - polygon: inside or on the boundary. The test is a crossing number in
///   (longitude, latitude) with exact orientation predicates (kew/geometry/predicates.hpp):
///   a point exactly on an edge or at a vertex, as the doubles say, is inside, whatever
///   the polygon's orientation, so the answer never depends on rounding or on the
///   order of the vertices;
/// - circle: geodesic distance from the centre (GeographicLib, WGS84) at most radius_m.
/// Boundaries are closed horizontally (two regions sharing an edge both hold a point on
/// it, and the first in order wins) and half-open vertically. A NaN latitude, longitude
/// or altitude is in no region.
class RegionMap {
 public:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  /// Most vertices of one polygon (problem() checks self-intersection pairwise).
  static constexpr std::size_t kMaxPolygonVertices = 10'000;

  RegionMap() = default;
  /// `regions` must be valid (problem() empty for each, names distinct); throws
  /// std::invalid_argument with first_problem() otherwise.
  explicit RegionMap(std::vector<Region> regions);

  /// What is wrong with `r`, in a sentence naming the field, or empty when it is valid.
  /// Besides the ranges above: a polygon has 3 to kMaxPolygonVertices vertices, no two
  /// consecutive ones equal, spans at most 180° of longitude (it may not cross the
  /// antimeridian; a circle may), and neither crosses nor touches itself; a polygon
  /// has radius_m = 0; floor_ft < ceiling_ft; an inhibition volume sets no parameter.
  static std::string problem(const Region& r);
  /// problem() of each region, prefixed with its number (from 1) and name, then names
  /// used twice; empty when `regions` may make a RegionMap.
  static std::string first_problem(const std::vector<Region>& regions);

  /// Whether `r` holds (lat, lon, altitude), tested on its shape alone (no bounding
  /// box): the reference that locate() equals.
  static bool holds(const Region& r, double lat_deg, double lon_deg, double alt_ft);

  /// Index of the first region holding (lat, lon, altitude), or kNone. A bounding box
  /// per region skips most shape tests; it never changes the answer for a latitude in
  /// [-90, 90] and a longitude in [-180, 180] (what the track table admits).
  std::size_t locate(double lat_deg, double lon_deg, double alt_ft) const;

  bool empty() const { return regions_.empty(); }
  std::size_t size() const { return regions_.size(); }
  const Region& operator[](std::size_t i) const { return regions_[i]; }
  const std::vector<Region>& regions() const { return regions_; }

 private:
  struct Box {  // a shape's bounding box in degrees, to skip most tests
    double lat_min, lat_max, lon_min, lon_max;
  };
  std::vector<Region> regions_;
  std::vector<Box> boxes_;
};

}  // namespace kew::region
