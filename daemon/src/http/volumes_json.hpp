#pragma once
// GET /api/volumes (design §5.8): the volumes of the area proximity warning (§4.11) as a
// GeoJSON FeatureCollection (RFC 7946) for the map.
//
//   fixed polygon   geometry Polygon: the outer ring, then the holes; positions
//                   [lon, lat], each ring closed, the outer counter-clockwise and the
//                   holes clockwise (§3.1.6)
//   fixed circle    geometry Polygon of kCirclePoints geodesic points at the radius,
//                   closed, counter-clockwise; properties.circle = {lat, lon, radius_m}
//   followed        geometry null; properties.follow (the id or callsign pattern) and
//                   radius_m; floor_ft and ceiling_ft relative to the followed
//                   aircraft's altitude
//
// Every feature's properties also hold name, kind, floor_ft, ceiling_ft, active_now (the
// schedule at the time given), lookahead_s and warning_s; the collection holds "t", that
// time. A ring whose edges cross the antimeridian keeps its longitudes continuous (beyond
// ±180°, as Leaflet draws it) rather than being cut in two (RFC 7946 §3.1.9's SHOULD).
// The geometries are made once; the properties are written at each request.

#include <string>
#include <vector>

#include "kew/volume/watched_volume.hpp"

namespace kew::daemon::http {

/// The points of a circle's outline.
inline constexpr int kCirclePoints = 72;

class VolumesGeoJson {
 public:
  explicit VolumesGeoJson(const std::vector<volume::WatchedVolume>& volumes);

  /// The FeatureCollection, with active_now at `now_unix_s` (UTC seconds), ending in '\n'.
  std::string text(double now_unix_s) const;

 private:
  std::vector<volume::WatchedVolume> volumes_;
  std::vector<std::string> geometries_;  ///< each volume's geometry member, JSON ("null" when followed)
  std::size_t bytes_ = 0;                ///< the geometries' length, to reserve the text
};

}  // namespace kew::daemon::http
