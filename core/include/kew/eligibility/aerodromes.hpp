#pragma once
// Aerodrome positions and elevations (design §4.5): where the lower limit of alerting is
// measured from. kew's table is data, not code: data/aerodromes.csv (OurAirports, public
// domain; data/README.md), read by kew_config ([eligibility] aerodromes_file) through the
// parser of aerodrome_csv.hpp and handed to eligibility::Rules in EligibilityConfig.
// A program or test may build a table of its own.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace kew::eligibility {

struct Aerodrome {
  std::string ident;    ///< OurAirports ident: the ICAO indicator where there is one; not empty
  double lat_deg;       ///< WGS84 degrees, [−90, 90]
  double lon_deg;       ///< WGS84 degrees, [−180, 180]
  double elevation_ft;  ///< feet above mean sea level, [kMinElevation_ft, kMaxElevation_ft]
  std::string name = {};  ///< empty when the source gives none
};

/// Elevations outside these (ft) are a wrong unit or a typo, not an aerodrome: the shore
/// of the Dead Sea (−1,266 ft) and Daocheng Yading (14,472 ft) lie well within.
inline constexpr double kMinElevation_ft = -1500.0;
inline constexpr double kMaxElevation_ft = 20000.0;

/// What is wrong with one aerodrome (an empty ident, a figure out of its range, a NaN),
/// as "lat_deg = 95 is outside [-90, 90]"; empty when nothing is.
std::string problem(const Aerodrome& aerodrome);

/// A table of aerodromes and its lookups: by ident, and the nearest to a position on a
/// grid of 1° cells. Immutable once built; share it as shared_ptr<const AerodromeTable>.
class AerodromeTable {
 public:
  /// Takes the rows in their order (the first of two equally near wins). Throws
  /// std::invalid_argument naming the ident when a row has a problem() or an ident is
  /// there twice.
  explicit AerodromeTable(std::vector<Aerodrome> aerodromes);

  std::span<const Aerodrome> aerodromes() const { return aerodromes_; }
  std::size_t size() const { return aerodromes_.size(); }

  /// The aerodrome of this ident (exact, case-sensitive); null when there is none.
  const Aerodrome* find(std::string_view ident) const;

  /// The aerodrome nearest to (lat, lon) (degrees) within radius_m (geodesic metres,
  /// (0, 100 km]), the first of the table on a tie; null when there is none.
  const Aerodrome* nearest(double lat_deg, double lon_deg, double radius_m) const;

 private:
  static std::int32_t cell(int lat_cell, int lon_cell) { return (lat_cell + 90) * 360 + (lon_cell + 180); }

  std::vector<Aerodrome> aerodromes_;
  std::unordered_map<std::string, std::uint32_t> by_ident_;
  std::unordered_map<std::int32_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace kew::eligibility
