// kew_volume: reference cases computed by hand, every degenerate case named in
// kew/volume/entry.hpp, and every refusal of Volume and Motion.
#include "kew/volume/entry.hpp"
#include "kew/volume/volume.hpp"

#include <gtest/gtest.h>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geodesic.hpp>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "volume_oracle.hpp"

namespace kew::volume {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNm = 1852.0;
constexpr double kKt360_mps = 185.2;  // 360 kt = 0.1 NM/s
const double kA = GeographicLib::Constants::WGS84_a();
const VerticalBand kAll{-2000.0, 60000.0};

const GeographicLib::Geodesic& wgs84() { return GeographicLib::Geodesic::WGS84(); }

// Longitude (deg) spanning d metres along the equator, which is a geodesic: d = a·Δλ.
double equator_deg(double d) { return d / kA * 180.0 / kPi; }

Ring box(double lat_half, double lon_west, double lon_east) {
  return {{-lat_half, lon_west}, {-lat_half, lon_east}, {lat_half, lon_east}, {lat_half, lon_west}};
}

Volume make(const Ring& outer, const std::vector<Ring>& holes = {}, VerticalBand band = kAll) {
  VolumeResult r = Volume::polygon(outer, holes, band);
  EXPECT_EQ(r.error, VolumeError::None) << kVolumeErrorNames.name(r.error);
  return *r.volume;
}

Motion flying(LatLon start, double track, double gs_kt, double alt = 10000.0, double vr = 0.0,
              std::optional<double> sel = std::nullopt) {
  return {start, alt, track, gs_kt, vr, sel};
}

// A flight at gs_kt that starts `distance_m` from `target` on the geodesic leaving it
// at `azimuth_deg`, and flies back along that geodesic: it reaches `target` after
// distance_m / speed.
Motion towards(LatLon target, double azimuth_deg, double distance_m, double gs_kt) {
  LatLon start;
  double arrival = 0.0;
  wgs84().Direct(target.lat_deg, target.lon_deg, azimuth_deg, distance_m, start.lat_deg, start.lon_deg, arrival);
  return flying(start, arrival + 180.0, gs_kt);
}

// A 10 NM square at the equator: its west and east edges are meridians 10 NM apart.
const double kHalf = equator_deg(5.0 * kNm);
const Ring kBox = box(kHalf, -kHalf, kHalf);

TEST(Volume, SquareAtTheEquatorEnteredHeadOnAtExactlyDistanceOverSpeed) {
  const Volume v = make(kBox);
  const Entry e = entry(v, flying({0.0, -1.0}, 90.0, 360.0), 700.0);
  const double expected = (kA * kPi / 180.0 - 5.0 * kNm) / kKt360_mps;  // 555.7 s
  ASSERT_TRUE(e.entry_s);
  EXPECT_NEAR(*e.entry_s, expected, 1e-6);
  ASSERT_TRUE(e.exit_s);
  EXPECT_NEAR(*e.exit_s, expected + 100.0, 1e-6);  // 10 NM at 0.1 NM/s
  EXPECT_FALSE(e.inside_now);
  EXPECT_FALSE(entry(v, flying({0.0, -1.0}, 90.0, 360.0), expected - 0.01).entry_s);
}

TEST(Volume, APathOutOfReachIsRefusedBeforeAnyGeodesicAndOneThatGrazesIsNot) {
  // A 10 km circle at the equator; paths of 30 km heading east from points 20 km west,
  // at a cross-track offset: within reach up to the radius and the slack of 1 % and
  // 200 m, refused beyond it.
  const Volume circle = *Volume::circle({0.0, 0.0}, 10e3, kAll).volume;
  const auto path_at = [](double north_m) {
    Motion m;
    m.start = {north_m / 110574.0, -equator_deg(20e3)};
    m.track_deg = 90.0;
    m.gs_kt = 360.0;
    return m;
  };
  EXPECT_TRUE(within_reach(circle, path_at(0.0), 30e3));
  EXPECT_TRUE(within_reach(circle, path_at(10e3), 30e3));    // tangent
  EXPECT_TRUE(within_reach(circle, path_at(10.5e3), 30e3));  // within the slack (600 m)
  EXPECT_FALSE(within_reach(circle, path_at(11e3), 30e3));
  EXPECT_FALSE(within_reach(circle, path_at(-50e3), 30e3));
  // Short of the circle: the path ends 15 km before its edge.
  EXPECT_FALSE(within_reach(circle, path_at(0.0), 5e3));
  // A path that ends 100 m inside the circle.
  EXPECT_TRUE(within_reach(circle, path_at(0.0), 20e3 - 9.9e3));
}

TEST(Volume, AHoleIsOutsideAndItsBoundaryInside) {
  const double hole = equator_deg(2.0 * kNm);
  const Volume v = make(kBox, {box(hole, -hole, hole)});
  const Motion m = flying({0.0, -1.0}, 90.0, 360.0);
  const double west = (kA * kPi / 180.0 - 5.0 * kNm) / kKt360_mps;
  const std::vector<Interval> h = horizontal_intervals(v, m, 700.0);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_NEAR(h[0].begin_s, west, 1e-6);
  EXPECT_NEAR(h[0].end_s, west + 30.0, 1e-6);  // 3 NM to the hole
  EXPECT_NEAR(h[1].begin_s, west + 70.0, 1e-6);
  EXPECT_NEAR(h[1].end_s, west + 100.0, 1e-6);
  // Starting in the middle of the hole, eastbound: 2 NM to its boundary.
  const Entry e = entry(v, flying({0.0, 0.0}, 90.0, 360.0), 60.0);
  ASSERT_TRUE(e.entry_s);
  EXPECT_NEAR(*e.entry_s, 20.0, 1e-6);
  EXPECT_FALSE(e.inside_now);
}

TEST(Volume, EnteredOverTheFloorWhileClimbing) {
  const Volume v = make(kBox, {}, {5000.0, 9000.0});
  const Entry e = entry(v, flying({0.0, 0.0}, 0.0, 0.0, 3000.0, 1200.0), 400.0);
  ASSERT_TRUE(e.entry_s);
  EXPECT_DOUBLE_EQ(*e.entry_s, 100.0);  // 2,000 ft at 1,200 ft/min
  ASSERT_TRUE(e.exit_s);
  EXPECT_DOUBLE_EQ(*e.exit_s, 300.0);  // through the ceiling, 6,000 ft above the start
}

TEST(Volume, LevellingOffBelowTheFloorNeverEnters) {
  const Volume v = make(kBox, {}, {5000.0, 9000.0});
  EXPECT_FALSE(entry(v, flying({0.0, 0.0}, 0.0, 0.0, 3000.0, 1200.0, 4000.0), 300.0).entry_s);
  // Levelling off above the floor: entered at the floor, and never left.
  const Entry above = entry(v, flying({0.0, 0.0}, 0.0, 0.0, 3000.0, 1200.0, 6000.0), 300.0);
  ASSERT_TRUE(above.entry_s);
  EXPECT_DOUBLE_EQ(*above.entry_s, 100.0);
  EXPECT_FALSE(above.exit_s);
  // Levelling off exactly at the floor: the floor is inside.
  const Entry at = entry(v, flying({0.0, 0.0}, 0.0, 0.0, 3000.0, 1200.0, 5000.0), 300.0);
  ASSERT_TRUE(at.entry_s);
  EXPECT_DOUBLE_EQ(*at.entry_s, 100.0);
  // A selection behind the aircraft is ignored: the descent continues through the band.
  const Entry behind = entry(v, flying({0.0, 0.0}, 0.0, 0.0, 12000.0, -1500.0, 13000.0), 300.0);
  ASSERT_TRUE(behind.entry_s);
  EXPECT_DOUBLE_EQ(*behind.entry_s, 120.0);
}

TEST(Volume, InsideNowIsAViolation) {
  const Entry e = entry(make(kBox), flying({0.0, 0.0}, 45.0, 250.0), 120.0);
  EXPECT_TRUE(e.inside_now);
  ASSERT_TRUE(e.entry_s);
  EXPECT_EQ(*e.entry_s, 0.0);
}

TEST(Volume, PolygonAcrossTheAntimeridian) {
  const Volume v = make(box(0.1, 179.9, -179.9));
  const double expected = (kA * 0.9 * kPi / 180.0) / kKt360_mps;
  const Entry eastbound = entry(v, flying({0.0, 179.0}, 90.0, 360.0), 3600.0);
  ASSERT_TRUE(eastbound.entry_s);
  EXPECT_NEAR(*eastbound.entry_s, expected, 1e-6);
  EXPECT_NEAR(*eastbound.exit_s, (kA * 1.1 * kPi / 180.0) / kKt360_mps, 1e-6);
  const Entry westbound = entry(v, flying({0.0, -179.0}, 270.0, 360.0), 3600.0);
  ASSERT_TRUE(westbound.entry_s);
  EXPECT_NEAR(*westbound.entry_s, expected, 1e-6);
  EXPECT_TRUE(v.contains_horizontally({0.05, 180.0}));
  EXPECT_TRUE(v.contains_horizontally({0.05, -180.0}));
  EXPECT_FALSE(v.contains_horizontally({0.0, 0.0}));
}

TEST(Volume, PolygonAroundThePoleCrossedOverThePole) {
  // Four vertices at 89.5°; the path follows meridian 0 through the vertex (89.5, 0),
  // over the pole, and out through the vertex (89.5, 180).
  const Volume v = make({{89.5, 0.0}, {89.5, 90.0}, {89.5, 180.0}, {89.5, -90.0}});
  EXPECT_NEAR(v.centre().lat_deg, 90.0, 1e-9);
  EXPECT_TRUE(v.contains_horizontally({90.0, 0.0}));
  double to_vertex = 0.0, to_pole = 0.0;
  wgs84().Inverse(89.0, 0.0, 89.5, 0.0, to_vertex);
  wgs84().Inverse(89.0, 0.0, 90.0, 0.0, to_pole);
  const Entry e = entry(v, flying({89.0, 0.0}, 0.0, 480.0), 900.0);
  const double speed = 480.0 * kNm / 3600.0;
  ASSERT_TRUE(e.entry_s);
  EXPECT_NEAR(*e.entry_s, to_vertex / speed, 1e-6);
  ASSERT_TRUE(e.exit_s);
  EXPECT_NEAR(*e.exit_s, (2.0 * to_pole - to_vertex) / speed, 1e-6);
}

TEST(Volume, CircleOfTwoNauticalMiles) {
  const LatLon c{45.0, 10.0};
  const Volume v = *Volume::circle(c, 2.0 * kNm, kAll).volume;
  // Start 20 NM west of the centre, flying towards it: 18 NM to the circle.
  const Motion m = towards(c, 270.0, 20.0 * kNm, 360.0);
  const Entry e = entry(v, m, 600.0);
  ASSERT_TRUE(e.entry_s);
  EXPECT_NEAR(*e.entry_s, 180.0, 1e-3);
  ASSERT_TRUE(e.exit_s);
  EXPECT_NEAR(*e.exit_s, 220.0, 1e-3);
  EXPECT_FALSE(entry(v, m, 179.9).entry_s);
}

TEST(Volume, TangentToACircleCountsAsEnteringAtTheTouch) {
  const LatLon c{-33.9, 151.2};
  const Volume v = *Volume::circle(c, 2.0 * kNm, kAll).volume;
  // The geodesic through the circle's northern point at right angles to the radius
  // touches the circle there (geodesic circles are orthogonal to the radii).
  LatLon touch;
  double radial = 0.0;
  wgs84().Direct(c.lat_deg, c.lon_deg, 0.0, 2.0 * kNm, touch.lat_deg, touch.lon_deg, radial);
  const Motion m = towards(touch, radial - 90.0, 5.0 * kNm, 360.0);
  const Entry e = entry(v, m, 120.0);
  ASSERT_TRUE(e.entry_s);
  EXPECT_NEAR(*e.entry_s, 50.0, 0.01);
  ASSERT_TRUE(e.exit_s);
  EXPECT_NEAR(*e.exit_s, *e.entry_s, 0.01);
  // 1 m farther out it is missed.
  const Volume smaller = *Volume::circle(c, 2.0 * kNm - 1.0, kAll).volume;
  EXPECT_FALSE(entry(smaller, m, 120.0).entry_s);
}

TEST(Volume, PathAlongAnEdgeIsOnTheBoundaryHenceInside) {
  const Volume v = make(kBox);
  // Northbound on the meridian of the west edge.
  const Motion m = flying({-1.0, -kHalf}, 0.0, 360.0);
  double to_corner = 0.0, to_far_corner = 0.0;
  wgs84().Inverse(-1.0, -kHalf, -kHalf, -kHalf, to_corner);
  wgs84().Inverse(-1.0, -kHalf, kHalf, -kHalf, to_far_corner);
  const Entry e = entry(v, m, 3600.0);
  ASSERT_TRUE(e.entry_s);
  EXPECT_NEAR(*e.entry_s, to_corner / kKt360_mps, 1e-6);
  ASSERT_TRUE(e.exit_s);
  EXPECT_NEAR(*e.exit_s, to_far_corner / kKt360_mps, 1e-6);
}

TEST(Volume, PathThroughAVertexAndTouchingAVertex) {
  const Volume v = make(kBox);
  const LatLon corner{-kHalf, -kHalf};
  // Into the box through its south-west corner along the diagonal.
  const Entry through = entry(v, towards(corner, 225.0, 10.0 * kNm, 360.0), 600.0);
  ASSERT_TRUE(through.entry_s);
  EXPECT_NEAR(*through.entry_s, 100.0, 1e-6);
  // Along the line through the same corner at 135°: it touches the corner only.
  const Entry touch = entry(v, towards(corner, 315.0, 10.0 * kNm, 360.0), 600.0);
  ASSERT_TRUE(touch.entry_s);
  EXPECT_NEAR(*touch.entry_s, 100.0, 1e-6);
  ASSERT_TRUE(touch.exit_s);
  EXPECT_NEAR(*touch.exit_s, 100.0, 1e-6);
}

TEST(Volume, ZeroSpeedAndZeroHorizon) {
  const Volume v = make(kBox, {}, {5000.0, 9000.0});
  const Entry still = entry(v, flying({0.0, 0.0}, 0.0, 0.0, 4000.0, 600.0), 300.0);
  ASSERT_TRUE(still.entry_s);
  EXPECT_DOUBLE_EQ(*still.entry_s, 100.0);
  EXPECT_FALSE(entry(v, flying({0.0, 1.0}, 0.0, 0.0, 6000.0), 300.0).entry_s);
  const Entry now = entry(v, flying({0.0, 0.0}, 0.0, 500.0, 6000.0), 0.0);
  EXPECT_TRUE(now.inside_now);
  EXPECT_FALSE(now.exit_s);
  EXPECT_FALSE(entry(v, flying({0.0, -1.0}, 90.0, 500.0, 6000.0), 0.0).entry_s);
}

TEST(Volume, ReferenceCasesAgreeWithTheBruteForce) {
  const Volume v = make(kBox, {box(equator_deg(2.0 * kNm), -equator_deg(2.0 * kNm), equator_deg(2.0 * kNm))});
  for (double track : {60.0, 90.0, 100.0, 135.0}) {
    const Motion m = flying({-0.05, -0.3}, track, 420.0, 8000.0, -900.0, 5000.0);
    const Entry e = entry(v, m, 300.0);
    const test::OracleResult o = test::VolumeOracle(v).run(m, 300.0);
    ASSERT_EQ(e.entry_s.has_value(), o.entry_s.has_value()) << track;
    if (e.entry_s) {
      EXPECT_NEAR(*e.entry_s, *o.entry_s, 1e-3) << track;
    }
  }
}

// Every refusal, with its name.
TEST(Volume, RefusesInvalidVolumesByName) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto polygon_error = [](const Ring& outer, const std::vector<Ring>& holes = {}, VerticalBand band = kAll) {
    return Volume::polygon(outer, holes, band).error;
  };
  EXPECT_EQ(polygon_error({{nan, 0}, {0, 1}, {1, 0}}), VolumeError::NotFinite);
  EXPECT_EQ(polygon_error({{91, 0}, {0, 1}, {1, 0}}), VolumeError::LatitudeRange);
  EXPECT_EQ(polygon_error({{0, 181}, {0, 1}, {1, 0}}), VolumeError::LongitudeRange);
  EXPECT_EQ(polygon_error({{0, 0}, {0, 1}}), VolumeError::TooFewVertices);
  EXPECT_EQ(polygon_error({{0, 0}, {0, 1}, {0, 1}, {0, 0}}), VolumeError::TooFewVertices);
  EXPECT_EQ(polygon_error({{90, 0}, {90, 50}, {89, 0}}), VolumeError::TooFewVertices);  // one pole
  EXPECT_EQ(polygon_error({{0, 0}, {0, 1}, {0, 2}}), VolumeError::ZeroArea);
  EXPECT_EQ(polygon_error({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), VolumeError::SelfIntersecting);
  EXPECT_EQ(polygon_error({{0, 0}, {0, 2}, {0, 1}, {1, 1}}), VolumeError::SelfIntersecting);  // folds back
  EXPECT_EQ(polygon_error(box(1, -1, 1), {box(0.5, 2, 3)}), VolumeError::HoleOutside);
  EXPECT_EQ(polygon_error(box(1, -1, 1), {box(0.5, 0.5, 1.5)}), VolumeError::HoleOutside);
  EXPECT_EQ(polygon_error(box(1, -1, 1), {box(0.5, -0.5, 1)}), VolumeError::HoleOutside);  // touches
  EXPECT_EQ(polygon_error(box(1, -1, 1), {box(0.5, -0.5, 0.2), box(0.5, 0.0, 0.5)}), VolumeError::HolesOverlap);
  EXPECT_EQ(polygon_error(box(1, -1, 1), {box(0.5, -0.5, 0.5), box(0.2, -0.2, 0.2)}), VolumeError::HolesOverlap);
  EXPECT_EQ(polygon_error({{0, 0}, {0, 120}, {0, -120}}), VolumeError::TooLarge);
  EXPECT_EQ(polygon_error({{0, 0}, {10, 170}, {-10, 170}, {0, 10}}), VolumeError::TooLarge);
  EXPECT_EQ(polygon_error(box(1, -1, 1), {}, {5000, 5000}), VolumeError::BandInverted);
  EXPECT_EQ(polygon_error(box(1, -1, 1), {}, {nan, 5000}), VolumeError::NotFinite);
  EXPECT_EQ(Volume::polygon(box(1, -1, 1), {box(0.5, 2, 3)}, kAll).ring, 1u);

  EXPECT_EQ(Volume::circle({0, 0}, 0.0, kAll).error, VolumeError::RadiusNotPositive);
  EXPECT_EQ(Volume::circle({0, 0}, -5.0, kAll).error, VolumeError::RadiusNotPositive);
  EXPECT_EQ(Volume::circle({0, 0}, nan, kAll).error, VolumeError::NotFinite);
  EXPECT_EQ(Volume::circle({0, 0}, 1e7, kAll).error, VolumeError::TooLarge);
  EXPECT_EQ(Volume::circle({-90.5, 0}, 1e3, kAll).error, VolumeError::LatitudeRange);
  EXPECT_EQ(Volume::circle({0, 0}, 1e3, {9000, 1000}).error, VolumeError::BandInverted);
  EXPECT_EQ(Volume::circle({0, 0}, 1e3, kAll).error, VolumeError::None);

  std::set<std::string> names;
  for (const auto& e : kVolumeErrorNames.entries()) names.insert(std::string(e.name));
  EXPECT_EQ(names.size(), kVolumeErrorNames.entries().size());
  EXPECT_EQ(kVolumeErrorNames.parse("hole_outside"), VolumeError::HoleOutside);
}

TEST(Volume, RefusesInvalidMotionsByName) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Volume v = make(kBox);
  const Motion ok = flying({0, 0}, 90, 300);
  EXPECT_EQ(validate(ok, 120.0), MotionError::None);
  Motion m = ok;
  m.vr_fpm = nan;
  EXPECT_EQ(entry(v, m, 120.0).error, MotionError::NotFinite);
  m = ok;
  m.sel_ft = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validate(m, 120.0), MotionError::NotFinite);
  EXPECT_EQ(validate(ok, nan), MotionError::NotFinite);
  m = ok;
  m.start.lat_deg = -90.01;
  EXPECT_EQ(validate(m, 120.0), MotionError::LatitudeRange);
  m = ok;
  m.start.lon_deg = 180.5;
  EXPECT_EQ(validate(m, 120.0), MotionError::LongitudeRange);
  m = ok;
  m.gs_kt = -1.0;
  EXPECT_EQ(validate(m, 120.0), MotionError::SpeedRange);
  m.gs_kt = 1000.5;
  EXPECT_EQ(validate(m, 120.0), MotionError::SpeedRange);
  EXPECT_EQ(validate(ok, -1.0), MotionError::HorizonRange);
  EXPECT_EQ(validate(ok, 3601.0), MotionError::HorizonRange);
  const Entry refused = entry(v, m, 120.0);
  EXPECT_FALSE(refused.entry_s);
  EXPECT_EQ(kMotionErrorNames.name(MotionError::SpeedRange), "speed_range");
}

}  // namespace
}  // namespace kew::volume
