// Zones (design §4.9): on traffic that straddles zone boundaries, the antimeridian and a
// pole, the zoned exact search gives exactly the events of the brute force over the
// whole sphere (every pair within reach judged in its owner's plane, whatever the zones'
// memberships), event for event.
#include "kew/pipeline/pipeline.hpp"
#include "kew/replay/traffic_generator.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace kew {
namespace {

struct ZonedRun {
  std::vector<AlertEvent> events;
  std::uint64_t candidates = 0;
  std::uint64_t zones_created = 0;
  std::size_t most_zones = 0;
  std::size_t audit_violations = 0;
};

ZonedRun run(const replay::GeneratorConfig& traffic, probe::ProbeMode mode) {
  PipelineConfig config;
  config.probe_mode = mode;
  Pipeline pipeline(config);
  ZonedRun out;
  pipeline.set_alert_sink([&](const AlertEvent& e) { out.events.push_back(e); });
  replay::TrafficGenerator generator(traffic);
  double next_audit = traffic.start_time + 30.0;
  for (TrackReport r; generator.next(r);) {
    pipeline.process(r);
    out.most_zones = std::max(out.most_zones, pipeline.zone_count());
    if (pipeline.now() >= next_audit) {
      out.audit_violations += pipeline.audit().violations_found;
      next_audit += 30.0;
    }
  }
  EXPECT_TRUE(pipeline.is_valid());
  pipeline.drop_all();
  out.candidates = pipeline.statistics().candidates;
  out.zones_created = pipeline.statistics().zones_created;
  return out;
}

struct Place {
  const char* name;
  double lat_deg, lon_deg, radius_km;
};

class ZoneEquivalence : public ::testing::TestWithParam<Place> {};

TEST_P(ZoneEquivalence, ExactEqualsBruteOverTheSphere) {
  const Place place = GetParam();
  replay::GeneratorConfig traffic;
  traffic.scenario = replay::Scenario::Mixed;
  traffic.aircraft = 800;
  traffic.duration_s = 80.0;
  traffic.seed = 20261203;
  traffic.missed_update_probability = 0.05;
  traffic.center_lat_deg = place.lat_deg;
  traffic.center_lon_deg = place.lon_deg;
  traffic.radius_km = place.radius_km;
  const ZonedRun exact = run(traffic, probe::ProbeMode::Exact);
  const ZonedRun brute = run(traffic, probe::ProbeMode::Brute);
  ASSERT_EQ(exact.events.size(), brute.events.size());
  std::size_t opened = 0;
  for (std::size_t i = 0; i < exact.events.size(); ++i) {
    SCOPED_TRACE("event " + std::to_string(i));
    const AlertEvent& x = exact.events[i];
    const AlertEvent& y = brute.events[i];
    ASSERT_EQ(x.id, y.id);
    ASSERT_EQ(x.seq, y.seq);
    ASSERT_EQ(x.state, y.state);
    ASSERT_EQ(x.t, y.t);
    ASSERT_EQ(x.severity, y.severity);
    ASSERT_EQ(x.t_los_s, y.t_los_s);
    ASSERT_EQ(x.cpa_h_m, y.cpa_h_m);
    ASSERT_EQ(x.sep_h_m, y.sep_h_m);
    opened += x.state == AlertState::New;
  }
  EXPECT_GE(opened, 5u) << "the scenario must exercise the probe";
  EXPECT_GE(exact.most_zones, 2u) << "the traffic must straddle zones";
  EXPECT_EQ(exact.audit_violations, 0u);
  EXPECT_LT(exact.candidates * 4, brute.candidates);
  RecordProperty("alerts_opened", static_cast<int>(opened));
  RecordProperty("zones", static_cast<int>(exact.most_zones));
}

INSTANTIATE_TEST_SUITE_P(Places, ZoneEquivalence,
                         ::testing::Values(Place{"Antimeridian", 52.0, 180.0, 300.0},
                                           Place{"NorthPole", 80.0, 30.0, 1300.0},
                                           Place{"FourZoneCorner", 0.0, 0.0, 300.0}),
                         [](const ::testing::TestParamInfo<Place>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace kew
