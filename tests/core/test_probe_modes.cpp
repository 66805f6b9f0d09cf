// The thesis' edge-only probe misses conflicts hidden by a third aircraft at another
// level (design §2.1); the exact probe and brute force find them.
#include "kew/pipeline/pipeline.hpp"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <vector>

namespace kew {
namespace {

constexpr double kT0 = 1714400000.0;

TrackReport at(const std::string& id, double t, double lat, double lon, double alt_ft, double gs_kt,
               double trk_deg) {
  TrackReport r;
  r.t = t;
  r.id = id;
  r.source = "stack";
  r.lat_deg = lat;
  r.lon_deg = lon;
  r.alt_ft = alt_ft;
  r.gs_kt = gs_kt;
  r.trk_deg = trk_deg;
  r.vr_fpm = 0.0;
  return r;
}

// A and B at FL350 converge head-on, 16 km apart; between them, near the middle of the
// segment AB, aircraft at FL330 (300 m north of it), FL370 (300 m south) and FL390 (on
// it) fly the same track as A. Every circle through A and B contains one of them, so AB
// is not a Delaunay edge; a ring of distant traffic makes the triangulation
// two-dimensional.
std::vector<AlertEvent> run(probe::ProbeMode mode) {
  PipelineConfig config;
  config.probe_mode = mode;
  Pipeline pipeline(config);
  std::vector<AlertEvent> events;
  pipeline.set_alert_sink([&](const AlertEvent& e) { events.push_back(e); });
  const auto& wgs84 = GeographicLib::Geodesic::WGS84();
  for (int period = 0; period < 4; ++period) {
    const double t = kT0 + 4.0 * period;
    const double advance = 4.0 * period * 200.0;  // metres flown at 200 m/s ≈ 388.8 kt
    const double gs = 200.0 * 3600.0 / 1852.0;
    const auto place = [&](double east_m, double* lat, double* lon, double north_m = 0.0) {
      double on_lat, on_lon;
      wgs84.Direct(50.0, 8.0, 90.0, east_m, on_lat, on_lon);
      wgs84.Direct(on_lat, on_lon, 0.0, north_m, *lat, *lon);
    };
    double lat, lon;
    const double middle[3][2] = {{33000.0, 300.0}, {37000.0, -300.0}, {39000.0, 0.0}};
    for (int m = 0; m < 3; ++m) {
      place(-200.0 + 200.0 * m + advance, &lat, &lon, middle[m][1]);
      pipeline.process(at(std::string("M") + std::to_string(m), t, lat, lon, middle[m][0], gs, 90.0));
    }
    for (int k = 0; k < 8; ++k) {
      double rlat, rlon;
      wgs84.Direct(50.0, 8.0, 45.0 * k + 10.0, 120000.0 + 128.6 * 4.0 * period, rlat, rlon);
      pipeline.process(at(std::string("R") + std::to_string(k), t, rlat, rlon, 20000.0, 250.0, 45.0 * k));
    }
    // A and B come last in each period, so the aircraft between them are already there.
    place(-8000.0 + advance, &lat, &lon);
    pipeline.process(at("A", t, lat, lon, 35000, gs, 90.0));
    place(8000.0 - advance, &lat, &lon);
    pipeline.process(at("B", t, lat, lon, 35000, gs, 270.0));
  }
  EXPECT_TRUE(pipeline.is_valid());
  return events;
}

bool has_alert_between(const std::vector<AlertEvent>& events, const std::string& x, const std::string& y) {
  for (const AlertEvent& e : events)
    if (e.state == AlertState::New && ((e.a.id == x && e.b.id == y) || (e.a.id == y && e.b.id == x))) return true;
  return false;
}

TEST(ProbeModes, EdgesMissesAStackedConflictThatExactAndBruteFind) {
  const std::vector<AlertEvent> exact = run(probe::ProbeMode::Exact);
  const std::vector<AlertEvent> brute = run(probe::ProbeMode::Brute);
  const std::vector<AlertEvent> edges = run(probe::ProbeMode::Edges);
  EXPECT_TRUE(has_alert_between(exact, "A", "B"));
  EXPECT_TRUE(has_alert_between(brute, "A", "B"));
  EXPECT_FALSE(has_alert_between(edges, "A", "B"));
  ASSERT_EQ(exact.size(), brute.size());
  for (std::size_t i = 0; i < exact.size(); ++i) {
    EXPECT_EQ(exact[i].id, brute[i].id);
    EXPECT_EQ(exact[i].seq, brute[i].seq);
  }
  // The alert is a loss of separation within the look-ahead: 16 km closing at 400 m/s.
  for (const AlertEvent& e : exact) {
    if (e.a.id != "A" || e.state != AlertState::New) continue;
    EXPECT_EQ(e.b.id, "B");
    EXPECT_EQ(e.severity, Severity::Warning);
    EXPECT_NEAR(e.cpa_h_m, 0.0, 50.0);
    EXPECT_NEAR(e.sep_v_ft, 0.0, 1e-9);
  }
}

}  // namespace
}  // namespace kew
