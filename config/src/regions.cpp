#include "kew/config/regions.hpp"

#include <simdjson.h>

#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "kew/config/document.hpp"
#include "parameter_ranges.hpp"

namespace kew::config {

namespace {

namespace dom = simdjson::dom;
using geo::GeodeticPosition;
using ranges::kFoot;
using ranges::kNauticalMile;
using region::Region;
using region::RegionMap;

constexpr ranges::Range kRadiusNm{0.1, 1000.0};
constexpr ranges::Range kAltitudeFt{-5000.0, 200000.0};  // as [tracks] min/max_altitude_ft

// The keys of a region, in a [[region]] table or a GeoJSON Feature's properties, but its
// geometry: radius_nm (NaN when absent) is placed by the caller, which knows the shape.
void read_region_keys(TableReader& r, Region& region, double& radius_nm, const PipelineConfig& pipeline) {
  r.string("name", region.name);
  if (region.name.empty())
    r.fail(r.node("name") ? r.node("name") : r.table_node(), "a region needs a name (a non-empty string)");
  r.number("radius_nm", radius_nm, kRadiusNm.lo, kRadiusNm.hi);
  r.number("floor_ft", region.floor_ft, kAltitudeFt.lo, kAltitudeFt.hi);
  r.number("ceiling_ft", region.ceiling_ft, kAltitudeFt.lo, kAltitudeFt.hi);
  r.boolean("inhibit", region.inhibit);
  // Absent parameters stay NaN (or 0 for the counts, below their range): the defaults'.
  double horizontal_nm = NAN, vertical_ft = NAN, lookahead_s = NAN, warning_s = NAN;
  int confirm = 0, clear = 0;
  r.number("horizontal_nm", horizontal_nm, ranges::kHorizontalNm.lo, ranges::kHorizontalNm.hi);
  r.number("vertical_ft", vertical_ft, ranges::kVerticalFt.lo, ranges::kVerticalFt.hi);
  r.number("lookahead_s", lookahead_s, ranges::kLookaheadS.lo, ranges::kLookaheadS.hi);
  r.number("warning_s", warning_s, ranges::kWarningS.lo, ranges::kWarningS.hi);
  r.integer("confirm", confirm, ranges::kEvaluationsMin, ranges::kEvaluationsMax);
  r.integer("clear", clear, ranges::kEvaluationsMin, ranges::kEvaluationsMax);
  region::RegionParameters& p = region.parameters;
  if (!std::isnan(horizontal_nm)) p.horizontal_m = horizontal_nm * kNauticalMile;
  if (!std::isnan(vertical_ft)) p.vertical_m = vertical_ft * kFoot;
  if (!std::isnan(lookahead_s)) p.lookahead_s = lookahead_s;
  if (!std::isnan(warning_s)) p.warning_s = warning_s;
  if (confirm != 0) p.confirm = confirm;
  if (clear != 0) p.clear = clear;
  // [probe] requires altimetry_tolerance_ft < vertical_ft; the tolerance is not a region's.
  const double tolerance_ft = pipeline.minima.altimetry_tolerance_m / kFoot;
  if (!std::isnan(vertical_ft) && !(vertical_ft > tolerance_ft))
    r.fail(r.node("vertical_ft"), fmt::format("vertical_ft = {} must be above [probe] altimetry_tolerance_ft = {}",
                                              vertical_ft, tolerance_ft));
}

// What RegionMap::problem() finds in a region read in full (its shape, band, inhibit).
void check_region(const TableReader& r, const toml::node* where, const Region& region) {
  if (std::string problem = RegionMap::problem(region); !problem.empty()) r.fail(where, problem);
}

Region read_region_table(TableReader& r, const PipelineConfig& pipeline) {
  Region region;
  std::optional<GeodeticPosition> center;
  double radius_nm = NAN;
  r.position_list("polygon", region.polygon);
  r.position("center", center);
  read_region_keys(r, region, radius_nm, pipeline);
  r.finish();  // a misspelt key ("radius") before what its absence implies
  if ((r.node("polygon") != nullptr) == center.has_value())
    r.fail(r.table_node(), "a region has either polygon = [[lat, lon], ...] or center = [lat, lon] with radius_nm");
  if (r.node("polygon") && region.polygon.empty()) r.fail(r.node("polygon"), "polygon has no vertices");
  if (center) {
    if (std::isnan(radius_nm)) r.fail(r.node("center"), "center needs radius_nm (the circle's radius)");
    region.center = *center;
    region.radius_m = radius_nm * kNauticalMile;
  } else if (!std::isnan(radius_nm)) {
    r.fail(r.node("radius_nm"), "radius_nm goes with center (a circle), not with polygon");
  }
  check_region(r, r.table_node(), region);
  return region;
}

// ---- GeoJSON (RFC 7946) ----

// A Feature's properties as a TOML table, so that one TableReader reads both forms with
// the same types, ranges and messages. Arrays and objects become an empty array (a type
// error if the key is known, "unknown key" otherwise); null is an absent key.
toml::table properties_table(dom::object properties) {
  toml::table table;
  for (const dom::key_value_pair member : properties) {
    const dom::element value = member.value;
    switch (value.type()) {
      case dom::element_type::INT64:
        table.insert(member.key, value.get_int64().value_unsafe());
        break;
      case dom::element_type::UINT64:
      case dom::element_type::DOUBLE:
        table.insert(member.key, value.get_double().value_unsafe());
        break;
      case dom::element_type::BOOL:
        table.insert(member.key, value.get_bool().value_unsafe());
        break;
      case dom::element_type::STRING:
        table.insert(member.key, std::string(value.get_string().value_unsafe()));
        break;
      case dom::element_type::NULL_VALUE:
        break;
      default:
        table.insert(member.key, toml::array{});
        break;
    }
  }
  return table;
}

bool has_type(dom::object object, std::string_view type) {
  std::string_view text;
  return object["type"].get_string().get(text) == simdjson::SUCCESS && text == type;
}

// A GeoJSON position [lon, lat] or [lon, lat, elevation] (elevation ignored), in range.
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
constexpr std::string_view kLonLat =
    "[lon, lat] (GeoJSON order: longitude first, in [-180, 180], then latitude, in [-90, 90])";

// The exterior ring of a Polygon's coordinates, without its closing position.
std::vector<GeodeticPosition> exterior_ring(const TableReader& r, dom::array rings) {
  if (rings.size() == 0) r.fail(nullptr, "a Polygon needs its exterior ring");
  if (rings.size() > 1)
    r.fail(nullptr, fmt::format("a Polygon with holes is not supported ({} interior rings): give only the exterior "
                                "ring",
                                rings.size() - 1));
  dom::array ring;
  if (rings.at(0).get_array().get(ring) != simdjson::SUCCESS)
    r.fail(nullptr, "a Polygon's coordinates are an array of rings, each an array of positions");
  std::vector<GeodeticPosition> polygon;
  for (const dom::element element : ring) {
    const auto position = lon_lat(element);
    if (!position) r.fail(nullptr, fmt::format("Polygon position {} must be {}", polygon.size() + 1, kLonLat));
    polygon.push_back(*position);
  }
  if (polygon.size() < 4 || polygon.front().lat_deg != polygon.back().lat_deg ||
      polygon.front().lon_deg != polygon.back().lon_deg)
    r.fail(nullptr, "a Polygon's ring is closed: at least 4 positions, the last equal to the first (RFC 7946 §3.1.6)");
  polygon.pop_back();
  return polygon;
}

Region read_feature(dom::element feature, const std::string& origin, std::size_t index,
                    const PipelineConfig& pipeline) {
  dom::object object;
  toml::table table;
  std::string_view problem;  // found before the reader that reports it exists
  dom::element properties;
  dom::object members;
  if (feature.get_object().get(object) != simdjson::SUCCESS || !has_type(object, "Feature"))
    problem = "is not a GeoJSON Feature (an object with \"type\": \"Feature\")";
  else if (object["properties"].get(properties) == simdjson::SUCCESS && !properties.is_null()) {
    // (No properties: "a region needs a name" below.)
    if (properties.get_object().get(members) != simdjson::SUCCESS) problem = "properties must be an object";
    else table = properties_table(members);
  }
  TableReader r(table, origin, fmt::format("feature {}", index + 1));
  if (!problem.empty()) r.fail(nullptr, problem);
  Region region;
  double radius_nm = NAN;
  read_region_keys(r, region, radius_nm, pipeline);
  r.finish();
  dom::object geometry;
  std::string_view type;
  dom::element coordinates;
  if (object["geometry"].get_object().get(geometry) != simdjson::SUCCESS ||
      geometry["type"].get_string().get(type) != simdjson::SUCCESS)
    r.fail(nullptr, "needs a geometry: a Polygon, or a Point with properties.radius_nm");
  if (type == "MultiPolygon")
    r.fail(nullptr, "a MultiPolygon is not supported: give each polygon a Feature of its own, with its own name");
  if (type != "Polygon" && type != "Point")
    r.fail(nullptr, fmt::format("geometry type \"{}\" is not a region: a Polygon, or a Point with "
                                "properties.radius_nm",
                                type));
  if (geometry["coordinates"].get(coordinates) != simdjson::SUCCESS)
    r.fail(nullptr, fmt::format("the {} has no coordinates", type));
  if (type == "Polygon") {
    if (!std::isnan(radius_nm)) r.fail(nullptr, "properties.radius_nm is for a Point (a circle), not a Polygon");
    dom::array rings;
    if (coordinates.get_array().get(rings) != simdjson::SUCCESS)
      r.fail(nullptr, "a Polygon's coordinates are an array of rings");
    region.polygon = exterior_ring(r, rings);
  } else {
    if (std::isnan(radius_nm)) r.fail(nullptr, "a Point needs properties.radius_nm (the circle's radius)");
    const auto center = lon_lat(coordinates);
    if (!center) r.fail(nullptr, fmt::format("a Point's coordinates must be {}", kLonLat));
    region.center = *center;
    region.radius_m = radius_nm * kNauticalMile;
  }
  check_region(r, nullptr, region);
  return region;
}

// Where each name was given, to refuse a second use.
struct Names {
  std::vector<std::string> names, places;
  /// The place of an earlier region named `name`, or nullptr.
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

}  // namespace

std::vector<Region> parse_regions_geojson(std::string_view text, const std::string& origin,
                                          const PipelineConfig& pipeline) {
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
  std::vector<Region> regions;
  Names names;
  for (const dom::element feature : features) {
    Region region = read_feature(feature, origin, regions.size(), pipeline);
    const std::string place = fmt::format("[feature {}]", regions.size() + 1);
    if (const std::string* earlier = names.taken(region.name))
      throw ConfigError(fmt::format("{}: {} name \"{}\" is already the name of {}", origin, place, region.name, *earlier));
    names.add(region.name, place);
    regions.push_back(std::move(region));
  }
  return regions;
}

std::vector<Region> read_regions(const Document& document, const PipelineConfig& pipeline,
                                 std::string* geojson_path) {
  std::vector<Region> regions;
  Names names;
  document.each_table("region", [&](TableReader& r, std::size_t index) {
    Region region = read_region_table(r, pipeline);
    if (const std::string* earlier = names.taken(region.name))
      r.fail(r.node("name"), fmt::format("name \"{}\" is already the name of {}", region.name, *earlier));
    names.add(region.name, fmt::format("[region {}]", index + 1));
    regions.push_back(std::move(region));
  });
  std::string path;
  document.section("regions", [&](TableReader& r) {
    r.path_beside_file("geojson", path);
    if (path.empty()) return;
    std::vector<Region> from_file;
    try {
      from_file = parse_regions_geojson(read_config_file(path), path, pipeline);
    } catch (const ConfigError& e) {
      r.fail(r.node("geojson"), e.what());
    }
    for (std::size_t i = 0; i < from_file.size(); ++i) {
      if (const std::string* earlier = names.taken(from_file[i].name))
        r.fail(r.node("geojson"), fmt::format("{}: [feature {}] name \"{}\" is already the name of {}", path, i + 1,
                                              from_file[i].name, *earlier));
      names.add(from_file[i].name, fmt::format("{} [feature {}]", path, i + 1));
      regions.push_back(std::move(from_file[i]));
    }
  });
  if (geojson_path) *geojson_path = path;
  return regions;
}

}  // namespace kew::config
