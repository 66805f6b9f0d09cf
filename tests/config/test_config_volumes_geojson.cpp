// Volumes in GeoJSON (design §4.11): the file of [volumes] geojson, a FeatureCollection
// whose Features carry a [[volume]] table's keys in their properties and its shape as a
// Polygon (holes allowed, [lon, lat], rings closed) or a Point with radius_nm; read by
// the reader of [[volume]] tables, after them, names unique across both; errors name the
// file, the Feature (from 1, and its name) and the key.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "kew/config/aerodromes.hpp"
#include "kew/config/config_error.hpp"
#include "kew/config/document.hpp"
#include "kew/config/volumes.hpp"

namespace kew::config {
namespace {

using volume::LatLon;
using volume::WatchedVolume;

const eligibility::AerodromeTable* aerodromes() {
  static const auto table = load_default_aerodromes();
  return table.get();
}

std::vector<WatchedVolume> geojson(const std::string& text) {
  return parse_volumes_geojson(text, "v.geojson", aerodromes());
}

std::string feature(const std::string& properties, const std::string& geometry) {
  return R"({"type": "Feature", "properties": )" + properties + R"(, "geometry": )" + geometry + "}";
}

std::string collection(const std::string& features) {
  return R"({"type": "FeatureCollection", "features": [)" + features + "]}";
}

std::string polygon(const std::string& rings) { return R"({"type": "Polygon", "coordinates": )" + rings + "}"; }

std::string point(const std::string& position) { return R"({"type": "Point", "coordinates": )" + position + "}"; }

// ED-R 138 of the TOML test (test_config_volumes.cpp), as GeoJSON: the exterior ring
// counter-clockwise and the hole clockwise, as RFC 7946 §3.1.6 recommends.
const std::string kRestrictedRings =
    "[[[11.50, 49.05], [11.50, 48.85], [11.90, 48.85], [11.90, 49.05], [11.50, 49.05]],"
    " [[11.65, 48.95], [11.75, 48.95], [11.75, 48.90], [11.65, 48.90], [11.65, 48.95]]]";
// The same rings in the other orientation.
const std::string kRestrictedRingsClockwise =
    "[[[11.50, 49.05], [11.90, 49.05], [11.90, 48.85], [11.50, 48.85], [11.50, 49.05]],"
    " [[11.65, 48.95], [11.65, 48.90], [11.75, 48.90], [11.75, 48.95], [11.65, 48.95]]]";
const std::string kBox = polygon("[[[1, 1], [2, 1], [2, 2], [1, 2], [1, 1]]]");
const std::string kBand = R"("floor_ft": 0, "ceiling_ft": 1000)";

TEST(VolumeGeoJson, ReadsAPolygonWithAHoleInEitherOrientation) {
  const std::string keys = R"("kind": "restricted", "floor_ft": 0, "ceiling_ft": 10000, "active": ["Mon-Fri 0600-1800"],
      "lookahead_s": 180, "warning_s": 90)";
  const auto volumes = geojson(collection(feature(R"({"name": "ED-R 138", )" + keys + "}", polygon(kRestrictedRings)) +
                                          "," +
                                          feature(R"({"name": "clockwise", )" + keys + "}",
                                                  polygon(kRestrictedRingsClockwise))));
  ASSERT_EQ(volumes.size(), 2u);
  for (const WatchedVolume& v : volumes) {
    SCOPED_TRACE(v.name);
    EXPECT_EQ(v.kind, volume::VolumeKind::Restricted);
    ASSERT_TRUE(v.area);
    EXPECT_FALSE(v.area->is_circle());
    ASSERT_EQ(v.area->rings().size(), 2u);  // the exterior ring and one hole
    EXPECT_EQ(v.area->rings()[0].size(), 4u);  // the closing position is dropped
    EXPECT_EQ(v.area->rings()[1].size(), 4u);
    EXPECT_EQ(v.area->band().floor_ft, 0.0);
    EXPECT_EQ(v.area->band().ceiling_ft, 10000.0);
    EXPECT_TRUE(v.area->contains_horizontally({49.0, 11.55}));   // in the polygon
    EXPECT_FALSE(v.area->contains_horizontally({48.92, 11.70}));  // in the hole
    EXPECT_FALSE(v.area->contains_horizontally({49.10, 11.70}));  // north of it
    EXPECT_FALSE(v.schedule.always());
    EXPECT_EQ(v.lookahead_s, 180.0);
    EXPECT_EQ(v.warning_s, 90.0);
    EXPECT_TRUE(v.follow.empty());
  }
  EXPECT_TRUE(geojson(collection("")).empty());
}

TEST(VolumeGeoJson, ReadsAPointWithRadiusAsACircleWithEveryKey) {
  const auto volumes = geojson(collection(feature(
      R"({"name": "house", "radius_nm": 2.0, "floor_ft": 0, "ceiling_ft": 3000, "reference": "aerodrome",
          "aerodrome": "EDDM", "callsigns": ["DLH*"], "addresses": ["3DDB41"], "squawks": ["7000"],
          "kind": "watch", "lookahead_s": null})",
      point("[11.7861, 48.3538, 450]"))));
  ASSERT_EQ(volumes.size(), 1u);
  const WatchedVolume& house = volumes[0];
  EXPECT_EQ(house.name, "house");
  ASSERT_TRUE(house.area && house.area->is_circle());
  EXPECT_NEAR(house.area->extent_m(), 3704.0, 1e-6);
  EXPECT_EQ(house.area->centre().lat_deg, 48.3538);
  EXPECT_EQ(house.area->centre().lon_deg, 11.7861);
  // Above the aerodrome table's elevation of EDDM (1,487 ft), the elevation of the
  // position ignored.
  EXPECT_NEAR(house.area->band().floor_ft, 1487.0, 1.0);
  EXPECT_NEAR(house.area->band().ceiling_ft, 4487.0, 1.0);
  EXPECT_EQ(house.traffic.callsigns, std::vector<std::string>{"DLH*"});
  EXPECT_EQ(house.traffic.addresses, std::vector<std::string>{"3DDB41"});
  EXPECT_EQ(house.traffic.squawks, std::vector<std::uint16_t>{07000});
  EXPECT_EQ(house.lookahead_s, WatchedVolume{}.lookahead_s);  // null: absent
  EXPECT_TRUE(house.schedule.always());
}

// GeoJSON positions are [lon, lat]: each case is read the right way round only. Near
// Munich both orders are valid positions, so a reader that swapped them would build a
// volume in the Indian Ocean and fail the containment checks.
TEST(VolumeGeoJson, PositionsAreLongitudeFirst) {
  struct Case {
    const char* what;
    std::string geometry;
    std::string radius;
  };
  const Case cases[] = {
      {"point", point("[11.7861, 48.3538]"), R"("radius_nm": 1, )"},
      {"polygon", polygon("[[[11.76, 48.34], [11.81, 48.34], [11.81, 48.37], [11.76, 48.37], [11.76, 48.34]]]"), ""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const auto volumes =
        geojson(collection(feature(R"({"name": "EDDM", )" + c.radius + kBand + "}", c.geometry)));
    ASSERT_EQ(volumes.size(), 1u);
    const volume::Volume& area = *volumes[0].area;
    EXPECT_NEAR(area.centre().lat_deg, 48.35, 0.02);
    EXPECT_NEAR(area.centre().lon_deg, 11.79, 0.02);
    EXPECT_TRUE(area.contains_horizontally({48.3538, 11.7861}));
    EXPECT_FALSE(area.contains_horizontally({11.7861, 48.3538}));
  }
  // Far from the diagonal, the swapped order is not even a position: lat 100.5.
  const auto bangkok = geojson(collection(feature(R"({"name": "VTBS", "radius_nm": 1, )" + kBand + "}",
                                                  point("[100.75, 13.69]"))));
  EXPECT_EQ(bangkok[0].area->centre().lat_deg, 13.69);
  EXPECT_EQ(bangkok[0].area->centre().lon_deg, 100.75);
}

// The same volume as a [[volume]] table and as a Feature is the same WatchedVolume.
TEST(VolumeGeoJson, AFeatureIsItsTable) {
  const std::string toml = R"([[volume]]
name = "ED-R 138"
kind = "restricted"
polygon = [[49.05, 11.50], [48.85, 11.50], [48.85, 11.90], [49.05, 11.90]]
holes = [[[48.95, 11.65], [48.95, 11.75], [48.90, 11.75], [48.90, 11.65]]]
floor_ft = 0
ceiling_ft = 10000
active = ["Mon-Fri 0600-1800", "Sat 0800-1200"]
callsigns = ["GAF*"]
squawks = ["3701"]
lookahead_s = 180
warning_s = 90
)";
  const auto from_toml = read_volumes(Document::parse(toml, "t.toml"), aerodromes());
  const auto from_json = geojson(collection(
      feature(R"({"name": "ED-R 138", "kind": "restricted", "floor_ft": 0, "ceiling_ft": 10000,
                  "active": ["Mon-Fri 0600-1800", "Sat 0800-1200"], "callsigns": ["GAF*"], "squawks": ["3701"],
                  "lookahead_s": 180, "warning_s": 90})",
              polygon(kRestrictedRings))));
  ASSERT_EQ(from_toml.size(), 1u);
  ASSERT_EQ(from_json.size(), 1u);
  const WatchedVolume& a = from_toml[0];
  const WatchedVolume& b = from_json[0];
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.kind, b.kind);
  ASSERT_TRUE(a.area && b.area);
  ASSERT_EQ(a.area->rings().size(), b.area->rings().size());
  for (std::size_t i = 0; i < a.area->rings().size(); ++i) {
    ASSERT_EQ(a.area->rings()[i].size(), b.area->rings()[i].size());
    for (std::size_t j = 0; j < a.area->rings()[i].size(); ++j) {
      EXPECT_EQ(a.area->rings()[i][j].lat_deg, b.area->rings()[i][j].lat_deg);
      EXPECT_EQ(a.area->rings()[i][j].lon_deg, b.area->rings()[i][j].lon_deg);
    }
  }
  EXPECT_EQ(a.area->band().floor_ft, b.area->band().floor_ft);
  EXPECT_EQ(a.area->band().ceiling_ft, b.area->band().ceiling_ft);
  EXPECT_EQ(a.schedule.windows().size(), b.schedule.windows().size());
  EXPECT_EQ(a.traffic.callsigns, b.traffic.callsigns);
  EXPECT_EQ(a.traffic.squawks, b.traffic.squawks);
  EXPECT_EQ(a.lookahead_s, b.lookahead_s);
  EXPECT_EQ(a.warning_s, b.warning_s);
}

struct ErrorCase {
  std::string text;
  std::string message;  ///< a part of the ConfigError's message
};

const std::string kPointA = feature(R"({"name": "A", "radius_nm": 1, )" + kBand + "}", point("[2, 41]"));

const ErrorCase kErrors[] = {
    {"{\"type\": ", "v.geojson: not valid JSON"},
    {"[]", "v.geojson: not a GeoJSON FeatureCollection"},
    {R"({"type": "FeatureCollection"})", "v.geojson: a FeatureCollection needs a \"features\" array"},
    {collection("3"), "v.geojson: [feature 1] is not a GeoJSON Feature"},
    {collection(R"({"type": "Feature", "properties": [1], "geometry": null})"), "[feature 1] properties must be an object"},
    {collection(feature(R"({"radius_nm": 1})", point("[2, 41]"))), "v.geojson: [feature 1] a volume needs a name"},
    {collection(feature(R"({"name": 7})", point("[2, 41]"))), "v.geojson: [feature 1] name must be a string"},
    // The feature is named by its index and its name; the key by its name.
    {collection(kPointA + "," + feature(R"({"name": "B", "radius_nm": 1, "floor_ft": -200000, "ceiling_ft": 1})",
                                        point("[2, 41]"))),
     "v.geojson: [feature 2 \"B\"] floor_ft = -200000 is outside [-100000, 200000]"},
    {collection(feature(R"({"name": "A", "radius_nm": 1, "stroke": "#f00", )" + kBand + "}", point("[2, 41]"))),
     "v.geojson: [feature 1 \"A\"] unknown key \"stroke\""},
    {collection(feature(R"({"name": "A", "radius": 1, )" + kBand + "}", point("[2, 41]"))),
     "v.geojson: [feature 1 \"A\"] unknown key \"radius\""},
    {collection(feature(R"({"name": "A", "kind": "military", )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] kind = \"military\": expected one of restricted"},
    {collection(feature(R"({"name": "A", "squawks": [7000], )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] squawks: each entry is a string of four octal digits"},
    {collection(feature(R"({"name": "A", "callsigns": "DLH*", )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] callsigns must be an array"},
    {collection(feature(R"({"name": "A", "callsigns": ["DLH*", null], )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] properties.callsigns holds a null inside it"},
    {collection(feature(R"({"name": "A", "active": ["weekdays 0600-1800"], )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] active: "},
    {collection(feature(R"({"name": "A", "warning_s": 200, )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] warning_s = 200 is beyond lookahead_s = 120"},
    {collection(feature(R"({"name": "A", "reference": "aerodrome", )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] reference = \"aerodrome\" needs aerodrome = \"ICAO\""},
    {collection(feature(R"({"name": "A", "reference": "aerodrome", "aerodrome": "XXXX", )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] aerodrome = \"XXXX\" is not in the aerodrome table"},
    {collection(feature(R"({"name": "A", "floor_ft": 0})", kBox)), "[feature 1 \"A\"] a volume needs floor_ft and ceiling_ft"},
    {collection(feature(R"({"name": "A", "floor_ft": 10, "ceiling_ft": 1})", kBox)),
     "[feature 1 \"A\"] the volume is refused: band_inverted"},
    // A followed volume has no geometry; the shape keys of a table are the geometry's.
    {collection(feature(R"({"name": "A", "follow": "3DDB41", "radius_nm": 1, )" + kBand + "}", point("[2, 41]"))),
     "v.geojson: [feature 1 \"A\"] follow is refused in GeoJSON: a followed volume has no geometry of its own"},
    {collection(feature(R"({"name": "A", "polygon": [[1, 1], [1, 2], [2, 2]], )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] properties.polygon is refused: the Feature's geometry is the volume's shape"},
    {collection(feature(R"({"name": "A", "circle": {"lat": 1, "lon": 1, "radius_nm": 1}, )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] properties.circle is refused"},
    {collection(feature(R"({"name": "A", "holes": [], )" + kBand + "}", kBox)), "[feature 1 \"A\"] properties.holes is refused"},
    // Geometries.
    {collection(R"({"type": "Feature", "properties": {"name": "A", "floor_ft": 0, "ceiling_ft": 1}})"),
     "v.geojson: [feature 1 \"A\"] needs a geometry: a Polygon, or a Point with properties.radius_nm"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", "null")), "[feature 1 \"A\"] needs a geometry"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", R"({"type": "LineString", "coordinates": [[2, 41], [3, 42]]})")),
     "v.geojson: [feature 1 \"A\"] geometry type \"LineString\" is not a volume: a Polygon, or a Point with "
     "properties.radius_nm"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", R"({"type": "MultiPolygon", "coordinates": []})")),
     "[feature 1 \"A\"] a MultiPolygon is not supported: give each polygon a Feature of its own"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", R"({"type": "Polygon"})")),
     "[feature 1 \"A\"] the Polygon has no coordinates"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", polygon("[]"))), "[feature 1 \"A\"] a Polygon needs its exterior ring"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", polygon("[1, 2]"))),
     "[feature 1 \"A\"] a Polygon's coordinates are an array of rings"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", polygon("[[[1, 1], [2, 1], [2, 2], [1, 2]]]"))),
     "[feature 1 \"A\"] Polygon exterior ring is not closed: at least 4 positions, the last equal to the first"},
    {collection(feature(R"({"name": "A", )" + kBand + "}",
                        polygon("[[[1, 1], [2, 1], [2, 2], [1, 2], [1, 1]], [[1.2, 1.2], [1.4, 1.2], [1.4, 1.4]]]"))),
     "[feature 1 \"A\"] Polygon hole 1 is not closed"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", polygon("[[[1, 1], [2, 1], [1, 1]]]"))),
     "[feature 1 \"A\"] Polygon exterior ring is not closed: at least 4 positions"},
    // Fewer than 3 distinct vertices, though closed.
    {collection(feature(R"({"name": "A", )" + kBand + "}", polygon("[[[1, 1], [2, 1], [2, 1], [1, 1]]]"))),
     "[feature 1 \"A\"] the volume is refused: too_few_vertices"},
    {collection(feature(R"({"name": "A", )" + kBand + "}",
                        polygon("[[[1, 1], [2, 1], [2, 2], [1, 2], [1, 1]], [[1.2, 1.2], [1.4, 1.2], [1.2, 1.2], "
                                "[1.2, 1.2]]]"))),
     "[feature 1 \"A\"] the volume is refused: too_few_vertices (hole 1)"},
    {collection(feature(R"({"name": "A", )" + kBand + "}",
                        polygon("[[[1, 1], [2, 1], [2, 2], [1, 2], [1, 1]], [[5, 5], [6, 5], [6, 6], [5, 5]]]"))),
     "[feature 1 \"A\"] the volume is refused: hole_outside (hole 1)"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", polygon("[[[1, 1], [2, 2], [1, 2], [2, 1], [1, 1]]]"))),
     "[feature 1 \"A\"] the volume is refused: self_intersecting"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", polygon("[[[1, 1], [1, 95], [2, 2], [1, 1]]]"))),
     "[feature 1 \"A\"] Polygon exterior ring: position 2 must be [lon, lat] (GeoJSON order: longitude first"},
    {collection(feature(R"({"name": "A", )" + kBand + "}",
                        polygon("[[[1, 1], [2, 1], [2, 2], [1, 2], [1, 1]], [[1.2, 1.2], [1.4, \"1.2\"]]]"))),
     "[feature 1 \"A\"] Polygon hole 1: position 2 must be [lon, lat]"},
    {collection(feature(R"({"name": "A", "radius_nm": 3, )" + kBand + "}", kBox)),
     "[feature 1 \"A\"] properties.radius_nm is for a Point (a circle), not a Polygon"},
    {collection(feature(R"({"name": "A", )" + kBand + "}", point("[2, 41]"))),
     "[feature 1 \"A\"] a Point needs properties.radius_nm (the circle's radius)"},
    {collection(feature(R"({"name": "A", "radius_nm": 1, )" + kBand + "}", point("[41]"))),
     "[feature 1 \"A\"] a Point's coordinates must be [lon, lat]"},
    {collection(feature(R"({"name": "A", "radius_nm": 0, )" + kBand + "}", point("[2, 41]"))),
     "[feature 1 \"A\"] radius_nm = 0 is outside [0.001, 4800]"},
    {collection(feature(R"({"name": "A", "radius_nm": "3", )" + kBand + "}", point("[2, 41]"))),
     "[feature 1 \"A\"] radius_nm must be a number"},
    // Names are unique within the file.
    {collection(kPointA + "," + kPointA), "v.geojson: [feature 2 \"A\"] name \"A\" is already the name of [feature 1 \"A\"]"},
};

TEST(VolumeGeoJson, RefusesMistakesNamingTheFileTheFeatureAndTheKey) {
  for (const ErrorCase& c : kErrors) {
    try {
      geojson(c.text);
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << c.text << "\n -> " << e.what();
    }
  }
}

// [volumes] geojson: a path relative to the configuration file's directory, read after
// the [[volume]] tables, with the configuration size cap; names unique across both.
TEST(VolumeGeoJson, TheFileIsFoundBesideTheConfigurationAndComesAfterTheTables) {
  const auto dir = std::filesystem::temp_directory_path() / ("kew-volumes-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "etc");
  std::filesystem::create_directories(dir / "elsewhere");
  const std::string config_path = (dir / "etc" / "k.toml").string();
  const std::string volumes_path = (dir / "etc" / "v.geojson").string();
  std::ofstream(volumes_path) << collection(feature(R"({"name": "box", )" + kBand + "}", kBox));
  const std::string table = "[[volume]]\nname = \"house\"\ncircle = { lat = 1.5, lon = 1.5, radius_nm = 1 }\n"
                            "floor_ft = 0\nceiling_ft = 1000\n";
  std::ofstream(config_path) << "[volumes]\ngeojson = \"v.geojson\"\n" << table;
  // From another working directory: the path is the configuration's neighbour.
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir / "elsewhere");
  std::string path = "unset";
  const auto volumes = read_volumes(Document::load(config_path), aerodromes(), &path);
  std::filesystem::current_path(cwd);
  ASSERT_EQ(volumes.size(), 2u);
  EXPECT_EQ(volumes[0].name, "house");
  EXPECT_EQ(volumes[1].name, "box");
  EXPECT_EQ(path, volumes_path);
  read_volumes(Document::parse(table, "t.toml"), aerodromes(), &path);
  EXPECT_EQ(path, "");

  const auto expect_refused = [&](const std::string& text, const std::string& message) {
    std::ofstream(config_path) << text;
    try {
      read_volumes(Document::load(config_path), aerodromes());
      ADD_FAILURE() << "accepted: " << text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  // A name of the file that a table has already.
  expect_refused(table + "[[volume]]\nname = \"box\"\ncircle = { lat = 1, lon = 1, radius_nm = 1 }\n"
                         "floor_ft = 0\nceiling_ft = 1\n[volumes]\ngeojson = \"v.geojson\"\n",
                 config_path + ":12: [volumes] " + volumes_path +
                     ": [feature 1 \"box\"] name \"box\" is already the name of [volume 2]");
  std::ofstream(dir / "etc" / "bad.geojson")
      << collection(kPointA + "," + feature(R"({"name": "B", "lookahead_s": 0, )" + kBand + "}", kBox));
  expect_refused("[volumes]\ngeojson = \"bad.geojson\"\n",
                 config_path + ":2: [volumes] " + (dir / "etc" / "bad.geojson").string() +
                     ": [feature 2 \"B\"] lookahead_s = 0 is outside [1, 3600]");
  {
    std::ofstream big(dir / "etc" / "big.geojson");
    big << collection("") << std::string(kMaxConfigBytes, ' ');
  }
  expect_refused("[volumes]\ngeojson = \"big.geojson\"\n", "big.geojson: larger than 1048576 bytes, refused");
  expect_refused("[volumes]\ngeojson = \"../etc\"\n", "not a regular file (a directory), refused");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kew::config
