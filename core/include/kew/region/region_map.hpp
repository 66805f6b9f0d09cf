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
class RegionMap {
 public:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

  RegionMap() = default;
  /// `regions` must be valid (problem() empty for each, names distinct).
  explicit RegionMap(std::vector<Region> regions);

  /// What is wrong with `r`, in a sentence naming the field, or empty when it is valid.
  static std::string problem(const Region& r);

  /// Index of the first region holding (lat, lon, altitude), or kNone.
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
