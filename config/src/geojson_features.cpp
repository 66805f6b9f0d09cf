#include "geojson_features.hpp"

#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>

namespace kew::config::geojson {

namespace {

using geo::GeodeticPosition;

bool has_type(dom::object object, std::string_view type) {
  std::string_view text;
  return object["type"].get_string().get(text) == simdjson::SUCCESS && text == type;
}

// Appends a JSON value to `out` as TOML, arrays and objects whole: a list of strings is
// read as the TOML list it stands for. False for a null, which TOML cannot hold.
bool append_json(dom::element value, toml::array& out) {
  switch (value.type()) {
    case dom::element_type::INT64:
      out.push_back(value.get_int64().value_unsafe());
      return true;
    case dom::element_type::UINT64:
    case dom::element_type::DOUBLE:
      out.push_back(value.get_double().value_unsafe());
      return true;
    case dom::element_type::BOOL:
      out.push_back(value.get_bool().value_unsafe());
      return true;
    case dom::element_type::STRING:
      out.push_back(std::string(value.get_string().value_unsafe()));
      return true;
    case dom::element_type::ARRAY: {
      const dom::array elements = value.get_array().value_unsafe();
      toml::array array;
      for (const dom::element element : elements)
        if (!append_json(element, array)) return false;
      out.push_back(std::move(array));
      return true;
    }
    case dom::element_type::OBJECT: {
      const dom::object members = value.get_object().value_unsafe();
      toml::table table;
      for (const dom::key_value_pair member : members) {
        toml::array one;
        if (!append_json(member.value, one)) return false;
        table.insert(member.key, std::move(*one.get(0)));
      }
      out.push_back(std::move(table));
      return true;
    }
    case dom::element_type::NULL_VALUE:
      return false;
  }
  return false;
}

// "" or what is wrong with the properties.
std::string properties_table(dom::object properties, toml::table& table) {
  for (const dom::key_value_pair member : properties) {
    if (member.value.is_null()) continue;
    toml::array one;
    if (!append_json(member.value, one))
      return fmt::format("properties.{} holds a null inside it: leave the entry out", member.key);
    if (!table.insert(member.key, std::move(*one.get(0))).second)
      return fmt::format("properties.{} is given twice", member.key);
  }
  return "";
}

std::optional<GeodeticPosition> lon_lat(dom::element element) {
  dom::array position;
  if (element.get_array().get(position) != simdjson::SUCCESS || position.size() < 2 || position.size() > 3)
    return std::nullopt;
  double lon = 0.0, lat = 0.0;
  if (position.at(0).get_double().get(lon) != simdjson::SUCCESS ||
      position.at(1).get_double().get(lat) != simdjson::SUCCESS)
    return std::nullopt;
  if (!(std::abs(lat) <= 90.0 && std::abs(lon) <= 180.0)) return std::nullopt;
  return GeodeticPosition{lat, lon};
}

}  // namespace

void each_feature(std::string_view text, const std::string& origin, const std::function<void(dom::element)>& each) {
  dom::parser parser;
  const simdjson::padded_string padded(text);
  dom::element document;
  if (const auto error = parser.parse(padded).get(document))
    throw ConfigError(fmt::format("{}: not valid JSON ({})", origin, simdjson::error_message(error)));
  dom::object collection;
  dom::array features;
  if (document.get_object().get(collection) != simdjson::SUCCESS || !has_type(collection, "FeatureCollection"))
    throw ConfigError(fmt::format("{}: not a GeoJSON FeatureCollection (an object with \"type\": "
                                  "\"FeatureCollection\")",
                                  origin));
  if (collection["features"].get_array().get(features) != simdjson::SUCCESS)
    throw ConfigError(fmt::format("{}: a FeatureCollection needs a \"features\" array", origin));
  for (const dom::element feature : features) each(feature);
}

Feature open_feature(dom::element element) {
  Feature feature;
  dom::element properties;
  dom::object members;
  if (element.get_object().get(feature.object) != simdjson::SUCCESS || !has_type(feature.object, "Feature"))
    feature.problem = "is not a GeoJSON Feature (an object with \"type\": \"Feature\")";
  else if (feature.object["properties"].get(properties) == simdjson::SUCCESS && !properties.is_null()) {
    // (No properties: the reader's "needs a name".)
    if (properties.get_object().get(members) != simdjson::SUCCESS) feature.problem = "properties must be an object";
    else feature.problem = properties_table(members, feature.properties);
  }
  return feature;
}

Geometry polygon_or_point(const TableReader& r, dom::object feature, std::string_view noun, double radius_nm) {
  dom::object geometry;
  std::string_view type;
  Geometry out;
  if (feature["geometry"].get_object().get(geometry) != simdjson::SUCCESS ||
      geometry["type"].get_string().get(type) != simdjson::SUCCESS)
    r.fail(nullptr, "needs a geometry: a Polygon, or a Point with properties.radius_nm");
  if (type == "MultiPolygon")
    r.fail(nullptr, "a MultiPolygon is not supported: give each polygon a Feature of its own, with its own name");
  if (type != "Polygon" && type != "Point")
    r.fail(nullptr, fmt::format("geometry type \"{}\" is not a {}: a Polygon, or a Point with properties.radius_nm",
                                type, noun));
  if (geometry["coordinates"].get(out.coordinates) != simdjson::SUCCESS)
    r.fail(nullptr, fmt::format("the {} has no coordinates", type));
  out.polygon = type == "Polygon";
  if (out.polygon && !std::isnan(radius_nm))
    r.fail(nullptr, "properties.radius_nm is for a Point (a circle), not a Polygon");
  if (!out.polygon && std::isnan(radius_nm))
    r.fail(nullptr, "a Point needs properties.radius_nm (the circle's radius)");
  return out;
}

GeodeticPosition point_position(const TableReader& r, dom::element coordinates) {
  const auto position = lon_lat(coordinates);
  if (!position) r.fail(nullptr, fmt::format("a Point's coordinates must be {}", kLonLat));
  return *position;
}

Ring read_ring(dom::element element) {
  Ring ring;
  dom::array positions;
  if (element.get_array().get(positions) != simdjson::SUCCESS) {
    ring.fault = RingFault::NotArray;
    return ring;
  }
  for (const dom::element position : positions) {
    const auto p = lon_lat(position);
    if (!p) {
      ring.fault = RingFault::BadPosition;
      ring.bad_position = ring.positions.size() + 1;
      return ring;
    }
    ring.positions.push_back(*p);
  }
  std::vector<GeodeticPosition>& p = ring.positions;
  if (p.size() < 4 || p.front().lat_deg != p.back().lat_deg || p.front().lon_deg != p.back().lon_deg) {
    ring.fault = RingFault::NotClosed;
    return ring;
  }
  p.pop_back();
  return ring;
}

}  // namespace kew::config::geojson
