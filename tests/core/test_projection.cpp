// The projection against GeographicLib's own geodesics (design §4.2).
#include "kew/geo/projection.hpp"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <cmath>

namespace kew::geo {
namespace {

struct Reference {
  const char* name;
  GeodeticPosition centre;
};

// Centres across latitudes, including one near the antimeridian and one in the south.
const Reference kCentres[] = {
    {"Frankfurt", {50.0, 8.6}}, {"Singapore", {1.35, 103.99}}, {"Anchorage", {61.17, -150.0}},
    {"Fiji", {-17.75, 179.5}},   {"Quito", {-0.13, -78.36}},    {"Tromso", {69.68, 18.92}},
};

// Points at these geodesic distances (m) and azimuths (deg) from the centre.
const double kDistances[] = {0.0, 10e3, 150e3, 600e3, 1200e3, 1490e3};
const double kAzimuths[] = {0.0, 37.0, 90.0, 180.0, 233.0, 270.0, 315.0};

TEST(Projection, RoundTripsEveryPointOfTheCoverageDisk) {
  for (const Reference& ref : kCentres) {
    const Projection projection(ref.centre, 1.5e6);
    for (double s : kDistances) {
      for (double azimuth : kAzimuths) {
        GeodeticPosition p;
        GeographicLib::Geodesic::WGS84().Direct(ref.centre.lat_deg, ref.centre.lon_deg, azimuth, s, p.lat_deg,
                                                p.lon_deg);
        ProjectionError error;
        const PlanePosition plane = projection.project(p, error);
        ASSERT_EQ(error, ProjectionError::None) << ref.name << " s=" << s << " az=" << azimuth;
        const GeodeticPosition back = projection.unproject(plane.p);
        EXPECT_LT(Projection::geodesic_distance_m(p, back), 1e-6) << ref.name;
        EXPECT_GE(plane.scale, 1.0 - 1e-12);
        EXPECT_LE(plane.scale, projection.max_scale() * (1 + 1e-12));
      }
    }
  }
}

TEST(Projection, ScaleCorrectedPlaneDistancesMatchGeodesics) {
  // Two points 9.26 km (5 NM) apart anywhere in the disk: the plane distance divided
  // by the pair scale equals the geodesic distance to better than 1 m (the probe's
  // accuracy at the separation minimum), while the raw plane distance can be off by
  // almost 3 % at the edge of coverage.
  double worst_raw = 0.0;
  for (const Reference& ref : kCentres) {
    const Projection projection(ref.centre, 1.5e6);
    for (double s : kDistances) {
      for (double azimuth : kAzimuths) {
        for (double heading : {0.0, 45.0, 90.0, 160.0}) {
          GeodeticPosition a, b;
          const auto& wgs84 = GeographicLib::Geodesic::WGS84();
          wgs84.Direct(ref.centre.lat_deg, ref.centre.lon_deg, azimuth, s, a.lat_deg, a.lon_deg);
          wgs84.Direct(a.lat_deg, a.lon_deg, heading, 9260.0, b.lat_deg, b.lon_deg);
          ProjectionError ea, eb;
          const PlanePosition pa = projection.project(a, ea);
          const PlanePosition pb = projection.project(b, eb);
          if (ea != ProjectionError::None || eb != ProjectionError::None) continue;
          const double plane = geometry::norm(pb.p - pa.p);
          const double corrected = plane / Projection::pair_scale(pa.scale, pb.scale);
          EXPECT_NEAR(corrected, 9260.0, 1.0) << ref.name << " s=" << s << " az=" << azimuth;
          worst_raw = std::max(worst_raw, std::abs(plane - 9260.0));
        }
      }
    }
  }
  EXPECT_GT(worst_raw, 150.0);  // the correction is needed: > 1.6 % at 1,490 km
}

TEST(Projection, MaxScaleAtTheDefaultCoverageRadius) {
  // k ≈ 1 + x²/(2R²) + x⁴/(24R⁴) at x = 1,500 km, ≈ 1.028 (kew.toml(5) documents 2.8 %).
  const Projection projection({50.0, 8.6}, 1.5e6);
  EXPECT_NEAR(projection.max_scale(), 1.0283, 0.0003) << projection.max_scale();
}

TEST(Projection, VelocityMatchesTheDisplacementAlongTheGeodesic) {
  // An aircraft at 250 m/s on true track θ covers 250 m of geodesic in one second. The
  // plane displacement over the second centred on the point (which cancels the
  // curvature term) must equal velocity_to_plane to within 0.1 mm.
  for (const Reference& ref : kCentres) {
    const Projection projection(ref.centre, 1.5e6);
    for (double s : kDistances) {
      for (double track : {0.0, 75.0, 180.0, 300.0}) {
        GeodeticPosition a, before, after;
        const auto& wgs84 = GeographicLib::Geodesic::WGS84();
        wgs84.Direct(ref.centre.lat_deg, ref.centre.lon_deg, 60.0, s, a.lat_deg, a.lon_deg);
        wgs84.Direct(a.lat_deg, a.lon_deg, track, 125.0, after.lat_deg, after.lon_deg);
        wgs84.Direct(a.lat_deg, a.lon_deg, track, -125.0, before.lat_deg, before.lon_deg);
        ProjectionError e;
        const PlanePosition pa = projection.project(a, e);
        const geometry::Vector2 moved = projection.project(after, e).p - projection.project(before, e).p;
        const geometry::Vector2 v = projection.velocity_to_plane(pa, 250.0, track);
        EXPECT_LT(geometry::norm(moved - v), 1e-4) << ref.name << " s=" << s << " track=" << track;
        double speed = 0, back = 0;
        projection.velocity_from_plane(pa, v, speed, back);
        EXPECT_NEAR(speed, 250.0, 1e-9);
        EXPECT_NEAR(std::remainder(back - track, 360.0), 0.0, 1e-9);
      }
    }
  }
}

TEST(Projection, RefusesWhatItCannotProject) {
  const Projection projection({50.0, 8.6}, 1.5e6);
  ProjectionError e;
  projection.project({std::nan(""), 8.0}, e);
  EXPECT_EQ(e, ProjectionError::NotFinite);
  projection.project({50.0, INFINITY}, e);
  EXPECT_EQ(e, ProjectionError::NotFinite);
  projection.project({90.5, 8.0}, e);
  EXPECT_EQ(e, ProjectionError::LatitudeRange);
  projection.project({50.0, -180.5}, e);
  EXPECT_EQ(e, ProjectionError::LongitudeRange);
  // Just inside and just outside the coverage radius, due east (largest scale).
  GeodeticPosition inside, outside;
  GeographicLib::Geodesic::WGS84().Direct(50.0, 8.6, 90.0, 1.4999e6, inside.lat_deg, inside.lon_deg);
  GeographicLib::Geodesic::WGS84().Direct(50.0, 8.6, 90.0, 1.5001e6, outside.lat_deg, outside.lon_deg);
  projection.project(inside, e);
  EXPECT_EQ(e, ProjectionError::None);
  projection.project(outside, e);
  EXPECT_EQ(e, ProjectionError::OutsideCoverage);
  projection.project({-50.0, 8.6}, e);
  EXPECT_EQ(e, ProjectionError::OutsideCoverage);
  EXPECT_THROW(Projection({95.0, 0.0}, 1e6), std::invalid_argument);
  EXPECT_THROW(Projection({0.0, 0.0}, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace kew::geo
