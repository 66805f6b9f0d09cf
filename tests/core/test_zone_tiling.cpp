// The worldwide tiling (design §4.9): cores partition the sphere, every position within
// the margin of a core is found in that zone, planes stay small enough.
#include "kew/zone/zone_tiling.hpp"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace kew::zone {
namespace {

constexpr double kMargin_m = 100e3;

bool contains(const ZoneKeys& keys, ZoneKey key) { return std::find(keys.begin(), keys.end(), key) != keys.end(); }

TEST(ZoneTiling, ReferenceCells) {
  const ZoneTiling tiling(kMargin_m);
  // Caps, the band edges and the antimeridian: cores are half-open [south, north) and
  // [west, east), 180° is −180°, the north pole in the north cap.
  EXPECT_EQ(tiling.name(tiling.home({90.0, 0.0})), "N90");
  EXPECT_EQ(tiling.name(tiling.home({81.0, 10.0})), "N90");
  EXPECT_EQ(tiling.name(tiling.home({-90.0, 0.0})), "S90");
  EXPECT_EQ(tiling.name(tiling.home({-81.0, 10.0})), tiling.name(tiling.home({-80.0, 10.0})));
  EXPECT_NE(tiling.home({-81.0, 10.0}), tiling.home({-81.0001, 10.0}));
  EXPECT_EQ(tiling.home({50.0, 180.0}), tiling.home({50.0, -180.0}));
  EXPECT_NE(tiling.home({50.0, 179.99}), tiling.home({50.0, -179.99}));
  // 40 cells of 9° at the equator: 0° is a cell boundary, 0° latitude a band boundary.
  EXPECT_EQ(tiling.name(tiling.home({0.0, 0.0})), "N04.5E004.5");
  EXPECT_EQ(tiling.name(tiling.home({-0.01, -0.01})), "S04.5W004.5");
  EXPECT_EQ(tiling.name(tiling.home({50.0, 8.0})), "N49.5E013.3");
  for (const ZoneKey key : {tiling.home({0.0, 0.0}), tiling.home({50.0, 8.0}), tiling.home({89.0, 0.0})})
    EXPECT_EQ(tiling.home(tiling.centre(key)), key);
}

TEST(ZoneTiling, MarginAndRangeAreChecked) {
  EXPECT_THROW(ZoneTiling(0.0), std::invalid_argument);
  EXPECT_THROW(ZoneTiling(-1.0), std::invalid_argument);
  EXPECT_THROW(ZoneTiling(std::nan("")), std::invalid_argument);
  EXPECT_THROW(ZoneTiling(1.5e6), std::invalid_argument);
}

// The margin's promise, which the pipeline's completeness rests on: whatever is within
// the margin of a position has its home among the position's zones. Random positions
// everywhere, with extra weight near the poles and the antimeridian.
TEST(ZoneTiling, EveryPositionWithinTheMarginIsInAZoneOfThePosition) {
  const ZoneTiling tiling(kMargin_m);
  const auto& geodesic = GeographicLib::Geodesic::WGS84();
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ZoneKeys near;
  std::size_t most = 0;
  for (int i = 0; i < 200000; ++i) {
    double lat = std::asin(2.0 * unit(rng) - 1.0) * 180.0 / M_PI;
    double lon = 360.0 * unit(rng) - 180.0;
    if (i % 4 == 1) lat = std::copysign(80.0 + 10.0 * unit(rng), lat);  // polar
    if (i % 4 == 2) lon = std::copysign(178.0 + 2.0 * unit(rng), lon);  // antimeridian
    tiling.zones_near({lat, lon}, near);
    ASSERT_TRUE(std::is_sorted(near.begin(), near.end()));
    ASSERT_TRUE(contains(near, tiling.home({lat, lon})));
    most = std::max(most, near.size());
    double lat2 = 0.0, lon2 = 0.0;
    geodesic.Direct(lat, lon, 360.0 * unit(rng), kMargin_m * unit(rng), lat2, lon2);
    const ZoneKey other = tiling.home({lat2, lon2});
    ASSERT_TRUE(contains(near, other)) << lat << "," << lon << " → " << lat2 << "," << lon2;
    for (const ZoneKey key : near) ASSERT_TRUE(tiling.valid(key));
  }
  EXPECT_LE(most, 6u);
}

// Every position a zone holds lies within its extent, whose plane keeps k below 1.02.
TEST(ZoneTiling, ZonesHoldTheirMembersWithinTheirExtent) {
  const ZoneTiling tiling(kMargin_m);
  const auto& geodesic = GeographicLib::Geodesic::WGS84();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ZoneKeys near;
  for (int i = 0; i < 50000; ++i) {
    const double lat = std::asin(2.0 * unit(rng) - 1.0) * 180.0 / M_PI;
    const double lon = 360.0 * unit(rng) - 180.0;
    tiling.zones_near({lat, lon}, near);
    for (const ZoneKey key : near) {
      double s = 0.0;
      geodesic.Inverse(tiling.centre(key).lat_deg, tiling.centre(key).lon_deg, lat, lon, s);
      ASSERT_LE(s, tiling.extent_m(key)) << tiling.name(key);
    }
  }
  double largest_scale = 1.0;
  for (ZoneKey key = 0; key < ZoneTiling::key_end(); ++key) {
    if (!tiling.valid(key)) continue;
    const geo::Projection plane(tiling.centre(key), tiling.extent_m(key));
    largest_scale = std::max(largest_scale, plane.max_scale());
  }
  EXPECT_LT(largest_scale, 1.02);
}

TEST(ZoneTiling, MidpointIsEquidistant) {
  const auto& geodesic = GeographicLib::Geodesic::WGS84();
  const geo::GeodeticPosition a{50.0, 179.5}, b{50.2, -179.7};
  const geo::GeodeticPosition m = ZoneTiling::midpoint(a, b);
  double sa = 0.0, sb = 0.0;
  geodesic.Inverse(m.lat_deg, m.lon_deg, a.lat_deg, a.lon_deg, sa);
  geodesic.Inverse(m.lat_deg, m.lon_deg, b.lat_deg, b.lon_deg, sb);
  EXPECT_NEAR(sa, sb, 0.01 * sa);
  EXPECT_GT(std::abs(m.lon_deg), 179.0);  // across the antimeridian, not around the world
  const geo::GeodeticPosition pole = ZoneTiling::midpoint({89.0, 0.0}, {89.0, 180.0});
  EXPECT_NEAR(pole.lat_deg, 90.0, 1e-9);
  // Antipodes have no midpoint: the first position stands for it.
  const geo::GeodeticPosition none = ZoneTiling::midpoint({10.0, 20.0}, {-10.0, -160.0});
  EXPECT_EQ(none.lat_deg, 10.0);
  EXPECT_EQ(none.lon_deg, 20.0);
}

}  // namespace
}  // namespace kew::zone
