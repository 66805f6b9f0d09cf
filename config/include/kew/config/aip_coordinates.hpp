#pragma once
// Positions as an AIP writes them (ICAO Annex 15, AIP ENR 5.1 and AD 2.17: lateral limits
// of restricted, danger and prohibited areas), so that a volume can be pasted from it:
//   "471234N 0083456E - 471500N 0084000E - 470830.5N 0084512E"
// Each position is latitude DDMMSS[.s] then N or S, and longitude DDDMMSS[.s] then E or W
// (seconds may be left out: DDMM and DDDMM); positions are separated by "-", "," or
// white space. A last position equal to the first (the ring written closed) is dropped.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kew/geo/projection.hpp"

namespace kew::config {

/// The positions of `text` in order (degrees, WGS84), or nullopt with `error` naming the
/// position at fault (1-based) and what is wrong with it. Arcs and words ("along the
/// border", "clockwise arc") are refused: write them out as positions.
std::optional<std::vector<geo::GeodeticPosition>> parse_aip_coordinates(std::string_view text, std::string& error);

}  // namespace kew::config
