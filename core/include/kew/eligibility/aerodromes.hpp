#pragma once
// Aerodrome positions and elevations (design §4.5): where the lower limit of alerting is
// measured from. The bundled table holds 8,588 aerodromes of every continent, from
// OurAirports' runways.csv (public domain, https://ourairports.com/data/; the generator
// and its rules are in core/src/eligibility/make_aerodromes.py): each with its runway
// thresholds' mean position and highest threshold elevation.

#include <cstdint>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace kew::eligibility {

struct Aerodrome {
  std::string_view ident;  ///< OurAirports ident: the ICAO indicator where there is one
  double lat_deg;          ///< WGS84 degrees, [−90, 90]
  double lon_deg;          ///< WGS84 degrees, [−180, 180]
  double elevation_ft;     ///< feet above mean sea level
};

/// The bundled table, ordered by latitude, then longitude.
std::span<const Aerodrome> bundled_aerodromes();

/// Nearest-aerodrome lookups over a table, on a grid of 1° cells.
class AerodromeIndex {
 public:
  explicit AerodromeIndex(std::span<const Aerodrome> aerodromes);

  /// The aerodrome nearest to (lat, lon) (degrees) within radius_m (geodesic metres,
  /// (0, 100 km]), the first of the table on a tie; null when there is none.
  const Aerodrome* nearest(double lat_deg, double lon_deg, double radius_m) const;

  /// The index of the bundled table, built once.
  static const AerodromeIndex& bundled();

 private:
  static std::int32_t cell(int lat_cell, int lon_cell) { return (lat_cell + 90) * 360 + (lon_cell + 180); }

  std::span<const Aerodrome> aerodromes_;
  std::unordered_map<std::int32_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace kew::eligibility
