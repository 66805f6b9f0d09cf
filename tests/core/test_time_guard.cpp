// Time and place you can trust (design §4.1–4.2): one record dated in the
// future never moves the data clock, a real jump of the data (a gap in a recording) loses
// nothing, and a stray first record does not fix the clock or the projection for good.
#include "kew/pipeline/pipeline.hpp"
#include "kew/track/time_guard.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace kew {
namespace {

constexpr double kT0 = 1714400000.0;
constexpr double kKnot = 1852.0 / 3600.0;

// Two aircraft head-on along 50° N at FL350, 20 NM apart at kT0 + start, closing at
// 900 kt: separation is lost 60 s later.
TrackReport head_on(const std::string& id, double t, double start) {
  const double metres_per_degree = 111320.0 * std::cos(50.0 * M_PI / 180.0);
  const double sign = id == "A" ? 1.0 : -1.0;
  const double east_m = -sign * 10.0 * 1852.0 + sign * 450.0 * kKnot * (t - kT0 - start);
  TrackReport r;
  r.t = t;
  r.id = id;
  r.source = "test";
  r.lat_deg = 50.0;
  r.lon_deg = 8.0 + east_m / metres_per_degree;
  r.alt_ft = 35000.0;
  r.gs_kt = 450.0;
  r.trk_deg = sign > 0 ? 90.0 : 270.0;
  r.vr_fpm = 0.0;
  return r;
}

struct Feed {
  Pipeline pipeline;
  std::size_t opened = 0;
  explicit Feed(const PipelineConfig& config = {}) : pipeline(config) {
    pipeline.set_alert_sink([this](const AlertEvent& e) { opened += e.state == AlertState::New; });
  }
  // A first record at −45°, 170°, then the head-on pair over Europe for 80 s.
  void fly_after_a_stray_first_position() {
    TrackReport stray = head_on("C", kT0, 0.0);
    stray.lat_deg = -45.0;
    stray.lon_deg = 170.0;
    pipeline.process(stray);
    fly(0.0, 80.0, 0.0);
  }
  // Both aircraft every 4 s over [from, to), the pair first 20 NM apart at `start`.
  void fly(double from, double to, double start) {
    for (double dt = from; dt < to; dt += 4.0) {
      pipeline.process(head_on("A", kT0 + dt, start));
      pipeline.process(head_on("B", kT0 + dt, start));
    }
  }
};

TEST(TimeGuard, OneFutureRecordNeverBlindsThePipeline) {
  // The reliability finding: one record dated 2099 (or a flipped bit of an ASTERIX time
  // of day, an hour ahead) moved the clock; every track timed out and every later record
  // was too late, so the conflict below never alerted.
  for (const double future : {4070908800.0, kT0 + 3600.0, kT0 + 40.0}) {
    SCOPED_TRACE(future);
    Feed run;
    run.fly(0.0, 20.0, 0.0);
    TrackReport misdated = head_on("C", kT0 + 16.0, 0.0);
    misdated.t = future;
    run.pipeline.process(misdated);
    run.fly(20.0, 80.0, 0.0);
    EXPECT_EQ(run.opened, 1u);
    EXPECT_EQ(run.pipeline.rejections().count("future_time"), 1u);
    EXPECT_EQ(run.pipeline.rejections().count("too_late"), 0u);
    EXPECT_LT(run.pipeline.now(), kT0 + 80.0);
    EXPECT_EQ(run.pipeline.statistics().accepted, 40u);
  }
}

TEST(TimeGuard, ARealJumpOfTheDataLosesNothing) {
  // A recording with a 10-minute gap: the first records after it are held until two more
  // confirm the jump, then applied in order; the conflict after the gap alerts (as the
  // one before it did, which ended when its tracks timed out in the gap).
  Feed run;
  run.fly(0.0, 12.0, 0.0);  // the second look once both were seen twice (first_records)
  EXPECT_EQ(run.opened, 1u);
  run.fly(600.0, 680.0, 600.0);
  EXPECT_EQ(run.opened, 2u);
  EXPECT_EQ(run.pipeline.rejections().total(), 0u);
  EXPECT_EQ(run.pipeline.statistics().accepted, 6u + 40u);
}

TEST(TimeGuard, HeldRecordsAreAppliedOnceTheClockReachesThemOrTheInputEnds) {
  Feed run;
  run.fly(0.0, 8.0, 0.0);
  // 12 s ahead of a clock at kT0 + 4: held. The next records (kT0 + 8) are not too late
  // for it (they do not contradict it) and bring the clock within reach: applied.
  run.pipeline.process(head_on("C", kT0 + 16.0, 0.0));
  EXPECT_EQ(run.pipeline.statistics().accepted, 4u);
  run.fly(8.0, 12.0, 0.0);
  EXPECT_EQ(run.pipeline.statistics().accepted, 7u);
  // At the end of the input a held record that nothing contradicted is applied.
  run.pipeline.process(head_on("D", kT0 + 100.0, 0.0));
  EXPECT_EQ(run.pipeline.statistics().accepted, 7u);
  run.pipeline.end_of_input();
  EXPECT_EQ(run.pipeline.statistics().accepted, 8u);
  EXPECT_EQ(run.pipeline.rejections().total(), 0u);
}

// The configurations where a position can be outside coverage: one plane (whose
// centre the first record fixes), and the worldwide zones with an explicit limit
// around the first record.
std::vector<PipelineConfig> limited_coverage() {
  PipelineConfig single;
  single.zone_mode = ZoneMode::Single;
  PipelineConfig limited;
  limited.coverage_radius_m = 1.5e6;
  return {single, limited};
}

TEST(RunStart, AStrayFirstPositionDoesNotFixTheProjection) {
  // The reliability finding: with no reference configured, a first record at −45°, 170°
  // made every later record of a European feed outside_coverage. Five refused in a row
  // restart the young run from them.
  for (const PipelineConfig& config : limited_coverage()) {
    SCOPED_TRACE(kZoneModeNames.name(config.zone_mode));
    Feed run(config);
    run.fly_after_a_stray_first_position();
    EXPECT_EQ(run.opened, 1u);
    EXPECT_EQ(run.pipeline.statistics().runs_restarted, 1u);
    EXPECT_EQ(run.pipeline.rejections().count("outside_coverage"), 5u);  // before the restart
    if (config.zone_mode == ZoneMode::Single) {
      EXPECT_NEAR(run.pipeline.projection()->reference().lat_deg, 50.0, 0.05);
    }
    EXPECT_EQ(run.pipeline.tracks().size(), 2u);
  }
}

TEST(RunStart, WorldwideZonesRefuseNoPositionWithoutALimit) {
  // The same stray first record: with zones and no limit it is a track like any other.
  Feed run;
  run.fly_after_a_stray_first_position();
  EXPECT_EQ(run.opened, 1u);
  EXPECT_EQ(run.pipeline.statistics().runs_restarted, 0u);
  EXPECT_EQ(run.pipeline.rejections().count("outside_coverage"), 0u);
  EXPECT_EQ(run.pipeline.tracks().size(), 2u);  // the stray one timed out
  EXPECT_EQ(run.pipeline.rejections().total(), 0u);
  EXPECT_GE(run.pipeline.statistics().zones_created, 2u);  // one of them at −45°, 170°
}

TEST(RunStart, AStrayFirstTimeDoesNotFixTheClock) {
  // A first record dated 2099 started the clock there: every later record was too late.
  for (const double stray_t : {4070908800.0, kT0 - 3600.0}) {
    SCOPED_TRACE(stray_t);
    Feed run;
    TrackReport stray = head_on("C", kT0, 0.0);
    stray.t = stray_t;
    run.pipeline.process(stray);
    run.fly(0.0, 80.0, 0.0);
    EXPECT_EQ(run.opened, 1u);
    EXPECT_EQ(run.pipeline.statistics().runs_restarted, stray_t > kT0 ? 1u : 0u);
    EXPECT_LT(run.pipeline.now(), kT0 + 80.0);
    EXPECT_GT(run.pipeline.now(), kT0 + 70.0);
  }
}

TEST(RunStart, AStrayFirstTimeDoesNotPostponeRenumbering) {
  // The renumbering's schedule (PipelineConfig::renumber_every_s) starts with the run: a
  // first record dated 2099 must not leave it waiting for 2099 after the restart.
  PipelineConfig config;
  config.renumber_every_s = 8.0;
  Pipeline pipeline(config);
  for (const double dt : {0.0, 4.0}) {  // a stray track that moved the clock once
    TrackReport stray = head_on("C", kT0, 0.0);
    stray.t = 4070908800.0 + dt;
    pipeline.process(stray);
  }
  for (double dt = 0.0; dt < 80.0; dt += 4.0) {
    pipeline.process(head_on("A", kT0 + dt, 0.0));
    pipeline.process(head_on("B", kT0 + dt, 0.0));
  }
  EXPECT_EQ(pipeline.statistics().runs_restarted, 1u);
  EXPECT_GE(pipeline.kinetic_statistics().renumberings, 8u);
}

TEST(RunStart, ARestartOfASparseFeedAppliesEveryRecordOnce) {
  // Review finding: a stray first record an hour ahead, then a sparse feed (a record every
  // 12 s, each more than max_time_jump_s after the last): the restart replays records that
  // the time guard holds and releases; the replay must not iterate a buffer that
  // processing reuses. Every record of the feed is applied once, none refused.
  Feed run;
  TrackReport stray = head_on("C", kT0, 0.0);
  stray.t = kT0 + 3600.0;
  run.pipeline.process(stray);
  for (int i = 0; i < 12; ++i) {
    TrackReport r = head_on("A", kT0 + 12.0 * i, 0.0);
    r.id = "sparse-feed-track-with-a-long-identifier-" + std::to_string(i % 3);
    run.pipeline.process(r);
  }
  run.pipeline.end_of_input();
  EXPECT_EQ(run.pipeline.statistics().runs_restarted, 1u);
  EXPECT_EQ(run.pipeline.statistics().accepted, 1u + 12u);  // the stray, then all 12
  EXPECT_EQ(run.pipeline.rejections().count("future_time"), 0u);
  EXPECT_EQ(run.pipeline.rejections().count("too_late"), 5u);  // before the restart
  EXPECT_EQ(run.pipeline.tracks().size(), 3u);
}

TEST(RunStart, AFeedWhoseDelayGrewCatchesUpWithTheLiveTick) {
  // Review finding: live, a feed running 5 s late switches to a path 20 s late. Its
  // records are too late; the tick (which moves the clock while nothing is accepted)
  // must not carry the clock out of their reach for ever.
  Feed run;
  for (int i = 0; i < 10; ++i) run.pipeline.process(head_on("A", kT0 + i, 0.0));  // wall = t + 5
  double wall = kT0 + 10.0 + 5.0;
  double last_accepted_wall = wall - 1.0;
  std::size_t accepted_after_switch = 0;
  for (int i = 0; i < 30; ++i, wall += 1.0) {
    const std::uint64_t before = run.pipeline.statistics().accepted;
    run.pipeline.process(head_on("A", wall - 20.0, 0.0));
    if (run.pipeline.statistics().accepted != before) {
      ++accepted_after_switch;
      last_accepted_wall = wall;
    } else {
      // kewd's tick when nothing was accepted for a whole second: the last data time plus
      // the wall time since.
      run.pipeline.advance_to(run.pipeline.statistics().last_data_time + (wall - last_accepted_wall));
    }
  }
  // Its records are too late (and, for this one aircraft, out of order until they pass its
  // last record at kT0 + 9); from then on every one is accepted.
  EXPECT_EQ(accepted_after_switch, 15u);
  EXPECT_GT(run.pipeline.rejections().count("too_late"), 0u);
}

TEST(RunStart, AnEstablishedRunIsNeverRestarted) {
  // Once five records were accepted, records elsewhere are only refused.
  for (const PipelineConfig& config : limited_coverage()) {
    SCOPED_TRACE(kZoneModeNames.name(config.zone_mode));
    Feed run(config);
    run.fly(0.0, 12.0, 0.0);
    for (int i = 0; i < 20; ++i) {
      TrackReport far = head_on(std::string("F") + std::to_string(i), kT0 + 12.0, 0.0);
      far.lat_deg = -45.0;
      run.pipeline.process(far);
    }
    EXPECT_EQ(run.pipeline.statistics().runs_restarted, 0u);
    EXPECT_EQ(run.pipeline.rejections().count("outside_coverage"), 20u);
    EXPECT_EQ(run.pipeline.tracks().size(), 2u);
  }
}

TEST(TimeGuard, RulesOnTheirOwn) {
  track::TimeGuard guard(10.0, 10.0, 3);
  EXPECT_FALSE(guard.ahead(110.0, 100.0));
  EXPECT_TRUE(guard.ahead(110.5, 100.0));
  TrackReport r;
  r.t = 200.0;
  EXPECT_FALSE(guard.hold(r));
  r.t = 150.0;  // 50 s before the first held: contradicts it, not itself
  std::vector<TrackReport> out;
  guard.refuse_contradicted(r.t, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].t, 200.0);
  EXPECT_FALSE(guard.hold(r));
  r.t = 155.0;
  EXPECT_FALSE(guard.hold(r));
  r.t = 161.0;
  EXPECT_TRUE(guard.hold(r));
  out.clear();
  guard.release_reached(150.0, out);  // 161 is more than 10 s ahead of 150
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].t, 150.0);
  EXPECT_EQ(out[1].t, 155.0);
  out.clear();
  guard.release(out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(guard.held(), 0u);
}

}  // namespace
}  // namespace kew
