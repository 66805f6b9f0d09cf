#pragma once
// Watched volumes in the configuration (design §4.11): the [[volume]] tables of a kew TOML
// file, and the GeoJSON file its [volumes] table names; the volumes the area proximity
// warning watches.
//
// One reader takes a volume's keys in both forms (a TOML table, or a GeoJSON Feature's
// properties) and refuses unknown keys. Only the shape differs:
//   TOML     polygon = [[lat, lon], ...] with holes = [[[lat, lon], ...], ...],
//            circle = { lat, lon, radius_nm },   or   follow = "ID" with radius_nm
//   GeoJSON  a Polygon (exterior ring then holes, positions [lon, lat], each ring
//            closed, RFC 7946)   or   a Point [lon, lat] with properties.radius_nm;
//            no follow (a followed volume has no geometry of its own)
// Every shape must then be one volume::Volume accepts, and names are unique across both
// forms.

#include <string>
#include <string_view>
#include <vector>

#include "kew/config/document.hpp"
#include "kew/eligibility/aerodromes.hpp"
#include "kew/volume/watched_volume.hpp"

namespace kew::config {

/// The volumes of `document`: its [[volume]] tables in file order, then the Features of
/// its [volumes] geojson file in file order. `aerodromes` resolves a band given above an
/// aerodrome (`reference = "aerodrome"`); null refuses such a band. A relative geojson
/// path is resolved against the directory of the configuration file, as [regions]
/// geojson is. `geojson_path`, when given, receives the resolved path ("" without one).
/// Throws ConfigError naming file, line and key (a GeoJSON message names the file, the
/// Feature, from 1, and its name).
std::vector<volume::WatchedVolume> read_volumes(const Document& document, const eligibility::AerodromeTable* aerodromes,
                                                std::string* geojson_path = nullptr);

/// The volumes of a GeoJSON FeatureCollection (`text`; `origin` names it in messages).
/// Each Feature is a Polygon (holes allowed) or a Point with properties.radius_nm (a
/// circle); its properties are the keys of a [[volume]] table but the shape (polygon,
/// holes, circle, follow). MultiPolygons (give each polygon its own Feature and name) and
/// other geometries are refused, as are unknown properties; null properties are absent;
/// a position's third number (elevation) is ignored, the band being floor_ft and
/// ceiling_ft. Throws ConfigError "origin: [feature N "name"] message".
std::vector<volume::WatchedVolume> parse_volumes_geojson(std::string_view text, const std::string& origin,
                                                         const eligibility::AerodromeTable* aerodromes);

}  // namespace kew::config
