// Regions in the configuration (design §4.8, deploy/kew.toml): [[region]] tables and the
// GeoJSON file of [regions], read by one reader of the keys with the ranges of [probe]
// and [alerts]; errors name the file and line (TOML) or the file and Feature (GeoJSON).
#include "kew/config/regions.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "kew/config/document.hpp"
#include "kew/config/shared_config.hpp"

namespace kew::config {
namespace {

using region::Region;

constexpr double kNm = 1852.0;
constexpr double kFt = 0.3048;

SharedConfig read(const std::string& text) { return read_shared_config(Document::parse(text, "t.toml")); }

TEST(ConfigRegions, ReadsPolygonsAndCirclesInFileOrder) {
  const SharedConfig c = read(R"(
[[region]]
name = "LEBL"
center = [41.297, 2.078]
radius_nm = 5
ceiling_ft = 2000
inhibit = true

[[region]]
name = "TMA"
polygon = [[41.0, 1.5], [41.0, 2.6], [41.8, 2.6], [41.8, 1.5]]
floor_ft = -1000
ceiling_ft = 19500
horizontal_nm = 3
vertical_ft = 1000
lookahead_s = 90
warning_s = 45
confirm = 3
clear = 2
)");
  const auto& regions = c.pipeline.regions;
  ASSERT_EQ(regions.size(), 2u);
  const Region& lebl = regions[0];
  EXPECT_EQ(lebl.name, "LEBL");
  EXPECT_TRUE(lebl.polygon.empty());
  EXPECT_EQ(lebl.center.lat_deg, 41.297);  // [lat, lon], as everywhere in kew's TOML
  EXPECT_EQ(lebl.center.lon_deg, 2.078);
  EXPECT_DOUBLE_EQ(lebl.radius_m, 5 * kNm);
  EXPECT_EQ(lebl.floor_ft, Region{}.floor_ft);  // unbounded below
  EXPECT_EQ(lebl.ceiling_ft, 2000.0);
  EXPECT_TRUE(lebl.inhibit);
  EXPECT_FALSE(lebl.parameters.horizontal_m || lebl.parameters.vertical_m || lebl.parameters.lookahead_s ||
               lebl.parameters.warning_s || lebl.parameters.confirm || lebl.parameters.clear);
  const Region& tma = regions[1];
  ASSERT_EQ(tma.polygon.size(), 4u);
  EXPECT_EQ(tma.polygon[1].lat_deg, 41.0);
  EXPECT_EQ(tma.polygon[1].lon_deg, 2.6);
  EXPECT_EQ(tma.radius_m, 0.0);
  EXPECT_EQ(tma.floor_ft, -1000.0);
  EXPECT_FALSE(tma.inhibit);
  EXPECT_DOUBLE_EQ(*tma.parameters.horizontal_m, 3 * kNm);
  EXPECT_DOUBLE_EQ(*tma.parameters.vertical_m, 1000 * kFt);
  EXPECT_EQ(*tma.parameters.lookahead_s, 90.0);
  EXPECT_EQ(*tma.parameters.warning_s, 45.0);
  EXPECT_EQ(*tma.parameters.confirm, 3);
  EXPECT_EQ(*tma.parameters.clear, 2);
  EXPECT_EQ(region::RegionMap::first_problem(regions), "");
  EXPECT_TRUE(read("").pipeline.regions.empty());
  EXPECT_EQ(read("").regions_geojson, "");
}

struct ErrorCase {
  const char* text;
  const char* message;  ///< a part of the ConfigError's message
};

const ErrorCase kTomlErrors[] = {
    {"[[region]]\nname = \"A\"\n", "t.toml:1: [region 1] a region has either polygon = [[lat, lon], ...] or center"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\npolygon = [[41, 2], [41, 3], [42, 3]]\n",
     "t.toml:1: [region 1] a region has either polygon"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\n", "t.toml:3: [region 1] center needs radius_nm"},
    {"[[region]]\nname = \"A\"\npolygon = [[41, 2], [41, 3], [42, 3]]\nradius_nm = 4\n",
     "t.toml:4: [region 1] radius_nm goes with center (a circle), not with polygon"},
    {"[[region]]\nname = \"A\"\npolygon = [[41, 2],\n  [41, 3],\n  [95, 3]]\n",
     "t.toml:5: [region 1] polygon: entry 3 must be [lat, lon]: latitude in [-90, 90] then longitude in [-180, 180]"},
    {"[[region]]\nname = \"A\"\npolygon = [[41, 2], [41, 3, 5], [42, 3]]\n", "polygon: entry 2 must be [lat, lon]"},
    {"[[region]]\nname = \"A\"\npolygon = [41, 2]\n", "polygon: entry 1 must be [lat, lon]"},
    {"[[region]]\nname = \"A\"\npolygon = \"41 2\"\n", "polygon: position 1: latitude \"41\" does not end in N or S"},
    {"[[region]]\nname = \"A\"\npolygon = []\n", "t.toml:3: [region 1] polygon has no vertices"},
    {"[[region]]\nname = \"A\"\npolygon = [[41, 2], [42, 2]]\n", "t.toml:1: [region 1] polygon has 2 vertices, fewer than 3"},
    {"[[region]]\nname = \"A\"\ncenter = [2.1]\nradius_nm = 3\n", "t.toml:3: [region 1] center must be [lat, lon]"},
    {"[[region]]\nname = \"A\"\ncenter = [41, \"2\"]\nradius_nm = 3\n", "center must be [lat, lon]"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 0\n", "t.toml:4: [region 1] radius_nm = 0 is outside [0.1, 1000]"},
    {"[[region]]\nname = \"A\"\npolygon = [[41, 2], [41, 3], [42, 2], [42, 3]]\n",
     "t.toml:1: [region 1] polygon edges 2 (vertex 2 to 3) and 4 (vertex 4 to 1) meet: the polygon intersects itself"},
    {"[[region]]\nname = \"A\"\npolygon = [[0, 179], [0, -179], [1, -179]]\n", "more than 180°: a polygon may not cross the antimeridian"},
    {"[[region]]\ncenter = [41, 2]\nradius_nm = 3\n", "t.toml:1: [region 1] a region needs a name"},
    {"[[region]]\nname = \"\"\ncenter = [41, 2]\nradius_nm = 3\n", "t.toml:2: [region 1] a region needs a name"},
    {"[[region]]\nname = 7\n", "t.toml:2: [region 1] name must be a string"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nfloor_ft = 5000\nceiling_ft = 2000\n",
     "t.toml:1: [region 1] floor_ft = 5000 must be below ceiling_ft = 2000"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nceiling_ft = 300000\n", "ceiling_ft = 300000 is outside [-5000, 200000]"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nhorizontal_nm = 0\n",
     "t.toml:5: [region 1] horizontal_nm = 0 is outside [0.1, 100]"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nconfirm = 0\n", "confirm = 0 is outside [1, 1000]"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nclear = 1.5\n", "clear must be an integer"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nlookahead_s = 4000\n", "lookahead_s = 4000 is outside [0, 3600]"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nwarning_s = -1\n", "warning_s = -1 is outside [0, 3600]"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nvertical_ft = 200\n",
     "t.toml:5: [region 1] vertical_ft = 200 must be above [probe] altimetry_tolerance_ft = 200"},
    {"[probe]\naltimetry_tolerance_ft = 100\n[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\nvertical_ft = 100\n",
     "vertical_ft = 100 must be above [probe] altimetry_tolerance_ft = 100"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\ninhibit = true\nhorizontal_nm = 3\n",
     "t.toml:1: [region 1] an inhibition volume (inhibit) sets no parameters"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\ninhibit = \"yes\"\n", "inhibit must be true or false"},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius = 3\n", "t.toml:4: [region 1] unknown key \"radius\""},
    {"[[region]]\nname = \"A\"\ncenter = [41, 2]\nradius_nm = 3\n[[region]]\nname = \"A\"\ncenter = [42, 2]\nradius_nm = 3\n",
     "t.toml:6: [region 2] name \"A\" is already the name of [region 1]"},
    {"region = 3\n", "t.toml:1: region must be written as [[region]] tables"},
    {"[region]\nname = \"A\"\n", "region must be written as [[region]] tables"},
    {"[regions]\nfile = \"r.geojson\"\n", "t.toml:2: [regions] unknown key \"file\""},
    {"[regions]\ngeojson = 3\n", "t.toml:2: [regions] geojson must be a string"},
    {"[regions]\ngeojson = \"kew-absent-regions.geojson\"\n", "kew-absent-regions.geojson: cannot open"},
};

// Each text must be refused by `read` with a message holding the case's.
template <std::size_t N, class Read>
void expect_errors(const ErrorCase (&cases)[N], Read read) {
  for (const ErrorCase& c : cases) {
    try {
      read(c.text);
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << c.text << "\n -> " << e.what();
    }
  }
}

TEST(ConfigRegions, RefusesMistakesWithFileAndLine) { expect_errors(kTomlErrors, read); }

std::vector<Region> geojson(const std::string& text) { return parse_regions_geojson(text, "r.geojson", {}); }

std::string feature(const std::string& properties, const std::string& geometry) {
  return R"({"type": "Feature", "properties": )" + properties + R"(, "geometry": )" + geometry + "}";
}

std::string collection(const std::string& features) {
  return R"({"type": "FeatureCollection", "features": [)" + features + "]}";
}

const std::string kSquare =
    R"({"type": "Polygon", "coordinates": [[[2.0, 41.0], [3.0, 41.0], [3.0, 42.0], [2.0, 42.0], [2.0, 41.0]]]})";

TEST(ConfigRegions, ReadsGeoJsonPolygonsAndPoints) {
  const auto regions = geojson(collection(
      feature(R"({"name": "LEBL", "radius_nm": 5, "ceiling_ft": 2000, "inhibit": true, "floor_ft": null})",
              R"({"type": "Point", "coordinates": [2.078, 41.297]})") +
      "," +
      feature(R"({"name": "TMA", "horizontal_nm": 3, "vertical_ft": 1000.0, "confirm": 3, "ceiling_ft": 19500})",
              kSquare) +
      "," +
      feature(R"({"name": "3D"})",
              R"({"type": "Polygon", "coordinates": [[[2, 41, 100], [3, 41, 100], [3, 42, 0], [2, 41, 100]]]})")));
  ASSERT_EQ(regions.size(), 3u);
  EXPECT_EQ(regions[0].name, "LEBL");
  EXPECT_EQ(regions[0].center.lat_deg, 41.297);  // GeoJSON positions are [lon, lat]
  EXPECT_EQ(regions[0].center.lon_deg, 2.078);
  EXPECT_DOUBLE_EQ(regions[0].radius_m, 5 * kNm);
  EXPECT_EQ(regions[0].ceiling_ft, 2000.0);
  EXPECT_EQ(regions[0].floor_ft, Region{}.floor_ft);  // null: absent
  EXPECT_TRUE(regions[0].inhibit);
  const Region& tma = regions[1];
  ASSERT_EQ(tma.polygon.size(), 4u);  // the closing position is dropped
  EXPECT_EQ(tma.polygon[1].lat_deg, 41.0);
  EXPECT_EQ(tma.polygon[1].lon_deg, 3.0);
  EXPECT_DOUBLE_EQ(*tma.parameters.horizontal_m, 3 * kNm);
  EXPECT_DOUBLE_EQ(*tma.parameters.vertical_m, 1000 * kFt);
  EXPECT_EQ(*tma.parameters.confirm, 3);
  EXPECT_FALSE(tma.parameters.clear);
  EXPECT_EQ(regions[2].polygon.size(), 3u);  // elevations ignored
  EXPECT_TRUE(geojson(collection("")).empty());
}

const ErrorCase kGeoJsonErrors[] = {
    {"{\"type\": ", "r.geojson: not valid JSON"},
    {"[]", "r.geojson: not a GeoJSON FeatureCollection"},
    {R"({"type": "Feature"})", "r.geojson: not a GeoJSON FeatureCollection"},
    {R"({"type": "FeatureCollection"})", "r.geojson: a FeatureCollection needs a \"features\" array"},
    {R"({"type": "FeatureCollection", "features": [3]})", "r.geojson: [feature 1] is not a GeoJSON Feature"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"}}]})",
     "r.geojson: [feature 1] needs a geometry: a Polygon, or a Point with properties.radius_nm"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"}, "geometry": null}]})",
     "[feature 1] needs a geometry"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": [1], "geometry": null}]})",
     "[feature 1] properties must be an object"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": {"type": "Point", "coordinates": [2, 41]}}]})",
     "[feature 1] a region needs a name"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Polygon", "coordinates": [[[2, 41], [3, 41], [3, 42], [2, 41]], [[2.1, 41.1], [2.2, 41.1], [2.2, 41.2], [2.1, 41.1]]]}}]})",
     "r.geojson: [feature 1] a Polygon with holes is not supported (1 interior rings): give only the exterior ring"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "MultiPolygon", "coordinates": []}}]})",
     "[feature 1] a MultiPolygon is not supported: give each polygon a Feature of its own, with its own name"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "LineString", "coordinates": [[2, 41], [3, 42]]}}]})",
     "[feature 1] geometry type \"LineString\" is not a region: a Polygon, or a Point with properties.radius_nm"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Polygon"}}]})",
     "[feature 1] the Polygon has no coordinates"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Polygon", "coordinates": []}}]})",
     "[feature 1] a Polygon needs its exterior ring"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Polygon", "coordinates": [[[2, 41], [3, 41], [3, 42], [2, 42]]]}}]})",
     "[feature 1] a Polygon's ring is closed: at least 4 positions, the last equal to the first (RFC 7946 §3.1.6)"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Polygon", "coordinates": [[[2, 41], [3, 41], [2, 41]]]}}]})",
     "a Polygon's ring is closed: at least 4 positions"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Polygon", "coordinates": [[[2, 41], [41, 200], [3, 42], [2, 41]]]}}]})",
     "[feature 1] Polygon position 2 must be [lon, lat] (GeoJSON order: longitude first"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Polygon", "coordinates": [[[2, 41], [3, 41], [2, 42], [3, 42], [2, 41]]]}}]})",
     "[feature 1] polygon edges 2 (vertex 2 to 3) and 4 (vertex 4 to 1) meet"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Point", "coordinates": [2, 41]}}]})",
     "[feature 1] a Point needs properties.radius_nm (the circle's radius)"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A", "radius_nm": 3},
        "geometry": {"type": "Point", "coordinates": [41]}}]})",
     "[feature 1] a Point's coordinates must be [lon, lat]"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A", "radius_nm": 3},
        "geometry": {"type": "Polygon", "coordinates": [[[2, 41], [3, 41], [3, 42], [2, 41]]]}}]})",
     "[feature 1] properties.radius_nm is for a Point (a circle), not a Polygon"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A", "radius_nm": 3, "stroke": "#f00"},
        "geometry": {"type": "Point", "coordinates": [2, 41]}}]})",
     "r.geojson: [feature 1] unknown key \"stroke\""},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A", "radius_nm": "3"},
        "geometry": {"type": "Point", "coordinates": [2, 41]}}]})",
     "[feature 1] radius_nm must be a number"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A", "radius_nm": 3, "confirm": [2]},
        "geometry": {"type": "Point", "coordinates": [2, 41]}}]})",
     "[feature 1] confirm must be an integer"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A", "radius_nm": 3, "horizontal_nm": 200},
        "geometry": {"type": "Point", "coordinates": [2, 41]}}]})",
     "[feature 1] horizontal_nm = 200 is outside [0.1, 100]"},
    {R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "A", "radius_nm": 3, "inhibit": true, "clear": 2},
        "geometry": {"type": "Point", "coordinates": [2, 41]}}]})",
     "[feature 1] an inhibition volume (inhibit) sets no parameters"},
    {R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"name": "A", "radius_nm": 3}, "geometry": {"type": "Point", "coordinates": [2, 41]}},
        {"type": "Feature", "properties": {"name": "A", "radius_nm": 4}, "geometry": {"type": "Point", "coordinates": [2, 41]}}]})",
     "r.geojson: [feature 2] name \"A\" is already the name of [feature 1]"},
};

TEST(ConfigRegions, RefusesGeoJsonMistakesNamingTheFeature) { expect_errors(kGeoJsonErrors, geojson); }

// [regions] geojson: a path relative to the configuration file's directory, read after
// the [[region]] tables, with the configuration size cap; names unique across both.
TEST(ConfigRegions, TheGeoJsonFileIsFoundBesideTheConfigurationAndComesAfterTheTables) {
  const auto dir = std::filesystem::temp_directory_path() / ("kew-regions-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "etc");
  const std::string config_path = (dir / "etc" / "k.toml").string();
  std::ofstream(dir / "etc" / "r.geojson")
      << collection(feature(R"({"name": "TMA", "horizontal_nm": 3})", kSquare));
  std::ofstream(config_path) << "[regions]\ngeojson = \"r.geojson\"\n[[region]]\nname = \"LEBL\"\ncenter = [41.3, "
                                "2.1]\nradius_nm = 5\ninhibit = true\n";
  // From another working directory: the path is the configuration's neighbour.
  const SharedConfig c = load_shared_config(config_path);
  ASSERT_EQ(c.pipeline.regions.size(), 2u);
  EXPECT_EQ(c.pipeline.regions[0].name, "LEBL");
  EXPECT_EQ(c.pipeline.regions[1].name, "TMA");
  EXPECT_EQ(c.regions_geojson, (dir / "etc" / "r.geojson").string());

  const auto expect_refused = [&](const std::string& text, const std::string& message) {
    std::ofstream(config_path) << text;
    try {
      load_shared_config(config_path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  expect_refused("[[region]]\nname = \"TMA\"\ncenter = [41.3, 2.1]\nradius_nm = 5\n[regions]\ngeojson = \"r.geojson\"\n",
                 config_path + ":6: [regions] " + (dir / "etc" / "r.geojson").string() +
                     ": [feature 1] name \"TMA\" is already the name of [region 1]");
  std::ofstream(dir / "etc" / "bad.geojson") << collection(feature(R"({"name": "X", "horizontal_nm": 0})", kSquare));
  expect_refused("[regions]\ngeojson = \"bad.geojson\"\n",
                 config_path + ":2: [regions] " + (dir / "etc" / "bad.geojson").string() +
                     ": [feature 1] horizontal_nm = 0 is outside [0.1, 100]");
  {
    std::ofstream big(dir / "etc" / "big.geojson");
    big << collection("") << std::string(kMaxConfigBytes, ' ');
  }
  expect_refused("[regions]\ngeojson = \"big.geojson\"\n", "big.geojson: larger than 1048576 bytes, refused");
  expect_refused("[regions]\ngeojson = \"../etc\"\n", "not a regular file (a directory), refused");
  std::filesystem::remove_all(dir);
}

// deploy/examples: the Barcelona terminal area in TOML and in GeoJSON are the same regions.
TEST(ConfigRegions, TheBarcelonaExamplesAgree) {
  const SharedConfig toml = load_shared_config(std::string(KEW_DEPLOY_DIR) + "/examples/barcelona-tma.toml");
  const SharedConfig json = load_shared_config(std::string(KEW_DEPLOY_DIR) + "/examples/barcelona-tma-geojson.toml");
  ASSERT_EQ(toml.pipeline.regions.size(), 2u);
  ASSERT_EQ(json.pipeline.regions.size(), toml.pipeline.regions.size());
  EXPECT_TRUE(toml.regions_geojson.empty());
  EXPECT_NE(json.regions_geojson.find("examples/barcelona-tma.geojson"), std::string::npos);
  for (std::size_t i = 0; i < toml.pipeline.regions.size(); ++i) {
    const Region& a = toml.pipeline.regions[i];
    const Region& b = json.pipeline.regions[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.polygon.size(), b.polygon.size());
    EXPECT_EQ(a.center.lat_deg, b.center.lat_deg);
    EXPECT_EQ(a.center.lon_deg, b.center.lon_deg);
    EXPECT_EQ(a.radius_m, b.radius_m);
    EXPECT_EQ(a.floor_ft, b.floor_ft);
    EXPECT_EQ(a.ceiling_ft, b.ceiling_ft);
    EXPECT_EQ(a.inhibit, b.inhibit);
    EXPECT_EQ(a.parameters.horizontal_m, b.parameters.horizontal_m);
    EXPECT_EQ(a.parameters.vertical_m, b.parameters.vertical_m);
  }
  // The inhibition volume comes first: inside the terminal area, it would be shadowed.
  EXPECT_TRUE(toml.pipeline.regions[0].inhibit);
  EXPECT_DOUBLE_EQ(*toml.pipeline.regions[1].parameters.horizontal_m, 3 * kNm);
  EXPECT_DOUBLE_EQ(*toml.pipeline.regions[1].parameters.vertical_m, 1000 * kFt);
  // The radar of the shared upc-bcn-cat048 recording, which the examples replay as is.
  ASSERT_EQ(toml.decoding.asterix.radars.size(), 1u);
  EXPECT_EQ(toml.decoding.asterix.radars[0].sac, 20);
  EXPECT_EQ(toml.decoding.asterix.radars[0].sic, 129);
  const region::RegionMap map(toml.pipeline.regions);
  // LEBL ARP at 1,500 ft: inhibited; at 5,000 ft: the terminal area; at FL200: neither.
  const double lat = 41.0 + 17.0 / 60 + 49.0 / 3600, lon = 2.0 + 4.0 / 60 + 42.0 / 3600;
  EXPECT_EQ(map.locate(lat, lon, 1500.0), 0u);
  EXPECT_EQ(map.locate(lat, lon, 5000.0), 1u);
  EXPECT_EQ(map.locate(lat, lon, 20000.0), region::RegionMap::kNone);
}

}  // namespace
}  // namespace kew::config
