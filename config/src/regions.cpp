#include "kew/config/regions.hpp"

#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "geojson_features.hpp"
#include "kew/config/document.hpp"
#include "name_places.hpp"
#include "parameter_ranges.hpp"

namespace kew::config {

namespace {

namespace dom = geojson::dom;
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

// The exterior ring of a Polygon's coordinates, without its closing position.
std::vector<GeodeticPosition> exterior_ring(const TableReader& r, dom::element coordinates) {
  dom::array rings;
  if (coordinates.get_array().get(rings) != simdjson::SUCCESS)
    r.fail(nullptr, "a Polygon's coordinates are an array of rings");
  if (rings.size() == 0) r.fail(nullptr, "a Polygon needs its exterior ring");
  if (rings.size() > 1)
    r.fail(nullptr, fmt::format("a Polygon with holes is not supported ({} interior rings): give only the exterior "
                                "ring",
                                rings.size() - 1));
  geojson::Ring ring = geojson::read_ring(rings.at(0).value_unsafe());
  switch (ring.fault) {
    case geojson::RingFault::None: break;
    case geojson::RingFault::NotArray:
      r.fail(nullptr, "a Polygon's coordinates are an array of rings, each an array of positions");
    case geojson::RingFault::BadPosition:
      r.fail(nullptr, fmt::format("Polygon position {} must be {}", ring.bad_position, geojson::kLonLat));
    case geojson::RingFault::NotClosed:
      r.fail(nullptr,
             "a Polygon's ring is closed: at least 4 positions, the last equal to the first (RFC 7946 §3.1.6)");
  }
  return std::move(ring.positions);
}

Region read_feature(dom::element element, const std::string& origin, std::size_t index,
                    const PipelineConfig& pipeline) {
  const geojson::Feature feature = geojson::open_feature(element);
  TableReader r(feature.properties, origin, fmt::format("feature {}", index + 1));
  if (!feature.problem.empty()) r.fail(nullptr, feature.problem);
  Region region;
  double radius_nm = NAN;
  read_region_keys(r, region, radius_nm, pipeline);
  r.finish();
  const geojson::Geometry geometry = geojson::polygon_or_point(r, feature.object, "region", radius_nm);
  if (geometry.polygon) {
    region.polygon = exterior_ring(r, geometry.coordinates);
  } else {
    region.center = geojson::point_position(r, geometry.coordinates);
    region.radius_m = radius_nm * kNauticalMile;
  }
  check_region(r, nullptr, region);
  return region;
}

// "[feature 2]": where messages place a Feature (by number only, as they always have).
std::string feature_place(std::size_t index, const Region&) { return fmt::format("[feature {}]", index + 1); }

}  // namespace

std::vector<Region> parse_regions_geojson(std::string_view text, const std::string& origin,
                                          const PipelineConfig& pipeline) {
  return geojson::read_features<Region>(
      text, origin,
      [&](dom::element feature, std::size_t index) { return read_feature(feature, origin, index, pipeline); },
      feature_place);
}

std::vector<Region> read_regions(const Document& document, const PipelineConfig& pipeline,
                                 std::string* geojson_path) {
  std::vector<Region> regions;
  NamePlaces names;
  document.each_table("region", [&](TableReader& r, std::size_t index) {
    Region region = read_region_table(r, pipeline);
    if (const std::string* earlier = names.taken(region.name))
      r.fail(r.node("name"), fmt::format("name \"{}\" is already the name of {}", region.name, *earlier));
    names.add(region.name, fmt::format("[region {}]", index + 1));
    regions.push_back(std::move(region));
  });
  const std::string path = append_geojson_items(
      document, "regions", names, regions,
      [&](const std::string& text, const std::string& origin) { return parse_regions_geojson(text, origin, pipeline); },
      feature_place);
  if (geojson_path) *geojson_path = path;
  return regions;
}

}  // namespace kew::config
