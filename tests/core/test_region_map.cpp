// Parameter regions and inhibition volumes (design §4.8): which region holds a position,
// against reference cases (polygons with the boundary inside, circles by geodesic
// distance, half-open altitude bands, first in order), the bounding-box prefilter against
// the shape tests alone and a plain ray-casting reference, and what problem() refuses.
#include "kew/region/region_map.hpp"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace kew::region {
namespace {

using geo::GeodeticPosition;

constexpr double kNm = 1852.0;
// LEBL aerodrome reference point (Spanish AIP AD 2-LEBL: 41°17′49″N 002°04′42″E).
constexpr GeodeticPosition kLebl{41.0 + 17.0 / 60 + 49.0 / 3600, 2.0 + 4.0 / 60 + 42.0 / 3600};

Region polygon(std::string name, std::vector<GeodeticPosition> vertices) {
  Region r;
  r.name = std::move(name);
  r.polygon = std::move(vertices);
  return r;
}

Region circle(std::string name, GeodeticPosition center, double radius_m) {
  Region r;
  r.name = std::move(name);
  r.center = center;
  r.radius_m = radius_m;
  return r;
}

// A "U" open to the north: two arms (lon 2.0–2.3 and 2.7–3.0) on a base (lat 41.0–41.3).
const std::vector<GeodeticPosition> kU = {{41.0, 2.0}, {41.0, 3.0}, {42.0, 3.0}, {42.0, 2.7},
                                          {41.3, 2.7}, {41.3, 2.3}, {42.0, 2.3}, {42.0, 2.0}};

struct PointCase {
  const char* what;
  double lat, lon;
  bool inside;
};

const PointCase kUCases[] = {
    {"west arm", 41.8, 2.1, true},
    {"east arm", 41.8, 2.9, true},
    {"base", 41.1, 2.5, true},
    {"the notch (concave part)", 41.8, 2.5, false},
    {"south of the base", 40.9, 2.5, false},
    {"east of everything", 41.5, 3.1, false},
    {"on the south edge", 41.0, 2.5, true},
    {"on the notch's floor", 41.3, 2.5, true},
    {"on the notch's west wall", 41.5, 2.3, true},
    {"on a vertex", 42.0, 2.0, true},
    {"on a notch vertex", 41.3, 2.7, true},
    {"ray through two vertices, west arm", 41.3, 2.1, true},
    {"ray through two vertices, east arm", 41.3, 2.9, true},
    {"ray through two vertices, outside", 41.3, 3.1, false},
    {"level with the top, in the notch", 42.0, 2.5, false},
    {"level with the top, on an arm's top edge", 42.0, 2.8, true},
    {"just north of the top", 42.0000001, 2.1, false},
};

TEST(RegionMap, ConcavePolygonWithItsBoundaryInsideInEitherOrientation) {
  std::vector<GeodeticPosition> reversed(kU.rbegin(), kU.rend());
  for (const auto& vertices : {kU, reversed}) {
    const Region u = polygon("U", vertices);
    ASSERT_EQ(RegionMap::problem(u), "");
    const RegionMap map({u});
    for (const PointCase& c : kUCases) {
      EXPECT_EQ(RegionMap::holds(u, c.lat, c.lon, 5000.0), c.inside) << c.what;
      EXPECT_EQ(map.locate(c.lat, c.lon, 5000.0), c.inside ? 0u : RegionMap::kNone) << c.what;
    }
  }
}

TEST(RegionMap, CircleByGeodesicDistanceAtEveryAzimuth) {
  // 1 mm inside and outside the radius, at centres where a circle's widest longitude is
  // far from due east (high latitudes) and across the antimeridian: the bounding box must
  // never cut off a point the geodesic test takes.
  const GeodeticPosition centres[] = {kLebl, {70.0, 20.0}, {-80.0, -60.0}, {-17.0, 179.9}, {0.0, -179.95}};
  const double radii[] = {5.0 * kNm, 40.0 * kNm, 300.0 * kNm};
  const auto& wgs84 = GeographicLib::Geodesic::WGS84();
  for (const GeodeticPosition& c : centres)
    for (const double radius : radii) {
      const RegionMap map({circle("C", c, radius)});
      for (double azimuth = 0.0; azimuth < 360.0; azimuth += 7.5) {
        for (const auto& [offset, inside] : {std::pair{-1e-3, true}, std::pair{1e-3, false}}) {
          double lat = 0.0, lon = 0.0;
          wgs84.Direct(c.lat_deg, c.lon_deg, azimuth, radius + offset, lat, lon);
          EXPECT_EQ(map.locate(lat, lon, 0.0), inside ? 0u : RegionMap::kNone)
              << c.lat_deg << "," << c.lon_deg << " r=" << radius << " az=" << azimuth << " offset=" << offset;
        }
      }
    }
}

TEST(RegionMap, CircleHoldingAPoleHoldsEveryLongitudeNearIt) {
  const RegionMap map({circle("polar", {88.0, 10.0}, 500e3)});
  for (double lon = -180.0; lon <= 180.0; lon += 15.0) EXPECT_EQ(map.locate(89.9, lon, 0.0), 0u) << lon;
  EXPECT_EQ(map.locate(80.0, 10.0, 0.0), RegionMap::kNone);
}

TEST(RegionMap, AltitudeBandIsHalfOpen) {
  Region r = circle("TMA", kLebl, 40.0 * kNm);
  r.floor_ft = 1000.0;
  r.ceiling_ft = 19500.0;
  const RegionMap map({r});
  const struct {
    double alt_ft;
    bool inside;
  } cases[] = {{999.999, false}, {1000.0, true}, {19499.999, true}, {19500.0, false}, {NAN, false}};
  for (const auto& c : cases)
    EXPECT_EQ(map.locate(kLebl.lat_deg, kLebl.lon_deg, c.alt_ft), c.inside ? 0u : RegionMap::kNone) << c.alt_ft;
  EXPECT_EQ(map.locate(NAN, kLebl.lon_deg, 5000.0), RegionMap::kNone);
  EXPECT_EQ(map.locate(kLebl.lat_deg, NAN, 5000.0), RegionMap::kNone);
}

TEST(RegionMap, TheFirstRegionInOrderWins) {
  Region inhibit = circle("LEBL", kLebl, 5.0 * kNm);
  inhibit.ceiling_ft = 2000.0;
  inhibit.inhibit = true;
  Region tma = circle("TMA", kLebl, 40.0 * kNm);
  tma.ceiling_ft = 19500.0;
  tma.parameters.horizontal_m = 3.0 * kNm;
  Region east = polygon("east", {{41.0, 2.2}, {41.0, 4.0}, {42.0, 4.0}, {42.0, 2.2}});
  const RegionMap map({inhibit, tma, east});
  EXPECT_EQ(map.locate(kLebl.lat_deg, kLebl.lon_deg, 1500.0), 0u);   // inside all three
  EXPECT_EQ(map.locate(kLebl.lat_deg, kLebl.lon_deg, 2000.0), 1u);   // above the inhibition volume
  EXPECT_EQ(map.locate(41.3, 2.5, 1500.0), 1u);                      // TMA and east: TMA is first
  EXPECT_EQ(map.locate(41.3, 2.5, 25000.0), 2u);                     // above the TMA
  EXPECT_EQ(map.locate(41.3, 3.9, 1500.0), 2u);                      // beyond 40 NM
  EXPECT_EQ(map.locate(40.0, 2.0, 1500.0), RegionMap::kNone);
  const RegionMap reordered({east, tma, inhibit});
  EXPECT_EQ(reordered.locate(41.3, 2.5, 1500.0), 0u);
  EXPECT_EQ(reordered.locate(kLebl.lat_deg, kLebl.lon_deg, 1500.0), 1u);  // the inhibition volume is shadowed
  EXPECT_TRUE(RegionMap().empty());
  EXPECT_EQ(RegionMap().locate(kLebl.lat_deg, kLebl.lon_deg, 0.0), RegionMap::kNone);
}

// Plain ray casting in doubles, boundary unspecified: the reference for points that are
// not on an edge (random points never are).
bool ray_cast(const std::vector<GeodeticPosition>& poly, double lat, double lon) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const GeodeticPosition& a = poly[i];
    const GeodeticPosition& b = poly[j];
    if ((a.lat_deg > lat) != (b.lat_deg > lat) &&
        lon < (b.lon_deg - a.lon_deg) * (lat - a.lat_deg) / (b.lat_deg - a.lat_deg) + a.lon_deg)
      inside = !inside;
  }
  return inside;
}

TEST(RegionMap, TheBoundingBoxesNeverChangeTheAnswer) {
  // Random star-shaped polygons and circles (some across the antimeridian or near a
  // pole), random bands; random points near them. locate() must equal the first region
  // whose shape test alone holds the point, and a polygon's test must equal ray casting.
  std::mt19937_64 random(19);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(random); };
  for (int round = 0; round < 40; ++round) {
    std::vector<Region> regions;
    const GeodeticPosition centre{uniform(-70.0, 70.0), round % 4 == 0 ? uniform(178.0, 180.0) : uniform(-170.0, 170.0)};
    while (regions.size() < 6) {
      const GeodeticPosition c{std::clamp(centre.lat_deg + uniform(-3.0, 3.0), -89.0, 89.0),
                               std::clamp(centre.lon_deg + uniform(-3.0, 3.0), -180.0, 180.0)};
      Region r;
      r.name = "r" + std::to_string(regions.size());
      if (unit(random) < 0.5) {
        r.center = c;
        r.radius_m = uniform(1e3, 400e3);
      } else {
        std::vector<double> angles(3 + static_cast<int>(unit(random) * 10));
        for (double& a : angles) a = uniform(0.0, 2.0 * M_PI);
        std::sort(angles.begin(), angles.end());
        for (const double a : angles) {
          const double d = uniform(0.2, 3.0);
          r.polygon.push_back({std::clamp(c.lat_deg + d * std::sin(a), -90.0, 90.0),
                               std::clamp(c.lon_deg + d * std::cos(a), -180.0, 180.0)});
        }
      }
      if (unit(random) < 0.5) {
        r.floor_ft = uniform(0.0, 10000.0);
        r.ceiling_ft = r.floor_ft + uniform(1000.0, 20000.0);
      }
      if (RegionMap::problem(r).empty()) regions.push_back(std::move(r));
    }
    const RegionMap map(regions);
    for (int k = 0; k < 2000; ++k) {
      const double lat = std::clamp(centre.lat_deg + uniform(-8.0, 8.0), -90.0, 90.0);
      double lon = centre.lon_deg + uniform(-8.0, 8.0);
      if (lon > 180.0) lon -= 360.0;
      const double alt = uniform(-1000.0, 35000.0);
      std::size_t expected = RegionMap::kNone;
      for (std::size_t i = 0; i < regions.size() && expected == RegionMap::kNone; ++i)
        if (RegionMap::holds(regions[i], lat, lon, alt)) expected = i;
      ASSERT_EQ(map.locate(lat, lon, alt), expected) << "round " << round << " at " << lat << "," << lon << " " << alt;
      for (const Region& r : regions) {
        if (!r.polygon.empty()) {
          ASSERT_EQ(RegionMap::holds(r, lat, lon, r.floor_ft), ray_cast(r.polygon, lat, lon));
        }
      }
    }
  }
}

struct ProblemCase {
  const char* what;
  void (*change)(Region&);
  const char* message;  ///< a part of problem(); "" when valid
};

void square(Region& r) { r.polygon = {{41.0, 2.0}, {41.0, 3.0}, {42.0, 3.0}, {42.0, 2.0}}; }

const ProblemCase kProblems[] = {
    {"a valid circle", [](Region&) {}, ""},
    {"a valid polygon", [](Region& r) { square(r); r.radius_m = 0.0; }, ""},
    {"no name", [](Region& r) { r.name.clear(); }, "name is empty"},
    {"radius 0", [](Region& r) { r.radius_m = 0.0; }, "radius_m = 0 must be above 0"},
    {"radius NaN", [](Region& r) { r.radius_m = NAN; }, "radius_m = nan must be above 0"},
    {"radius infinite", [](Region& r) { r.radius_m = INFINITY; }, "radius_m = inf must be above 0"},
    {"centre latitude", [](Region& r) { r.center.lat_deg = 91.0; }, "center has latitude 91, outside [-90, 90]"},
    {"centre NaN", [](Region& r) { r.center.lon_deg = NAN; }, "center is not a finite latitude and longitude"},
    {"two vertices", [](Region& r) { r.radius_m = 0.0; r.polygon = {{41.0, 2.0}, {42.0, 2.0}}; },
     "polygon has 2 vertices, fewer than 3"},
    {"vertex longitude", [](Region& r) { square(r); r.radius_m = 0.0; r.polygon[2].lon_deg = 181.0; },
     "polygon vertex 3 has longitude 181, outside [-180, 180]"},
    {"vertex infinite", [](Region& r) { square(r); r.radius_m = 0.0; r.polygon[1].lat_deg = -INFINITY; },
     "polygon vertex 2 is not a finite latitude and longitude"},
    {"antimeridian", [](Region& r) { r.radius_m = 0.0; r.polygon = {{0.0, 179.0}, {0.0, -179.0}, {1.0, -179.0}}; },
     "polygon spans 358° of longitude (-179 to 179), more than 180°: a polygon may not cross the antimeridian"},
    {"repeated vertex", [](Region& r) { square(r); r.radius_m = 0.0; r.polygon.insert(r.polygon.begin() + 2, r.polygon[1]); },
     "polygon vertex 3 repeats vertex 2"},
    {"collinear", [](Region& r) { r.radius_m = 0.0; r.polygon = {{41.0, 2.0}, {41.0, 2.5}, {41.0, 3.0}}; },
     "polygon folds back on itself at vertex"},
    {"spike", [](Region& r) { square(r); r.radius_m = 0.0; r.polygon.push_back({41.5, 2.0}); r.polygon.push_back({41.5, 2.5}); r.polygon.push_back({41.5, 2.0}); },
     "polygon folds back on itself at vertex 6"},
    {"bow tie", [](Region& r) { square(r); r.radius_m = 0.0; std::swap(r.polygon[2], r.polygon[3]); },
     "polygon edges 2 (vertex 2 to 3) and 4 (vertex 4 to 1) meet: the polygon intersects itself"},
    {"touching itself", [](Region& r) { r.radius_m = 0.0; r.polygon = {{0, 0}, {0, 4}, {4, 4}, {2, 4}, {2, 2}, {4, 0}}; },
     "polygon folds back on itself at vertex 3"},
    {"vertex on a far edge", [](Region& r) { r.radius_m = 0.0; r.polygon = {{0, 0}, {0, 4}, {4, 4}, {4, 2}, {0, 2}, {-1, 0}}; },
     "polygon edges 1 (vertex 1 to 2) and 4 (vertex 4 to 5) meet"},
    {"polygon and radius", [](Region& r) { square(r); }, "radius_m = 1000 is set with a polygon"},
    {"floor at ceiling", [](Region& r) { r.floor_ft = r.ceiling_ft = 2000.0; }, "floor_ft = 2000 must be below ceiling_ft = 2000"},
    {"floor NaN", [](Region& r) { r.floor_ft = NAN; }, "floor_ft = nan must be below ceiling_ft"},
    {"horizontal 0", [](Region& r) { r.parameters.horizontal_m = 0.0; }, "horizontal_m = 0 must be above 0"},
    {"vertical NaN", [](Region& r) { r.parameters.vertical_m = NAN; }, "vertical_m = nan must be above 0"},
    {"look-ahead", [](Region& r) { r.parameters.lookahead_s = -1.0; }, "lookahead_s = -1 must be at least 0"},
    {"warning", [](Region& r) { r.parameters.warning_s = INFINITY; }, "warning_s = inf must be at least 0"},
    {"confirm", [](Region& r) { r.parameters.confirm = 0; }, "confirm = 0 must be at least 1"},
    {"clear", [](Region& r) { r.parameters.clear = -2; }, "clear = -2 must be at least 1"},
    {"zero look-ahead is fine", [](Region& r) { r.parameters.lookahead_s = 0.0; r.parameters.warning_s = 0.0; }, ""},
    {"inhibit alone", [](Region& r) { r.inhibit = true; }, ""},
    {"inhibit with a parameter", [](Region& r) { r.inhibit = true; r.parameters.clear = 3; },
     "an inhibition volume (inhibit) sets no parameters"},
};

TEST(RegionMap, ProblemNamesTheField) {
  for (const ProblemCase& c : kProblems) {
    Region r = circle("R", kLebl, 1000.0);
    c.change(r);
    const std::string problem = RegionMap::problem(r);
    if (std::string(c.message).empty()) {
      EXPECT_EQ(problem, "") << c.what;
      EXPECT_NO_THROW(RegionMap({r})) << c.what;
    } else {
      EXPECT_NE(problem.find(c.message), std::string::npos) << c.what << ": " << problem;
      EXPECT_THROW(RegionMap({r}), std::invalid_argument) << c.what;
    }
  }
}

TEST(RegionMap, FirstProblemNumbersTheRegionAndRefusesNamesUsedTwice) {
  Region bad = circle("B", kLebl, -1.0);
  EXPECT_EQ(RegionMap::first_problem({circle("A", kLebl, 1.0), bad}),
            "region 2 (\"B\"): radius_m = -1 must be above 0 (a circle; or give a polygon)");
  EXPECT_EQ(RegionMap::first_problem({circle("A", kLebl, 1.0), circle("B", kLebl, 1.0), circle("A", kLebl, 2.0)}),
            "regions 1 and 3 are both named \"A\"");
  EXPECT_EQ(RegionMap::first_problem({}), "");
  try {
    RegionMap({circle("A", kLebl, 1.0), circle("A", kLebl, 2.0)});
    ADD_FAILURE() << "a name used twice was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "regions 1 and 2 are both named \"A\"");
  }
}

}  // namespace
}  // namespace kew::region
