// Zones (design §4.9): on traffic that straddles zone boundaries, the antimeridian and a
// pole, the zoned exact search gives exactly the events of the brute force over the
// whole sphere (every pair within reach judged in its owner's plane, whatever the zones'
// memberships), event for event.
#include "kew/pipeline/pipeline.hpp"
#include "kew/replay/traffic_generator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

namespace kew {
namespace {

// Zones in parallel (design §3.3): the same records give the same events, byte for byte,
// whatever the number of threads, the size of a batch, and the records judged one by one
// after each flush of a live daemon's reads.
struct Batching {
  std::size_t threads = 1, batch = 1;
  std::size_t prompt = 0;  // PipelineConfig::prompt_records
  std::size_t read = 0;    // a flush() after every this many records (0: none)
};

std::vector<std::string> events_with(const std::vector<TrackReport>& records, Batching b) {
  PipelineConfig config;
  config.threads = b.threads;
  config.batch_records = b.batch;
  config.prompt_records = b.prompt;
  config.renumber_every_s = 20.0;
  Pipeline pipeline(config);
  std::vector<std::string> out;
  pipeline.set_alert_sink([&](const AlertEvent& e) {
    out.push_back(std::to_string(e.seq) + " " + e.id + " " + std::to_string(static_cast<int>(e.state)) + " " +
                  std::to_string(e.t) + " " + std::to_string(e.t_los_s) + " " + std::to_string(e.cpa_h_m) + " " +
                  std::to_string(e.sep_h_m) + " " + e.a.id + " " + e.b.id + " " + std::to_string(e.a.lat_deg));
  });
  for (std::size_t i = 0; i < records.size(); ++i) {
    pipeline.process(records[i]);
    if (b.read > 0 && (i + 1) % b.read == 0) pipeline.flush();
  }
  pipeline.end_of_input();
  pipeline.drop_all();
  // The engines' figures, which ?STATS and --stats-json report, are the batching's too.
  const kinetic::KineticStatistics k = pipeline.kinetic_statistics();
  out.push_back("queue_mean " + std::to_string(k.queue_mean()) + ", events " + std::to_string(k.events_executed) +
                ", solved " + std::to_string(k.certificates_solved) + ", updates " + std::to_string(k.updates) +
                ", reinsertions " + std::to_string(k.reinsertions));
  return out;
}

TEST(ZonesInParallel, ThreadsAndBatchesChangeNoByte) {
  // Two regions far apart (Europe, the North Pacific across the antimeridian), so that
  // many zones work in each batch.
  std::vector<TrackReport> records;
  for (const auto& [lat, lon] : {std::pair{50.0, 8.0}, std::pair{52.0, 180.0}}) {
    replay::GeneratorConfig traffic;
    traffic.scenario = replay::Scenario::Mixed;
    traffic.aircraft = 1500;
    traffic.duration_s = 60.0;
    traffic.seed = static_cast<std::uint64_t>(lon) + 3;
    traffic.center_lat_deg = lat;
    traffic.center_lon_deg = lon;
    traffic.radius_km = 900.0;
    replay::TrafficGenerator generator(traffic);
    for (TrackReport r; generator.next(r);) {
      r.id += lon > 100.0 ? "P" : "E";
      records.push_back(r);
    }
  }
  std::stable_sort(records.begin(), records.end(), [](const TrackReport& a, const TrackReport& b) { return a.t < b.t; });
  const std::vector<std::string> serial = events_with(records, {});
  ASSERT_GE(serial.size(), 20u) << "the traffic must alert";
  for (const Batching b : {Batching{1, 700}, Batching{2, 1}, Batching{2, 64}, Batching{4, 5000}, Batching{2, 5000, 7, 30}}) {
    SCOPED_TRACE("threads " + std::to_string(b.threads) + ", batch " + std::to_string(b.batch) + ", prompt " +
                 std::to_string(b.prompt) + ", read " + std::to_string(b.read));
    EXPECT_EQ(events_with(records, b), serial);
  }
}

}  // namespace
}  // namespace kew
