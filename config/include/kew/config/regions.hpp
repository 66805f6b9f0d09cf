#pragma once
// Parameter regions and inhibition volumes in the configuration (design §4.8): the
// [[region]] tables of a kew TOML file, and the GeoJSON file its [regions] table names.
// deploy/kew.toml documents the keys; deploy/examples/ has a terminal area in each form.
//
// One reader takes a region's keys in both forms (a TOML table, or a GeoJSON Feature's
// properties), with the ranges of [probe] and [alerts], and refuses unknown keys. Only
// the geometry differs:
//   TOML     polygon = [[lat, lon], ...]   or   center = [lat, lon] with radius_nm
//   GeoJSON  a Polygon (exterior ring only; positions [lon, lat], RFC 7946)   or
//            a Point [lon, lat] with properties.radius_nm
// Every region must then pass region::RegionMap::problem(), and names are unique across
// both forms.

#include <string>
#include <string_view>
#include <vector>

#include "kew/pipeline/pipeline.hpp"
#include "kew/region/region_map.hpp"

namespace kew::config {

class Document;

/// The regions of `document`: its [[region]] tables in file order, then the Features of
/// its [regions] geojson file in file order. A relative geojson path is resolved against
/// the directory of the configuration file (unlike the output paths of kewd, which are
/// resolved against the working directory: the regions belong with the file that names
/// them). `pipeline`: the configuration read so far (a region's vertical_ft must exceed
/// [probe] altimetry_tolerance_ft). `geojson_path`, when given, receives the resolved
/// path ("" without [regions]). Throws ConfigError naming file and line (a GeoJSON
/// message names the file and the Feature, from 1).
std::vector<region::Region> read_regions(const Document& document, const PipelineConfig& pipeline,
                                         std::string* geojson_path = nullptr);

/// The regions of a GeoJSON FeatureCollection (`text`; `origin` names it in messages).
/// Each Feature is a Polygon or a Point (with properties.radius_nm); its properties are
/// the keys of a [[region]] table but the geometry. Holes, MultiPolygons (give each
/// polygon its own Feature and name) and other geometries are refused, as are unknown
/// properties; a position's third number (elevation) is ignored, the band being
/// floor_ft and ceiling_ft. Throws ConfigError.
std::vector<region::Region> parse_regions_geojson(std::string_view text, const std::string& origin,
                                                  const PipelineConfig& pipeline);

}  // namespace kew::config
