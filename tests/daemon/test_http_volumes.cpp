// GET /api/volumes (daemon/src/http/volumes_json.hpp, design §5.8, docs/protocol.md
// "HTTP"): the area proximity warning's volumes as a GeoJSON FeatureCollection. A polygon
// with a hole keeps its rings as [lon, lat], closed, the outer counter-clockwise and the
// hole clockwise whatever the configuration's order; a circle is 72 geodesic points at
// its radius with its centre and radius in properties.circle; a followed volume has no
// geometry and names what it follows; active_now is the schedule at the time asked.

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <simdjson.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "router.hpp"
#include "volumes_json.hpp"

namespace kew::daemon::http {
namespace {

using volume::LatLon;
using volume::Volume;
using volume::VolumeKind;
using volume::WatchedVolume;

constexpr double kMondayNoon = 1714392000.0;  // 2024-04-29 12:00:00Z, a Monday
constexpr double kSundayNoon = 1714305600.0;  // 2024-04-28 12:00:00Z

volume::WeeklySchedule schedule(const std::vector<std::string>& entries) {
  std::string error;
  const auto parsed = volume::WeeklySchedule::parse(entries, error);
  EXPECT_TRUE(parsed) << error;
  return parsed.value_or(volume::WeeklySchedule());
}

/// ED-R 138 of the configuration tests: a box with a hole, both given clockwise (north
/// edge first, going east), floor 0, ceiling 10,000 ft, Mon-Fri 0600-1800.
WatchedVolume restricted_with_hole() {
  WatchedVolume v;
  v.name = "ED-R 138";
  v.kind = VolumeKind::Restricted;
  const volume::Ring outer{{49.05, 11.50}, {49.05, 11.90}, {48.85, 11.90}, {48.85, 11.50}};
  const volume::Ring hole{{48.95, 11.65}, {48.95, 11.75}, {48.90, 11.75}, {48.90, 11.65}};
  v.area = Volume::polygon(outer, {hole}, {0.0, 10000.0}).volume;
  EXPECT_TRUE(v.area);
  v.schedule = schedule({"Mon-Fri 0600-1800"});
  v.lookahead_s = 180.0;
  v.warning_s = 90.0;
  return v;
}

WatchedVolume danger_circle(LatLon centre = {50.0, 8.0}) {
  WatchedVolume v;
  v.name = "EDD-2";
  v.kind = VolumeKind::Danger;
  v.area = Volume::circle(centre, 3704.0, {1000.0, 6500.0}).volume;
  EXPECT_TRUE(v.area);
  return v;
}

WatchedVolume followed() {
  WatchedVolume v;
  v.name = "CHX escort";
  v.kind = VolumeKind::Watch;
  v.follow = "CHX*";
  v.follow_radius_m = 1852.0;
  v.follow_band = {-500.0, 500.0};
  v.lookahead_s = 60.0;
  v.warning_s = 30.0;
  return v;
}

struct Position {
  double lon, lat;
};

std::vector<Position> ring_of(simdjson::dom::element ring) {
  std::vector<Position> out;
  for (simdjson::dom::element p : ring.get_array()) {
    simdjson::dom::array a = p.get_array();
    EXPECT_EQ(a.size(), 2u);
    out.push_back({double(a.at(0)), double(a.at(1))});
  }
  return out;
}

/// Twice the signed area in degrees (x = lon, y = lat): positive when counter-clockwise.
double signed_area2(const std::vector<Position>& ring) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) sum += ring[i].lon * ring[i + 1].lat - ring[i + 1].lon * ring[i].lat;
  return sum;
}

class VolumesDocument : public ::testing::Test {
 protected:
  simdjson::dom::element parse(const std::string& text) {
    simdjson::dom::element doc;
    EXPECT_EQ(parser_.parse(text).get(doc), simdjson::SUCCESS) << text;
    return doc;
  }
  simdjson::dom::parser parser_;
};

TEST_F(VolumesDocument, APolygonWithAHoleACircleAndAFollowedVolume) {
  const std::vector<WatchedVolume> volumes{restricted_with_hole(), danger_circle(), followed()};
  const std::string text = VolumesGeoJson(volumes).text(kMondayNoon);
  ASSERT_EQ(text.back(), '\n');
  const simdjson::dom::element doc = parse(text);
  EXPECT_EQ(std::string_view(doc["type"]), "FeatureCollection");
  EXPECT_EQ(double(doc["t"]), kMondayNoon);
  const simdjson::dom::array features = doc["features"];
  ASSERT_EQ(features.size(), 3u);

  // The polygon: the outer ring and its hole, closed, [lon, lat], in RFC 7946's senses.
  const simdjson::dom::element polygon = features.at(0);
  EXPECT_EQ(std::string_view(polygon["type"]), "Feature");
  EXPECT_EQ(std::string_view(polygon["id"]), "ED-R 138");
  EXPECT_EQ(std::string_view(polygon["geometry"]["type"]), "Polygon");
  const simdjson::dom::array rings = polygon["geometry"]["coordinates"];
  ASSERT_EQ(rings.size(), 2u);
  const std::vector<Position> outer = ring_of(rings.at(0)), hole = ring_of(rings.at(1));
  ASSERT_EQ(outer.size(), 5u);
  ASSERT_EQ(hole.size(), 5u);
  EXPECT_EQ(outer.front().lon, outer.back().lon);
  EXPECT_EQ(outer.front().lat, outer.back().lat);
  EXPECT_EQ(hole.front().lon, hole.back().lon);
  EXPECT_EQ(outer.front().lon, 11.50);  // the first vertex as configured, lon first
  EXPECT_EQ(outer.front().lat, 49.05);
  EXPECT_GT(signed_area2(outer), 0.0) << "outer ring counter-clockwise";
  EXPECT_LT(signed_area2(hole), 0.0) << "hole clockwise";
  for (const Position& p : hole) {
    EXPECT_TRUE(p.lon == 11.65 || p.lon == 11.75) << p.lon;
    EXPECT_TRUE(p.lat == 48.95 || p.lat == 48.90) << p.lat;
  }
  const simdjson::dom::element pp = polygon["properties"];
  EXPECT_EQ(std::string_view(pp["name"]), "ED-R 138");
  EXPECT_EQ(std::string_view(pp["kind"]), "restricted");
  EXPECT_EQ(double(pp["floor_ft"]), 0.0);
  EXPECT_EQ(double(pp["ceiling_ft"]), 10000.0);
  EXPECT_EQ(bool(pp["active_now"]), true);
  EXPECT_EQ(double(pp["lookahead_s"]), 180.0);
  EXPECT_EQ(double(pp["warning_s"]), 90.0);
  EXPECT_EQ(pp["circle"].error(), simdjson::NO_SUCH_FIELD);
  EXPECT_EQ(pp["follow"].error(), simdjson::NO_SUCH_FIELD);

  // The circle: 72 geodesic points at the radius, closed, counter-clockwise.
  const simdjson::dom::element circle = features.at(1);
  const simdjson::dom::array circle_rings = circle["geometry"]["coordinates"];
  ASSERT_EQ(circle_rings.size(), 1u);
  const std::vector<Position> points = ring_of(circle_rings.at(0));
  ASSERT_EQ(points.size(), std::size_t(kCirclePoints) + 1);
  EXPECT_EQ(points.front().lon, points.back().lon);
  EXPECT_EQ(points.front().lat, points.back().lat);
  EXPECT_GT(signed_area2(points), 0.0);
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  for (const Position& p : points) {
    double s = 0.0;
    wgs84.Inverse(50.0, 8.0, p.lat, p.lon, s);
    EXPECT_NEAR(s, 3704.0, 0.05);
  }
  const simdjson::dom::element cp = circle["properties"];
  EXPECT_EQ(std::string_view(cp["kind"]), "danger");
  EXPECT_EQ(double(cp["floor_ft"]), 1000.0);
  EXPECT_EQ(double(cp["ceiling_ft"]), 6500.0);
  EXPECT_EQ(bool(cp["active_now"]), true);
  EXPECT_EQ(double(cp["lookahead_s"]), 120.0);
  EXPECT_EQ(double(cp["warning_s"]), 60.0);
  EXPECT_EQ(double(cp["circle"]["lat"]), 50.0);
  EXPECT_EQ(double(cp["circle"]["lon"]), 8.0);
  EXPECT_EQ(double(cp["circle"]["radius_m"]), 3704.0);

  // The followed volume: no geometry, what it follows, its radius and relative band.
  const simdjson::dom::element follow = features.at(2);
  EXPECT_TRUE(follow["geometry"].is_null());
  const simdjson::dom::element fp = follow["properties"];
  EXPECT_EQ(std::string_view(fp["name"]), "CHX escort");
  EXPECT_EQ(std::string_view(fp["kind"]), "watch");
  EXPECT_EQ(std::string_view(fp["follow"]), "CHX*");
  EXPECT_EQ(double(fp["radius_m"]), 1852.0);
  EXPECT_EQ(double(fp["floor_ft"]), -500.0);
  EXPECT_EQ(double(fp["ceiling_ft"]), 500.0);
  EXPECT_EQ(bool(fp["active_now"]), true);
  EXPECT_EQ(double(fp["lookahead_s"]), 60.0);
  EXPECT_EQ(double(fp["warning_s"]), 30.0);
  EXPECT_EQ(fp["circle"].error(), simdjson::NO_SUCH_FIELD);
}

TEST_F(VolumesDocument, ActiveNowIsTheScheduleAtTheTimeAsked) {
  const VolumesGeoJson document({restricted_with_hole(), danger_circle()});
  const simdjson::dom::array sunday = parse(document.text(kSundayNoon))["features"];
  EXPECT_EQ(bool(sunday.at(0)["properties"]["active_now"]), false);
  EXPECT_EQ(bool(sunday.at(1)["properties"]["active_now"]), true) << "no schedule: always active";
  const simdjson::dom::array monday = parse(document.text(kMondayNoon))["features"];
  EXPECT_EQ(bool(monday.at(0)["properties"]["active_now"]), true);
}

TEST_F(VolumesDocument, ACircleAcrossTheAntimeridianKeepsItsLongitudesContinuous) {
  const VolumesGeoJson document({danger_circle({-16.5, 179.99})});
  const simdjson::dom::array features = parse(document.text(kMondayNoon))["features"];
  const std::vector<Position> points = ring_of(features.at(0)["geometry"]["coordinates"].at(0));
  ASSERT_EQ(points.size(), std::size_t(kCirclePoints) + 1);
  for (std::size_t i = 1; i < points.size(); ++i) EXPECT_LT(std::abs(points[i].lon - points[i - 1].lon), 1.0);
  EXPECT_GT(signed_area2(points), 0.0);
}

TEST_F(VolumesDocument, NoVolumesIsAnEmptyCollection) {
  const simdjson::dom::element doc = parse(VolumesGeoJson({}).text(kMondayNoon));
  EXPECT_EQ(std::string_view(doc["type"]), "FeatureCollection");
  EXPECT_EQ(simdjson::dom::array(doc["features"]).size(), 0u);
}

TEST_F(VolumesDocument, TheRouterServesItAsGeoJson) {
  HttpSource source;
  source.volumes = std::make_shared<const std::vector<WatchedVolume>>(
      std::vector<WatchedVolume>{restricted_with_hole(), danger_circle(), followed()});
  Rejections refusals;
  Router router("", "", {}, source, refusals);
  Request request{boost::beast::http::verb::get, "/api/volumes", 11};
  const Reply reply = router.handle(request, "127.0.0.1:50000", 8747);
  EXPECT_EQ(reply.status, 200u);
  EXPECT_EQ(reply.content_type, "application/geo+json");
  const simdjson::dom::array features = parse(reply.body)["features"];
  ASSERT_EQ(features.size(), 3u);
  EXPECT_EQ(std::string_view(features.at(2)["properties"]["follow"]), "CHX*");

  HttpSource none;
  Router empty("", "", {}, none, refusals);
  const Reply nothing = empty.handle(request, "127.0.0.1:50000", 8747);
  EXPECT_EQ(nothing.status, 200u);
  EXPECT_EQ(simdjson::dom::array(parse(nothing.body)["features"]).size(), 0u);
}

}  // namespace
}  // namespace kew::daemon::http
