// The track table and the pipeline's handling of bad records (design §4.3, design §6.3
// "Bad input"): every kind of bad record is refused with its own counted reason and
// never reaches the triangulation.
#include "kew/pipeline/pipeline.hpp"
#include "kew/track/track_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace kew {
namespace {

constexpr double kT0 = 1714400000.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TrackReport report(const std::string& id, double t, double lat, double lon, double alt_ft = 35000.0,
                   std::optional<double> gs = 450.0, std::optional<double> trk = 90.0) {
  TrackReport r;
  r.t = t;
  r.id = id;
  r.source = "test";
  r.lat_deg = lat;
  r.lon_deg = lon;
  r.alt_ft = alt_ft;
  r.gs_kt = gs;
  r.trk_deg = trk;
  r.vr_fpm = 0.0;
  return r;
}

struct BadRecord {
  const char* reason;
  TrackReport record;
};

std::vector<BadRecord> bad_records() {
  std::vector<BadRecord> bad;
  const auto with = [](auto mutate) {
    TrackReport r = report("ABC123", kT0 + 8.0, 50.01, 8.02);
    mutate(r);
    return r;
  };
  bad.push_back({"empty_id", with([](TrackReport& r) { r.id.clear(); })});
  bad.push_back({"id_too_long", with([](TrackReport& r) { r.id = std::string(65, 'X'); })});
  bad.push_back({"time_not_finite", with([](TrackReport& r) { r.t = kNaN; })});
  bad.push_back({"time_not_finite", with([](TrackReport& r) { r.t = kInf; })});
  bad.push_back({"position_not_finite", with([](TrackReport& r) { r.lat_deg = kNaN; })});
  bad.push_back({"position_not_finite", with([](TrackReport& r) { r.lon_deg = -kInf; })});
  bad.push_back({"latitude_out_of_range", with([](TrackReport& r) { r.lat_deg = 91.0; })});
  bad.push_back({"longitude_out_of_range", with([](TrackReport& r) { r.lon_deg = 180.5; })});
  bad.push_back({"altitude_missing", with([](TrackReport& r) { r.alt_ft = kNaN; })});
  bad.push_back({"altitude_not_finite", with([](TrackReport& r) { r.alt_ft = kInf; })});
  bad.push_back({"altitude_out_of_range", with([](TrackReport& r) { r.alt_ft = 250000.0; })});
  bad.push_back({"on_ground", with([](TrackReport& r) { r.on_ground = true; })});
  bad.push_back({"outside_coverage", with([](TrackReport& r) { r.lat_deg = -40.0; })});
  bad.push_back({"too_late", with([](TrackReport& r) { r.t = kT0 - 60.0; r.id = "LATE01"; })});
  // Time going backwards and duplicates of the good track "GOOD01" (last t = kT0 + 4).
  bad.push_back({"out_of_order", with([](TrackReport& r) { r.id = "GOOD01"; r.t = kT0 + 3.0; })});
  bad.push_back({"duplicate_time", with([](TrackReport& r) { r.id = "GOOD01"; r.t = kT0 + 4.0; })});
  return bad;
}

TEST(BadRecords, AreRefusedWithTheirReasonAndNeverReachTheTriangulation) {
  PipelineConfig limited;  // worldwide zones with an explicit coverage limit
  limited.coverage_radius_m = 1.5e6;
  Pipeline pipeline(limited);
  pipeline.process(report("GOOD01", kT0, 50.0, 8.0));
  pipeline.process(report("GOOD01", kT0 + 4.0, 50.0, 8.025));
  ASSERT_EQ(pipeline.live_tracks(), 1u);
  const auto kinetic_before = pipeline.kinetic_statistics();
  const track::TrackSlot good = pipeline.tracks().find("test", "GOOD01");
  const double good_lon = pipeline.tracks()[good].lon_deg;

  std::map<std::string, std::uint64_t> expected;
  for (const BadRecord& bad : bad_records()) {
    SCOPED_TRACE(bad.reason);
    const std::uint64_t before = pipeline.rejections().count(bad.reason);
    pipeline.process(bad.record);
    EXPECT_EQ(pipeline.rejections().count(bad.reason), before + 1);
    ++expected[bad.reason];
    EXPECT_EQ(pipeline.live_tracks(), 1u);
    EXPECT_EQ(pipeline.tracks().size(), 1u);
  }
  EXPECT_EQ(pipeline.rejections().total(), bad_records().size());
  for (const auto& [reason, n] : expected) EXPECT_EQ(pipeline.rejections().count(reason), n) << reason;
  const auto& kinetic_after = pipeline.kinetic_statistics();
  EXPECT_EQ(kinetic_after.insertions, kinetic_before.insertions);
  EXPECT_EQ(kinetic_after.updates, kinetic_before.updates);
  EXPECT_EQ(pipeline.tracks()[good].lon_deg, good_lon);
  EXPECT_TRUE(pipeline.is_valid());
}

// A feed whose I062/220 held −165,100 ft/min lost those records whole, its
// tracks starved and real conflicts went unalerted. A bad optional field now costs only
// that field; the track table derives what is missing.
TEST(BadOptionalFields, CostOnlyTheFieldAndTheRecordIsAccepted) {
  struct Case {
    const char* reason;
    void (*mutate)(TrackReport&);
  };
  const Case cases[] = {
      {"speed_not_finite", [](TrackReport& r) { r.gs_kt = kNaN; }},
      {"speed_negative", [](TrackReport& r) { r.gs_kt = -5.0; }},
      {"speed_too_high", [](TrackReport& r) { r.gs_kt = 5000.0; }},
      {"track_angle_out_of_range", [](TrackReport& r) { r.trk_deg = 400.0; }},
      {"track_angle_not_finite", [](TrackReport& r) { r.trk_deg = kNaN; }},
      {"vertical_rate_too_high", [](TrackReport& r) { r.vr_fpm = -165100.0; }},
      {"vertical_rate_not_finite", [](TrackReport& r) { r.vr_fpm = kInf; }},
      {"selected_altitude_out_of_range", [](TrackReport& r) { r.sel_ft = 150000.0; }},
      {"selected_altitude_out_of_range", [](TrackReport& r) { r.sel_ft = -2025.0; }},
      {"selected_altitude_not_finite", [](TrackReport& r) { r.sel_ft = kNaN; }},
      {"track_angle_rate_too_high", [](TrackReport& r) { r.tar_dps = 30.5; }},
      {"track_angle_rate_too_high", [](TrackReport& r) { r.tar_dps = -45.0; }},
      {"track_angle_rate_not_finite", [](TrackReport& r) { r.tar_dps = -kInf; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.reason);
    Pipeline pipeline;
    // 0.025° of longitude at 50° N in 4 s: about 780 kt east, climbing 1,500 ft/min.
    pipeline.process(report("GOOD01", kT0, 50.0, 8.0, 35000.0));
    TrackReport bad = report("GOOD01", kT0 + 4.0, 50.0, 8.025, 35100.0);
    c.mutate(bad);
    pipeline.process(bad);
    EXPECT_EQ(pipeline.rejections().total(), 0u);
    EXPECT_EQ(pipeline.statistics().accepted, 2u);
    EXPECT_EQ(pipeline.dropped_fields().count(c.reason), 1u);
    EXPECT_EQ(pipeline.dropped_fields().total(), 1u);
    const track::Track& track = pipeline.tracks()[pipeline.tracks().find("test", "GOOD01")];
    EXPECT_EQ(track.lon_deg, 8.025);
    EXPECT_TRUE(std::isfinite(track.gs_kt) && std::isfinite(track.trk_deg) && std::isfinite(track.vr_fpm));
    EXPECT_LE(track.gs_kt, 1200.0);
    EXPECT_LT(std::abs(track.vr_fpm), 20000.0);
    if (std::string(c.reason).rfind("vertical", 0) == 0) {
      EXPECT_NEAR(track.vr_fpm, 1500.0, 1e-6);
    }
    EXPECT_EQ(pipeline.live_tracks(), 1u);
  }
}

TEST(BadOptionalFields, SelectedAltitudeAndTrackAngleRateInRangeAreKept) {
  // The bounds themselves are plausible: the altitude range of the track table, ±30 deg/s.
  const std::vector<std::pair<std::optional<double>, std::optional<double>>> values = {
      {-2000.0, -30.0}, {100000.0, 30.0}, {35000.0, 0.0}, {-0.0, -3.0}};
  track::TrackTable table;
  const geo::Projection projection(geo::GeodeticPosition{50.0, 8.0}, 1000e3);
  double t = kT0;
  for (const auto& [sel_ft, tar_dps] : values) {
    TrackReport r = report("GOOD01", t, 50.0, 8.0);
    r.sel_ft = sel_ft;
    r.tar_dps = tar_dps;
    EXPECT_EQ(table.admit(r, t, projection).refusal, track::Refusal::None);
    t += 4.0;
  }
  EXPECT_EQ(table.dropped_fields().total(), 0u);
  EXPECT_EQ(table.rejections().total(), 0u);
}

TEST(BadRecords, RejectionsAreReportedRateLimited) {
  Pipeline pipeline;
  std::vector<std::string> messages;
  pipeline.rejections().set_reporter(
      [&](std::string_view reason, std::string_view) { messages.emplace_back(reason); });
  for (int i = 0; i < 1000; ++i) pipeline.process(report(std::string("X").append(std::to_string(i)), kT0 + i, kNaN, 8.0));
  EXPECT_EQ(pipeline.rejections().count("position_not_finite"), 1000u);
  EXPECT_EQ(messages.size(), 10u + 6u);  // a burst of 10, then at 20, 40, 80, 160, 320, 640
}

TEST(TrackTable, SameIdFromTwoSourcesIsTwoTracks) {
  Pipeline pipeline;
  TrackReport a = report("1234", kT0, 50.0, 8.0);
  TrackReport b = a;
  b.source = "other";
  b.lat_deg = 50.5;
  pipeline.process(a);
  pipeline.process(b);
  EXPECT_EQ(pipeline.live_tracks(), 2u);
  EXPECT_NE(pipeline.tracks().find("test", "1234"), pipeline.tracks().find("other", "1234"));
}

TEST(TrackTable, DerivesVelocityFromTheLastTwoPositions) {
  Pipeline pipeline;
  // Positions only (no ground speed, track or vertical rate), 4 s apart, due east.
  TrackReport first = report("NOVEL1", kT0, 50.0, 8.0, 30000.0, std::nullopt, std::nullopt);
  first.vr_fpm.reset();
  pipeline.process(first);
  EXPECT_EQ(pipeline.live_tracks(), 0u);  // no velocity yet: not in the engine
  EXPECT_EQ(pipeline.tracks().size(), 1u);
  const double lon2 = 8.02;
  TrackReport second = report("NOVEL1", kT0 + 4.0, 50.0, lon2, 30400.0, std::nullopt, std::nullopt);
  second.vr_fpm.reset();
  pipeline.process(second);
  EXPECT_EQ(pipeline.live_tracks(), 1u);
  const track::Track& t = pipeline.tracks()[pipeline.tracks().find("test", "NOVEL1")];
  const double metres = geo::Projection::geodesic_distance_m({50.0, 8.0}, {50.0, lon2});
  EXPECT_NEAR(t.gs_kt, metres / 4.0 * 3600.0 / 1852.0, 0.01);
  EXPECT_NEAR(t.trk_deg, 90.0, 0.01);
  EXPECT_NEAR(t.vr_fpm, 400.0 / 4.0 * 60.0, 1e-6);
  EXPECT_EQ(pipeline.tracks().velocities_derived(), 1u);
}

TEST(TrackTable, AnImpossibleJumpResetsTheVelocity) {
  Pipeline pipeline;
  pipeline.process(report("JUMP01", kT0, 50.0, 8.0, 30000.0, std::nullopt, std::nullopt));
  pipeline.process(report("JUMP01", kT0 + 4.0, 50.0, 8.02, 30000.0, std::nullopt, std::nullopt));
  ASSERT_EQ(pipeline.live_tracks(), 1u);
  pipeline.process(report("JUMP01", kT0 + 8.0, 51.0, 8.02, 30000.0, std::nullopt, std::nullopt));  // 111 km in 4 s
  EXPECT_EQ(pipeline.live_tracks(), 0u);
  EXPECT_EQ(pipeline.tracks().velocity_resets(), 1u);
  pipeline.process(report("JUMP01", kT0 + 12.0, 51.0, 8.03, 30000.0, std::nullopt, std::nullopt));
  EXPECT_EQ(pipeline.live_tracks(), 1u);
}

TEST(TrackTable, SilentTracksAreDroppedAfterTheTimeout) {
  Pipeline pipeline;
  pipeline.process(report("QUIET1", kT0, 50.0, 8.0));
  pipeline.process(report("TALKER", kT0, 50.3, 8.0));
  for (int i = 1; i <= 7; ++i) pipeline.process(report("TALKER", kT0 + 4.0 * i, 50.3, 8.0 + 0.02 * i));
  EXPECT_EQ(pipeline.live_tracks(), 2u);  // QUIET1 silent for 28 s
  pipeline.process(report("TALKER", kT0 + 32.0, 50.3, 8.16));
  EXPECT_EQ(pipeline.live_tracks(), 1u);  // 32 s > 30 s
  EXPECT_EQ(pipeline.tracks().find("test", "QUIET1"), track::kNoTrack);
  EXPECT_EQ(pipeline.statistics().tracks_dropped, 1u);
  pipeline.advance_to(kT0 + 63.0);
  EXPECT_EQ(pipeline.live_tracks(), 0u);
  EXPECT_TRUE(pipeline.is_valid());
}

TEST(TrackTable, OnGroundTargetsMayBeIncluded) {
  PipelineConfig config;
  config.tracks.exclude_on_ground = false;
  Pipeline pipeline(config);
  TrackReport r = report("TAXI01", kT0, 50.0, 8.0, 300.0, 15.0, 45.0);
  r.on_ground = true;
  pipeline.process(r);
  EXPECT_EQ(pipeline.live_tracks(), 1u);
}

TEST(TrackTable, LateRecordsWithinTheLimitAreExtrapolatedToTheClock) {
  Pipeline pipeline;
  pipeline.process(report("AAA001", kT0 + 10.0, 50.0, 8.0));
  pipeline.process(report("BBB002", kT0 + 5.0, 50.2, 8.0));  // 5 s late: accepted
  EXPECT_EQ(pipeline.live_tracks(), 2u);
  EXPECT_EQ(pipeline.now(), kT0 + 10.0);
  const track::TrackSlot slot = pipeline.tracks().find("test", "BBB002");
  const zone::Zone& home = *pipeline.home_zone(slot);
  const geometry::Point2 at_clock = home.engine().position_now(home.point_of(slot));
  const probe::Kinematics k = pipeline.tracks()[pipeline.tracks().find("test", "BBB002")].at(kT0 + 10.0);
  EXPECT_LT(geometry::norm(at_clock - k.position), 1e-6);
}

TEST(TrackTable, TheTrackLimitIsEnforced) {
  PipelineConfig config;
  config.tracks.max_tracks = 3;
  Pipeline pipeline(config);
  for (int i = 0; i < 5; ++i) pipeline.process(report("LIM" + std::to_string(i), kT0, 50.0 + 0.1 * i, 8.0));
  EXPECT_EQ(pipeline.live_tracks(), 3u);
  EXPECT_EQ(pipeline.rejections().count("track_limit"), 2u);
}

}  // namespace
}  // namespace kew
