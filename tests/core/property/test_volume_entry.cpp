// kew_volume's entry() against the brute force of tests/core/volume_oracle.hpp on random
// volumes and motions (fixed seed): random star-shaped polygons (convex and not, some with
// a hole) and circles of 0.5–50 NM, anywhere including across the antimeridian and within
// 1° of both poles, random bands; straight tracks at 0–600 kt with random vertical rates,
// with and without a level-off. The entry times agree within 0.1 s, and neither finds an
// entry the other misses, except at a tangency: a disagreement is accepted only when the
// inside stretch in question lasts less than kGraze_s (the brute force steps 0.01 s).
// A tenth of the tracks are built degenerate: aimed at a vertex, laid along an edge,
// tangent to a circle. KEW_VOLUME_CASES sets the number of cases (10,000),
// KEW_VOLUME_VERBOSE=1 prints every graze and every difference above 1 ms.
#include "kew/volume/entry.hpp"
#include "kew/volume/volume.hpp"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "../volume_oracle.hpp"

namespace kew::volume {
namespace {

constexpr double kNm = 1852.0;
constexpr double kTolerance_s = 0.1;
constexpr double kGraze_s = 0.05;
const int kCases = std::getenv("KEW_VOLUME_CASES") ? std::atoi(std::getenv("KEW_VOLUME_CASES")) : 10000;

struct Generator {
  std::mt19937_64 rng{20240611};
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  std::size_t index(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); }

  LatLon somewhere() {
    const double kind = uniform(0.0, 1.0);
    if (kind < 0.25) return {uniform(-60.0, 60.0), chance(0.5) ? uniform(179.0, 180.0) : uniform(-180.0, -179.0)};
    if (kind < 0.40) return {uniform(89.0, 90.0), uniform(-180.0, 180.0)};
    if (kind < 0.55) return {uniform(-90.0, -89.0), uniform(-180.0, 180.0)};
    return {uniform(-75.0, 75.0), uniform(-180.0, 180.0)};
  }

  static LatLon from(LatLon p, double azimuth, double distance_m) {
    LatLon out;
    GeographicLib::Geodesic::WGS84().Direct(p.lat_deg, p.lon_deg, azimuth, distance_m, out.lat_deg, out.lon_deg);
    return out;
  }

  // A star-shaped ring around `c`: n vertices at sorted angles, radii in [min, 1]·r.
  Ring star(LatLon c, double radius_m, int n, double min_fraction) {
    Ring ring;
    const double offset = uniform(0.0, 360.0);
    for (int i = 0; i < n; ++i) {
      const double angle = offset + (i + uniform(-0.35, 0.35)) * 360.0 / n;
      ring.push_back(from(c, angle, radius_m * uniform(min_fraction, 1.0)));
    }
    return ring;
  }

  VerticalBand band() {
    if (chance(0.3)) return {-2000.0, 60000.0};
    const double floor = uniform(0.0, 30000.0);
    return {floor, floor + uniform(500.0, 20000.0)};
  }

  Volume volume(LatLon c, double radius_m, int& kind) {
    kind = static_cast<int>(uniform(0.0, 3.0));
    for (;;) {
      const VerticalBand b = band();
      if (kind == 0) return *Volume::circle(c, radius_m, b).volume;
      const int n = kind == 1 ? static_cast<int>(uniform(3.0, 13.0)) : static_cast<int>(uniform(6.0, 25.0));
      const double min_fraction = kind == 1 ? 1.0 : 0.3;
      std::vector<Ring> holes;
      if (kind == 2 && chance(0.4)) holes.push_back(star(c, 0.18 * radius_m, static_cast<int>(uniform(3, 9)), 0.5));
      VolumeResult r = Volume::polygon(star(c, radius_m, n, min_fraction), holes, b);
      if (r.volume) return *r.volume;
    }
  }

  // `constructed`: 0 a random track, 1 aimed at a vertex, 2 along an edge, 3 tangent to a circle.
  Motion motion(const Volume& v, double horizon_s, int& constructed) {
    constructed = 0;
    Motion m;
    m.gs_kt = chance(0.05) ? 0.0 : uniform(0.0, 600.0);
    const double reach = v.extent_m() + m.gs_kt * kNm / 3600.0 * horizon_s;
    // Mostly outside, a few inside (a violation now).
    const double distance = chance(0.15) ? uniform(0.0, reach) : uniform(0.8 * v.extent_m(), 1.1 * reach);
    m.start = from(v.centre(), uniform(0.0, 360.0), distance);
    // Mostly towards the volume, give or take, sometimes anywhere.
    double towards = 0.0, s12 = 0.0, back = 0.0;
    GeographicLib::Geodesic::WGS84().Inverse(m.start.lat_deg, m.start.lon_deg, v.centre().lat_deg,
                                             v.centre().lon_deg, s12, towards, back);
    m.track_deg = chance(0.7) ? towards + uniform(-40.0, 40.0) : uniform(0.0, 360.0);
    const double special = uniform(0.0, 1.0);
    const auto& g = GeographicLib::Geodesic::WGS84();
    if (!v.is_circle() && special < 0.1) {  // straight at a vertex
      constructed = 1;
      const LatLon aim = v.rings()[0][index(v.rings()[0].size())];
      g.Inverse(m.start.lat_deg, m.start.lon_deg, aim.lat_deg, aim.lon_deg, s12, m.track_deg, back);
    } else if (!v.is_circle() && special < 0.2) {  // along an edge, from before its first vertex
      constructed = 2;
      const Ring& ring = v.rings()[0];
      const std::size_t i = index(ring.size());
      const LatLon a = ring[i], b = ring[(i + 1) % ring.size()];
      double azimuth = 0.0;
      g.Inverse(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, s12, azimuth, back);
      g.Direct(a.lat_deg, a.lon_deg, azimuth + 180.0, uniform(0.0, 0.5) * reach, m.start.lat_deg, m.start.lon_deg,
               back);
      m.track_deg = back + 180.0;
    } else if (v.is_circle() && special < 0.15) {  // a tangent: at right angles to a radius
      constructed = 3;
      LatLon touch;
      double radial = 0.0;
      g.Direct(v.centre().lat_deg, v.centre().lon_deg, uniform(0.0, 360.0), v.extent_m(), touch.lat_deg,
               touch.lon_deg, radial);
      g.Direct(touch.lat_deg, touch.lon_deg, radial + 90.0, uniform(0.0, 0.5) * reach, m.start.lat_deg,
               m.start.lon_deg, back);
      m.track_deg = back + 180.0;
    }
    const VerticalBand b = v.band();
    m.alt_ft = uniform(std::max(-2000.0, b.floor_ft - 6000.0), std::min(60000.0, b.ceiling_ft + 6000.0));
    m.vr_fpm = chance(0.2) ? 0.0 : uniform(-4000.0, 4000.0);
    if (chance(0.5)) m.sel_ft = m.alt_ft + uniform(-6000.0, 6000.0);
    return m;
  }
};

// Length (s) of the inside stretch of `intervals` ∩ vertical that starts at t.
double stretch(const Volume& v, const Motion& m, double horizon_s, double t) {
  const auto vertical = vertical_interval(m, v.band(), horizon_s);
  if (!vertical) return 0.0;
  for (const Interval& h : horizontal_intervals(v, m, horizon_s)) {
    const double begin = std::max(h.begin_s, vertical->begin_s), end = std::min(h.end_s, vertical->end_s);
    if (begin <= end && std::abs(begin - t) < 1e-6) return end - begin;
  }
  return 0.0;
}

TEST(VolumeEntryProperty, EntryEqualsBruteForceOnRandomVolumesAndTracks) {
  Generator g;
  int entries = 0, violations = 0, kinds[3] = {0, 0, 0}, built[4] = {0, 0, 0, 0};
  int grazes[2] = {0, 0};                                    // random tracks, constructed ones
  double worst[2] = {0.0, 0.0}, worst_exit[2] = {0.0, 0.0};  // the same
  for (int i = 0; i < kCases; ++i) {
    const LatLon c = g.somewhere();
    const double radius_m = g.uniform(0.5, 50.0) * kNm;
    int kind = 0;
    const Volume v = g.volume(c, radius_m, kind);
    ++kinds[kind];
    const double horizon_s = g.chance(0.5) ? 120.0 : g.uniform(0.0, 600.0);
    int constructed = 0;
    const Motion m = g.motion(v, horizon_s, constructed);
    ++built[constructed];
    const Entry e = entry(v, m, horizon_s);
    ASSERT_EQ(e.error, MotionError::None);
    const test::OracleResult o = test::VolumeOracle(v).run(m, horizon_s);
    const auto where = [&] {
      char text[400];
      std::snprintf(text, sizeof text,
                    "case %d kind %d centre (%.9f, %.9f) r %.1f m start (%.9f, %.9f) trk %.6f gs %.3f alt %.1f "
                    "vr %.1f sel %s T %.3f entry %s oracle %s",
                    i, kind, v.centre().lat_deg, v.centre().lon_deg, v.extent_m(), m.start.lat_deg,
                    m.start.lon_deg, m.track_deg, m.gs_kt, m.alt_ft, m.vr_fpm,
                    m.sel_ft ? std::to_string(*m.sel_ft).c_str() : "-", horizon_s,
                    e.entry_s ? std::to_string(*e.entry_s).c_str() : "-",
                    o.entry_s ? std::to_string(*o.entry_s).c_str() : "-");
      return std::string(text);
    };
    if (e.entry_s && o.entry_s && std::abs(*e.entry_s - *o.entry_s) <= kTolerance_s) {
      worst[constructed > 0] = std::max(worst[constructed > 0], std::abs(*e.entry_s - *o.entry_s));
      if (std::getenv("KEW_VOLUME_VERBOSE") && std::abs(*e.entry_s - *o.entry_s) > 1e-3)
        std::printf("differs %s\n", where().c_str());
      ++entries;
      violations += o.inside_now;
      EXPECT_EQ(e.inside_now, o.inside_now) << where();
      if (e.exit_s && o.exit_s && stretch(v, m, horizon_s, *e.entry_s) > 1.0) {
        worst_exit[constructed > 0] = std::max(worst_exit[constructed > 0], std::abs(*e.exit_s - *o.exit_s));
        EXPECT_NEAR(*e.exit_s, *o.exit_s, kTolerance_s) << where();
      }
      continue;
    }
    if (!e.entry_s && !o.entry_s) continue;
    // A disagreement: accepted only at a graze, which entry() finds and a 0.01 s step may not.
    const bool graze_found = e.entry_s && stretch(v, m, horizon_s, *e.entry_s) < kGraze_s;
    const bool graze_missed = o.entry_s && o.exit_s && *o.exit_s - *o.entry_s < kGraze_s;
    if (graze_found || graze_missed) {
      if (std::getenv("KEW_VOLUME_VERBOSE")) std::printf("graze %d %d %s\n", graze_found, graze_missed, where().c_str());
      ++grazes[constructed > 0];
      continue;
    }
    ADD_FAILURE() << where();
  }
  std::printf("[ volume   ] %d cases (%d circles, %d convex, %d star-shaped; %d random tracks, %d at a vertex, "
              "%d along an edge, %d tangent), %d entries (%d inside now)\n",
              kCases, kinds[0], kinds[1], kinds[2], built[0], built[1], built[2], built[3], entries, violations);
  std::printf("[ volume   ] random tracks: %d grazes, largest |entry - brute force| %.3g s, |exit - brute force| "
              "%.3g s; constructed: %d grazes, %.3g s, %.3g s\n",
              grazes[0], worst[0], worst_exit[0], grazes[1], worst[1], worst_exit[1]);
  EXPECT_GT(entries, kCases / 5);
  EXPECT_LT(grazes[0], kCases / 100);
  // On random tracks the refinement makes crossings exact, far inside the 0.1 s required
  // (measured: µs). Constructed ones differ by up to kBoundaryTolerance_m / (v·sin θ), θ the
  // angle between the path and the edge it touches within the tolerance.
  EXPECT_LT(worst[0], 1e-3);
}

}  // namespace
}  // namespace kew::volume
