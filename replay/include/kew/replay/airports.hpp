#pragma once
// Real aerodromes, the end points of the generator's global scenario (replay/README.md):
// a fixed selection of 240 on every continent, from the busiest hubs to the Arctic, Pacific
// and Antarctic fields that put routes over the poles, the oceans and the antimeridian.
// The selection (which aerodromes, on which continent) is the generator's own, in
// replay/src/generator/airports.cpp; their positions and elevations are the aerodrome
// table's (data/aerodromes.csv), the one the lower limit of alerting reads.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "kew/eligibility/aerodromes.hpp"

namespace kew::replay {

/// The continent an aerodrome lies on (islands with the continent they are usually
/// counted with: the Azores and Iceland with Europe, the Canaries and Ascension with
/// Africa, Greenland with North America, Hawaii and Easter Island with Oceania).
enum class Continent : std::uint8_t { Africa, Antarctica, Asia, Europe, NorthAmerica, Oceania, SouthAmerica };

/// One aerodrome of the selection.
struct SelectedAirport {
  std::string_view ident;  ///< its ident in the aerodrome table: 4 upper-case letters
  Continent continent;
};

struct Airport {
  std::string_view ident;  ///< the selection's (static storage)
  double lat_deg;          ///< the table's: WGS84 degrees in [−90, 90]
  double lon_deg;          ///< the table's: WGS84 degrees in [−180, 180], east positive
  double elevation_ft;     ///< the table's: feet above mean sea level
  Continent continent;
};

/// The selection, in a fixed order (the generator's draws index it, so a change of order
/// or content changes the global scenario's records); idents are unique.
std::span<const SelectedAirport> selected_airports();

/// The selection with the figures of `aerodromes`, in the selection's order. Throws
/// std::invalid_argument naming the first ident the table lacks.
std::vector<Airport> world_airports(const eligibility::AerodromeTable& aerodromes);

}  // namespace kew::replay
