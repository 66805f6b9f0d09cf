#pragma once
// Real aerodromes, the end points of the generator's global scenario (replay/README.md):
// a fixed table of 240 on every continent, from the busiest hubs to the Arctic, Pacific
// and Antarctic fields that put routes over the poles, the oceans and the antimeridian.
// The data and its source are in replay/src/generator/airports.cpp.

#include <cstdint>
#include <span>
#include <string_view>

namespace kew::replay {

/// The continent an aerodrome lies on (islands with the continent they are usually
/// counted with: the Azores and Iceland with Europe, the Canaries and Ascension with
/// Africa, Greenland with North America, Hawaii and Easter Island with Oceania).
enum class Continent : std::uint8_t { Africa, Antarctica, Asia, Europe, NorthAmerica, Oceania, SouthAmerica };

struct Airport {
  std::string_view icao;  ///< ICAO location indicator: 4 upper-case letters
  double lat_deg;         ///< aerodrome reference point, WGS84 degrees in [−90, 90]
  double lon_deg;         ///< WGS84 degrees in [−180, 180], east positive
  double elevation_ft;    ///< aerodrome elevation, feet above mean sea level
  Continent continent;
};

/// Every aerodrome of the table, in a fixed order (the generator's draws index it, so a
/// change of order or content changes the global scenario's records); ICAO codes are
/// unique.
std::span<const Airport> world_airports();

}  // namespace kew::replay
