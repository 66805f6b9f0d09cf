#pragma once
// The sphere cut into zones (design §4.9). Each zone has a core, a lat/lon cell of about
// 1,000 km, and a margin around it; the cores partition the sphere, so every position is
// in exactly one core (its home zone), and a track is a member of every zone whose core
// lies within the margin of its position. A zone projects its members onto its own
// transverse Mercator plane centred on the core: no plane reaches farther than about
// 1,200 km from its meridian, so the point scale k stays below 1.02 everywhere.
//
// Layout: two polar caps (|latitude| ≥ 81°, one zone each, centred on the pole) and 18
// bands of 9° between them, each cut into equal longitude cells, as many as make a cell
// about 1,000 km wide at the band's middle latitude (40 at the equator, 10 next to the
// caps). Cells start at −180°, so the antimeridian is a cell boundary like any other.
//
// Pure geometry: no state beyond the margin. A ZoneKey is dense (below key_end()), so
// the pipeline keeps its zones in a vector indexed by key, and iterating that vector
// visits zones in key order.

#include <cstdint>
#include <string>

#include <vector>

#include "kew/geo/projection.hpp"

namespace kew::zone {

using ZoneKey = std::uint32_t;
inline constexpr ZoneKey kNoZone = ~ZoneKey{0};

/// Zones a position belongs to: rarely more than four (a core's corner).
using ZoneKeys = std::vector<ZoneKey>;

class ZoneTiling {
 public:
  /// Latitude (degrees, > 0) from which a polar cap is one zone.
  static constexpr double kCapLatitude_deg = 81.0;
  /// Height of a latitude band (degrees).
  static constexpr double kBandHeight_deg = 9.0;
  /// Width a core aims at, east to west at its band's middle latitude (metres).
  static constexpr double kCoreWidth_m = 1.0e6;

  /// A worldwide tiling whose zones hold every track within `margin_m` (metres on the
  /// ellipsoid, in (0, 1,000 km]) of their core. Throws std::invalid_argument otherwise.
  explicit ZoneTiling(double margin_m);

  /// The zone whose core holds `p` (WGS84 degrees, latitude in [−90, 90], longitude in
  /// [−180, 180]; 180 is −180). Cores are half-open: [south, north) × [west, east), the
  /// north pole in the north cap.
  ZoneKey home(geo::GeodeticPosition p) const;

  /// Every zone whose core may lie within margin_m() of `p`, in increasing key order,
  /// home(p) among them. A superset: the distance is bounded on a sphere of the
  /// ellipsoid's smallest radius of curvature, widened by 2 %.
  void zones_near(geo::GeodeticPosition p, ZoneKeys& out) const;

  /// The centre of a zone's core (its plane's origin and central meridian): the cell's
  /// middle, or the pole for a cap.
  geo::GeodeticPosition centre(ZoneKey key) const;

  /// A geodesic radius around centre(key) (metres) that holds every position whose
  /// zones_near() names the zone: the farthest corner or edge midpoint of the core plus
  /// √2 widened margins (the box around the margin's cap reaches that far).
  double extent_m(ZoneKey key) const;

  /// A core's bounds (degrees): [south, north) × [west, east); a cap spans every
  /// longitude.
  struct Core {
    double south_deg, north_deg, west_deg, east_deg;
  };
  Core core(ZoneKey key) const;

  /// A readable name, e.g. "N40.5E004.5", "S04.5W177.5", "N90" for a cap (the map, the
  /// metrics' zone label, statistics).
  std::string name(ZoneKey key) const;

  /// True for a key home() can return.
  bool valid(ZoneKey key) const;
  /// One past the largest key: keys are band · kCellsMax + cell.
  static constexpr ZoneKey key_end() { return kBands * kCellsMax; }

  double margin_m() const { return margin_m_; }

  /// The zone that judges a pair whose last reports are `a` and `b` (design §4.9): the
  /// home of their midpoint.
  ZoneKey owner(geo::GeodeticPosition a, geo::GeodeticPosition b) const { return home(midpoint(a, b)); }

  /// A deterministic midpoint of two positions: the normalised sum of their unit vectors
  /// on the sphere (latitudes taken as spherical), equidistant from both; `a` when they
  /// are antipodal.
  static geo::GeodeticPosition midpoint(geo::GeodeticPosition a, geo::GeodeticPosition b);

 private:
  static constexpr std::uint32_t kBands = 20;     // south cap, 18 bands, north cap
  static constexpr std::uint32_t kCellsMax = 64;  // more than any band has
  std::uint32_t cells_[kBands];                   // cells per band (1 for a cap)
  double margin_m_;
  double margin_rad_;  // the widened margin as an angle on the smallest sphere
  static double band_south_deg(std::uint32_t band);
};

}  // namespace kew::zone
