// The area proximity warning in the pipeline (design §4.11): scripted flights across,
// over, under and beside a volume, a circle following one aircraft, a schedule and a
// traffic filter; the same events whatever the threads and batches, and after a
// checkpoint.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "kew/pipeline/pipeline.hpp"
#include "scripted_flight.hpp"

namespace kew {
namespace {

using test_support::Flight;
using test_support::kT0;

constexpr double kMetresPerDegreeLat = 111195.0;
const double kMetresPerDegreeLon = 111195.0 * std::cos(50.0 * M_PI / 180.0);

// A point `east_m` east and `north_m` north of (50° N, 8° E).
volume::LatLon at(double east_m, double north_m) {
  return {50.0 + north_m / kMetresPerDegreeLat, 8.0 + east_m / kMetresPerDegreeLon};
}

// 20–30 km east, ±5 km north of the origin, 2,000–10,000 ft.
volume::WatchedVolume square(const std::string& name = "SQUARE") {
  volume::WatchedVolume v;
  v.name = name;
  v.kind = volume::VolumeKind::Restricted;
  v.area = volume::Volume::polygon({at(20e3, -5e3), at(30e3, -5e3), at(30e3, 5e3), at(20e3, 5e3)}, {},
                                   {2000.0, 10000.0})
               .volume;
  return v;
}

// A 1 NM circle, 500 ft either side, around the aircraft called HELI.
volume::WatchedVolume bubble() {
  volume::WatchedVolume v;
  v.name = "HELI-BUBBLE";
  v.kind = volume::VolumeKind::Watch;
  v.follow = "heli";
  v.follow_radius_m = 1852.0;
  v.follow_band = {-500.0, 500.0};
  return v;
}

Flight eastbound(const std::string& id, double north_m, double alt_ft) {
  Flight f;
  f.id = id;
  f.north_m = north_m;
  f.alt_ft = alt_ft;
  f.gs_kt = 300.0;
  f.trk_deg = 90.0;
  return f;
}

// CROSS flies through the square; OVER above it, UNDER below it, SKIM 1 km north of it.
// HELI flies east at 1,000 ft far to the west, INTR meets it head-on at its level, and
// FAR passes 3 NM north of it.
std::vector<Flight> scenario() {
  std::vector<Flight> f = {eastbound("CROSS", 0.0, 5000.0), eastbound("OVER", -3e3, 12000.0),
                           eastbound("UNDER", 3e3, 1000.0), eastbound("SKIM", 6e3, 5000.0)};
  Flight heli;
  heli.id = "HELI";
  heli.east_m = -60e3;
  heli.alt_ft = 1000.0;
  heli.gs_kt = 100.0;
  heli.trk_deg = 90.0;
  Flight intruder = heli;
  intruder.id = "INTR";
  intruder.east_m = -40e3;
  intruder.alt_ft = 1200.0;
  intruder.gs_kt = 120.0;
  intruder.trk_deg = 270.0;
  Flight far = intruder;
  far.id = "FAR";
  far.north_m = 3 * 1852.0;
  f.push_back(heli);
  f.push_back(intruder);
  f.push_back(far);
  return f;
}

PipelineConfig with_volumes(std::vector<volume::WatchedVolume> volumes) {
  PipelineConfig config;
  config.volumes = std::move(volumes);
  return config;
}

std::vector<AlertEvent> apw(const std::vector<AlertEvent>& events) {
  std::vector<AlertEvent> out;
  std::copy_if(events.begin(), events.end(), std::back_inserter(out),
               [](const AlertEvent& e) { return e.kind == AlertKind::Apw; });
  return out;
}

std::vector<std::string> ids_alerted(const std::vector<AlertEvent>& events) {
  std::vector<std::string> ids;
  for (const AlertEvent& e : apw(events))
    if (e.state == AlertState::New) ids.push_back(e.a.id + "/" + e.volume);
  return ids;
}

TEST(AreaWarning, AlertsTheCrossingAircraftOnlyFromCautionToViolationToItsEnd) {
  const auto run = test_support::fly(scenario(), 300.0, with_volumes({square()}));
  EXPECT_EQ(ids_alerted(run.events), (std::vector<std::string>{"CROSS/SQUARE"}));
  std::vector<Severity> severities;
  for (const AlertEvent& e : apw(run.events)) {
    EXPECT_EQ(e.volume_kind, "restricted");
    EXPECT_TRUE(e.b.id.empty());
    if (e.state != AlertState::End) severities.push_back(e.severity);
  }
  ASSERT_GE(severities.size(), 3u);
  EXPECT_EQ(severities.front(), Severity::Caution);
  EXPECT_TRUE(std::find(severities.begin(), severities.end(), Severity::Warning) != severities.end());
  EXPECT_EQ(severities.back(), Severity::Loss);
  const std::vector<AlertEvent> events = apw(run.events);
  EXPECT_EQ(events.back().state, AlertState::End);
  EXPECT_EQ(events.back().end_reason, AlertEndReason::Cleared);
  // 300 kt from 20 km out: inside from about 130 s to 195 s after kT0.
  const auto first_loss = std::find_if(events.begin(), events.end(),
                                       [](const AlertEvent& e) { return e.severity == Severity::Loss; });
  EXPECT_NEAR(first_loss->t - kT0, 130.0, 4.5);
  EXPECT_GT(events.back().t - kT0, 195.0);
}

TEST(AreaWarning, ACircleFollowingAnAircraftAlertsWhoApproachesIt) {
  const auto run = test_support::fly(scenario(), 300.0, with_volumes({bubble()}));
  EXPECT_EQ(ids_alerted(run.events), (std::vector<std::string>{"INTR/HELI-BUBBLE"}));
  const std::vector<AlertEvent> events = apw(run.events);
  // Closing at 220 kt from 20 km with a 1 NM circle: inside from about 161 s.
  const auto first_loss = std::find_if(events.begin(), events.end(),
                                       [](const AlertEvent& e) { return e.severity == Severity::Loss; });
  ASSERT_NE(first_loss, events.end());
  EXPECT_NEAR(first_loss->t - kT0, (20e3 - 1852.0) / (220.0 * 1852.0 / 3600.0), 4.5);
}

TEST(AreaWarning, TheFollowedAircraftsDepartureEndsItsCirclesAlerts) {
  std::vector<Flight> flights = scenario();
  for (Flight& f : flights)
    if (f.id == "HELI")
      f.edit = [](TrackReport& r) {
        if (r.t > kT0 + 180.0) r.id = "HELI-GONE";  // a new track: HELI times out
      };
  const auto run = test_support::fly(flights, 300.0, with_volumes({bubble()}));
  const std::vector<AlertEvent> events = apw(run.events);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().state, AlertState::End);
  EXPECT_EQ(events.back().end_reason, AlertEndReason::TrackDropped);
}

TEST(AreaWarning, ASchedulesWindowOpensTheVolumeMidRun) {
  volume::WatchedVolume v = square();
  std::string error;
  v.schedule = *volume::WeeklySchedule::parse({"Mon 1415-2359"}, error);  // kT0 is a Monday, 14:13:20 UTC
  const auto always = test_support::fly(scenario(), 300.0, with_volumes({square()}));
  const auto later = test_support::fly(scenario(), 300.0, with_volumes({v}));
  const auto opened = [](const std::vector<AlertEvent>& events) {
    for (const AlertEvent& e : apw(events))
      if (e.state == AlertState::New) return e.t - kT0;
    return -1.0;
  };
  EXPECT_LT(opened(always.events), 100.0);
  EXPECT_GE(opened(later.events), 100.0);
}

TEST(AreaWarning, ATrafficFilterLeavesOthersAlone) {
  volume::WatchedVolume v = square();
  v.traffic.addresses = {"OV*"};
  const auto run = test_support::fly(scenario(), 300.0, with_volumes({v}));
  EXPECT_TRUE(ids_alerted(run.events).empty());  // OVER matches but never enters
  v.traffic.addresses = {"CR*"};
  EXPECT_EQ(ids_alerted(test_support::fly(scenario(), 300.0, with_volumes({v})).events),
            (std::vector<std::string>{"CROSS/SQUARE"}));
}

std::string text(const std::vector<AlertEvent>& events) {
  std::string out;
  for (const AlertEvent& e : events)
    out += std::to_string(e.seq) + " " + std::string(to_string(e.kind)) + " " + e.id + " " +
           std::string(to_string(e.state)) + " " + std::string(to_string(e.severity)) + " " + e.volume + " " +
           std::to_string(e.t) + " " + std::to_string(e.t_los_s) + "\n";
  return out;
}

TEST(AreaWarning, ThreadsAndBatchesGiveTheSameEvents) {
  const std::vector<volume::WatchedVolume> volumes = {square(), bubble(), square("SQUARE-2")};
  const auto one = test_support::fly(scenario(), 300.0, with_volumes(volumes));
  PipelineConfig parallel = with_volumes(volumes);
  parallel.threads = 4;
  parallel.batch_records = 64;
  const auto many = test_support::fly(scenario(), 300.0, parallel);
  ASSERT_FALSE(apw(one.events).empty());
  EXPECT_EQ(text(one.events), text(many.events));
}

TEST(AreaWarning, ACheckpointContinuesEventForEvent) {
  const std::vector<volume::WatchedVolume> volumes = {square(), bubble()};
  const std::vector<Flight> flights = scenario();
  const auto records_until = [&](double from, double to, Pipeline& p) {
    for (double t = kT0 + from; t < kT0 + to; t += 4.0)
      for (const Flight& f : flights) p.process(f.at(t));
    p.flush();
  };
  std::vector<AlertEvent> whole, halves;
  Pipeline straight(with_volumes(volumes));
  straight.set_alert_sink([&](const AlertEvent& e) { whole.push_back(e); });
  records_until(0.0, 300.0, straight);

  Pipeline first(with_volumes(volumes));
  first.set_alert_sink([&](const AlertEvent& e) { halves.push_back(e); });
  records_until(0.0, 140.0, first);  // CROSS inside, INTR closing on HELI
  const std::optional<std::string> bytes = first.checkpoint();
  ASSERT_TRUE(bytes);
  Pipeline second(with_volumes(volumes));
  second.set_alert_sink([&](const AlertEvent& e) { halves.push_back(e); });
  second.restore(*bytes);
  records_until(140.0, 300.0, second);
  EXPECT_EQ(text(whole), text(halves));
}

}  // namespace
}  // namespace kew
