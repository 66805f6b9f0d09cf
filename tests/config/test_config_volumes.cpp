// [[volume]] tables (design §4.11): a restricted area from an AIP-style coordinate list, a
// watch circle over a house, a bubble that follows a helicopter, schedules and traffic
// filters; every mistake refused at its line.
#include <gtest/gtest.h>

#include <string>

#include "kew/config/config_error.hpp"
#include "kew/config/document.hpp"
#include "kew/config/aerodromes.hpp"
#include "kew/config/volumes.hpp"

namespace kew::config {
namespace {

struct Read {
  std::vector<volume::WatchedVolume> volumes;
};
Read read(const std::string& text) {
  static const auto aerodromes = load_default_aerodromes();
  return {read_volumes(Document::parse(text, "t.toml"), aerodromes.get())};
}

void expect_error(const std::string& text, const std::string& needle) {
  try {
    read(text);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(VolumeConfig, ReadsEveryShape) {
  const Read c = read(R"([[volume]]
name = "ED-R 138"
kind = "restricted"
polygon = [[49.05, 11.50], [49.05, 11.90], [48.85, 11.90], [48.85, 11.50]]
holes = [[[48.95, 11.65], [48.95, 11.75], [48.90, 11.75], [48.90, 11.65]]]
floor_ft = 0
ceiling_ft = 10000
active = ["Mon-Fri 0600-1800"]
lookahead_s = 180
warning_s = 90

[[volume]]
name = "house"
circle = { lat = 48.3538, lon = 11.7861, radius_nm = 2.0 }
floor_ft = 0
ceiling_ft = 3000
reference = "aerodrome"
aerodrome = "EDDM"

[[volume]]
name = "Christoph 1"
follow = "3DDB41"
radius_nm = 1.0
floor_ft = -500
ceiling_ft = 500
callsigns = ["DLH*"]
squawks = ["7000"]
)");
  ASSERT_EQ(c.volumes.size(), 3u);
  const volume::WatchedVolume& area = c.volumes[0];
  EXPECT_EQ(area.name, "ED-R 138");
  EXPECT_EQ(area.kind, volume::VolumeKind::Restricted);
  ASSERT_TRUE(area.area);
  EXPECT_FALSE(area.area->is_circle());
  EXPECT_EQ(area.area->rings().size(), 2u);
  EXPECT_FALSE(area.schedule.always());
  EXPECT_EQ(area.lookahead_s, 180.0);
  EXPECT_EQ(area.warning_s, 90.0);
  EXPECT_TRUE(area.traffic.everyone());
  const volume::WatchedVolume& house = c.volumes[1];
  EXPECT_EQ(house.kind, volume::VolumeKind::Watch);
  ASSERT_TRUE(house.area && house.area->is_circle());
  EXPECT_NEAR(house.area->extent_m(), 3704.0, 1e-6);
  // Above the aerodrome table's elevation of EDDM (1,487 ft).
  EXPECT_NEAR(house.area->band().floor_ft, 1487.0, 1.0);
  EXPECT_NEAR(house.area->band().ceiling_ft, 4487.0, 1.0);
  const volume::WatchedVolume& bubble = c.volumes[2];
  EXPECT_FALSE(bubble.area);
  EXPECT_EQ(bubble.follow, "3DDB41");
  EXPECT_EQ(bubble.follow_radius_m, 1852.0);
  EXPECT_EQ(bubble.follow_band.floor_ft, -500.0);
  EXPECT_EQ(bubble.traffic.callsigns, std::vector<std::string>{"DLH*"});
  EXPECT_EQ(bubble.traffic.squawks, std::vector<std::uint16_t>{07000});
}

TEST(VolumeConfig, APolygonPastedFromAnAipReadsAsItsDegrees) {
  const Read aip = read(R"([[volume]]
name = "ED-R 138"
kind = "restricted"
polygon = "490300N 0113000E - 490300N 0115400E - 485100N 0115400E - 485100N 0113000E - 490300N 0113000E"
floor_ft = 0
ceiling_ft = 10000
)");
  const Read degrees = read(R"([[volume]]
name = "ED-R 138"
kind = "restricted"
polygon = [[49.05, 11.50], [49.05, 11.90], [48.85, 11.90], [48.85, 11.50]]
floor_ft = 0
ceiling_ft = 10000
)");
  ASSERT_EQ(aip.volumes.size(), 1u);
  const auto& a = aip.volumes[0].area->rings()[0];
  const auto& d = degrees.volumes[0].area->rings()[0];
  ASSERT_EQ(a.size(), d.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i].lat_deg, d[i].lat_deg, 1e-12);
    EXPECT_NEAR(a[i].lon_deg, d[i].lon_deg, 1e-12);
  }
  expect_error(R"([[volume]]
name = "x"
polygon = "490300N 0113000E - 490300N 0115400E - along the border"
floor_ft = 0
ceiling_ft = 1000
)",
               "t.toml:3: [volume 1] polygon: position 3: latitude \"along\" does not end in N or S");
}

TEST(VolumeConfig, RefusesMistakesAtTheirLine) {
  const std::string box = "polygon = [[1, 1], [1, 2], [2, 2], [2, 1]]\nfloor_ft = 0\nceiling_ft = 1000\n";
  expect_error("[[volume]]\n" + box, "a volume needs a name");
  expect_error("[[volume]]\nname = \"a\"\nfloor_ft = 0\nceiling_ft = 1\n", "a volume is one of polygon");
  expect_error("[[volume]]\nname = \"a\"\n" + box + "circle = { lat = 1, lon = 1, radius_nm = 1 }\n", "one of polygon");
  expect_error("[[volume]]\nname = \"a\"\n" + box + "[[volume]]\nname = \"a\"\n" + box,
               "t.toml:7: [volume 2] name \"a\" is already the name of [volume 1]");
  expect_error("[[volume]]\nname = \"a\"\nkind = \"military\"\n" + box, "expected one of restricted");
  expect_error("[[volume]]\nname = \"a\"\npolygon = [[1, 1], [2, 2], [1, 2], [2, 1]]\nfloor_ft = 0\nceiling_ft = 1\n",
               "self_intersecting");
  expect_error("[[volume]]\nname = \"a\"\npolygon = [[1, 1], [1, 2], [2, 2], [2, 1]]\nfloor_ft = 10\nceiling_ft = 1\n",
               "band_inverted");
  expect_error("[[volume]]\nname = \"a\"\n" + box + "holes = [[[5, 5], [5, 6], [6, 6]]]\n", "hole_outside (hole 1)");
  expect_error("[[volume]]\nname = \"a\"\ncircle = { lat = 1, lon = 1 }\nfloor_ft = 0\nceiling_ft = 1\n",
               "a circle needs lat, lon and radius_nm");
  expect_error("[[volume]]\nname = \"a\"\ncircle = { lat = 1, lon = 1, radius_nm = 1, r = 2 }\nfloor_ft = 0\nceiling_ft = 1\n",
               "unknown key \"r\"");
  expect_error("[[volume]]\nname = \"a\"\nfollow = \"abc\"\nfloor_ft = 0\nceiling_ft = 1\n", "follow needs radius_nm");
  expect_error("[[volume]]\nname = \"a\"\n" + box + "reference = \"aerodrome\"\n", "needs aerodrome");
  expect_error("[[volume]]\nname = \"a\"\n" + box + "reference = \"aerodrome\"\naerodrome = \"XXXX\"\n",
               "not in the aerodrome table");
  expect_error("[[volume]]\nname = \"a\"\n" + box + "active = [\"weekdays 0600-1800\"]\n", "is not DAYS HHMM-HHMM");
  expect_error("[[volume]]\nname = \"a\"\n" + box + "warning_s = 200\n", "beyond lookahead_s");
  expect_error("[[volume]]\nname = \"a\"\n" + box + "squawks = [\"7778\"]\n", "squawks");
  // A misspelt key is named before what its absence implies.
  expect_error("[[volume]]\nname = \"a\"\nfollow = \"abc\"\nradius = 1\nfloor_ft = 0\nceiling_ft = 1\n",
               "t.toml:4: [volume 1] unknown key \"radius\"");
  expect_error("[[volume]]\nname = \"a\"\npolygon = [[1, 1], [1, 2], [2, 2], [2, 1]]\nfloor = 0\nceiling_ft = 1\n",
               "t.toml:4: [volume 1] unknown key \"floor\"");
  expect_error("[[volume]]\nname = \"a\"\npolygon = [[1, 1], [1, 2], [1, 1]]\nfloor_ft = 0\nceiling_ft = 1\n",
               "t.toml:3: [volume 1] the volume is refused: too_few_vertices");
  expect_error("[volumes]\ngeojson = 3\n", "t.toml:2: [volumes] geojson must be a string");
  expect_error("[volumes]\nfile = \"v.geojson\"\n", "t.toml:2: [volumes] unknown key \"file\"");
  expect_error("[volumes]\ngeojson = \"kew-absent-volumes.geojson\"\n", "kew-absent-volumes.geojson: cannot open");
}

}  // namespace
}  // namespace kew::config
