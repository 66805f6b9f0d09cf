#pragma once
// The names of regions and of volumes are unique across the TOML tables and the GeoJSON
// file alike: where each name was given, so that a second use is refused with the place
// of the first, and the reading of the file that comes after the tables. Internal to
// kew_config.

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "kew/config/document.hpp"

namespace kew::config {

struct NamePlaces {
  std::vector<std::string> names, places;
  /// The place of an earlier `name`, or nullptr.
  const std::string* taken(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return &places[i];
    return nullptr;
  }
  void add(std::string name, std::string place) {
    names.push_back(std::move(name));
    places.push_back(std::move(place));
  }
};

/// Appends to `items` those of the GeoJSON file that [section] geojson names (resolved
/// beside the configuration file): `parse(text, path)` reads them, `place(index, item)`
/// says where one stands in the file ("[feature 2]"). Fails at the geojson key when the
/// file cannot be read or a name was given before. Returns the resolved path, "" for none.
template <class Item, class Parse, class Place>
std::string append_geojson_items(const Document& document, std::string_view section, NamePlaces& names,
                                 std::vector<Item>& items, const Parse& parse, const Place& place) {
  std::string path;
  document.section(section, [&](TableReader& r) {
    r.path_beside_file("geojson", path);
    if (path.empty()) return;
    std::vector<Item> from_file;
    try {
      from_file = parse(read_config_file(path), path);
    } catch (const ConfigError& e) {
      r.fail(r.node("geojson"), e.what());
    }
    for (std::size_t i = 0; i < from_file.size(); ++i) {
      const std::string where = place(i, from_file[i]);
      if (const std::string* earlier = names.taken(from_file[i].name))
        r.fail(r.node("geojson"),
               fmt::format("{}: {} name \"{}\" is already the name of {}", path, where, from_file[i].name, *earlier));
      names.add(from_file[i].name, fmt::format("{} {}", path, where));
      items.push_back(std::move(from_file[i]));
    }
  });
  return path;
}

}  // namespace kew::config
