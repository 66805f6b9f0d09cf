#pragma once
// The GeoJSON (RFC 7946) reading that [regions] and [volumes] geojson share: the Features
// of a FeatureCollection, a Feature's properties as a TOML table (so that one TableReader
// reads both forms of a region or a volume with the same types, ranges and messages), its
// Polygon or Point geometry, and rings of [lon, lat] positions. What the two word apart
// (the noun, how a ring is named) stays with them. Internal to kew_config.

#include <simdjson.h>

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "kew/config/document.hpp"
#include "kew/geo/projection.hpp"
#include "name_places.hpp"

namespace kew::config::geojson {

namespace dom = simdjson::dom;

inline constexpr std::string_view kLonLat =
    "[lon, lat] (GeoJSON order: longitude first, in [-180, 180], then latitude, in [-90, 90])";

/// Calls `each` with every element of the FeatureCollection's "features", in order.
/// Throws ConfigError "origin: ..." when `text` is not JSON or not a FeatureCollection.
void each_feature(std::string_view text, const std::string& origin, const std::function<void(dom::element)>& each);

/// The items (regions, volumes) of the FeatureCollection `text`, `read(feature, index)`
/// one from each Feature; a name given to an earlier one is refused with the places
/// `place(index, item)` gives ("[feature 2]"). Throws ConfigError "origin: ...".
template <class Item, class Read, class Place>
std::vector<Item> read_features(std::string_view text, const std::string& origin, const Read& read,
                                const Place& place) {
  std::vector<Item> items;
  NamePlaces names;
  each_feature(text, origin, [&](dom::element feature) {
    Item item = read(feature, items.size());
    std::string where = place(items.size(), item);
    if (const std::string* earlier = names.taken(item.name))
      throw ConfigError(
          fmt::format("{}: {} name \"{}\" is already the name of {}", origin, where, item.name, *earlier));
    names.add(item.name, std::move(where));
    items.push_back(std::move(item));
  });
  return items;
}

/// An element of "features", opened before the TableReader that reports its problems (and
/// names it from its properties) exists.
struct Feature {
  dom::object object;
  /// The properties, JSON values as TOML ones; a null property is an absent key, no
  /// properties an empty table.
  toml::table properties;
  /// What is wrong with the Feature or its properties; empty when nothing is.
  std::string problem;
};
Feature open_feature(dom::element element);

/// A Feature's geometry: a Polygon, or a Point (a circle) with properties.radius_nm.
struct Geometry {
  bool polygon = false;
  dom::element coordinates;
};
/// Fails through `r` on any other geometry (`noun`, "region" or "volume", words it), and
/// when radius_nm (NaN: absent) is given with a Polygon or missing with a Point.
Geometry polygon_or_point(const TableReader& r, dom::object feature, std::string_view noun, double radius_nm);

/// A Point's [lon, lat] (an elevation ignored); fails through `r` otherwise.
geo::GeodeticPosition point_position(const TableReader& r, dom::element coordinates);

/// What is wrong with a ring, for the caller to word: regions and volumes name their rings
/// differently.
enum class RingFault { None, NotArray, BadPosition, NotClosed };
struct Ring {
  std::vector<geo::GeodeticPosition> positions;  ///< without the closing position
  RingFault fault = RingFault::None;
  std::size_t bad_position = 0;  ///< BadPosition: which, from 1
};
/// A Polygon's ring: positions [lon, lat] in range (an elevation ignored), closed (at
/// least 4, the last equal to the first, RFC 7946 §3.1.6).
Ring read_ring(dom::element ring);

}  // namespace kew::config::geojson
