// kew-eval's scoring of area proximity warnings (design §4.11, replay/README.md
// "kew-eval", docs/alert-quality.md "Area proximity warnings"): the AreaTruth of scripted
// flights through, short of and into volumes whose geometry puts each entry at a known
// second, APW alerts scored by hand and as the pipeline raises them.
#include "kew/replay/area_evaluation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <GeographicLib/Constants.hpp>

#include "kew/pipeline/pipeline.hpp"
#include "kew/replay/truth.hpp"

namespace kew::replay {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kNm = 1852.0;
constexpr double kT0 = 1714400000.0;  // Monday 2024-04-29 14:13:20 UTC, a whole second
constexpr std::int64_t kS0 = static_cast<std::int64_t>(kT0);
constexpr double kLat0 = 50.0;
constexpr double kKnot = kNm / 3600.0;
const eligibility::AerodromeTable kNoAerodromes(std::vector<eligibility::Aerodrome>{});

double meridional_m() {
  const double a = GeographicLib::Constants::WGS84_a(), f = GeographicLib::Constants::WGS84_f();
  const double e2 = f * (2 - f), s = std::sin(kLat0 * kDeg);
  return a * (1 - e2) / std::pow(1 - e2 * s * s, 1.5);
}

// An aircraft on the meridian `lon`, north_m(t − kT0) north of kLat0 (m), reporting every
// `period` s from kT0 + from_s to kT0 + to_s at `alt_ft` and speed |north_m'|.
struct Flight {
  std::string id;
  std::string source = "test";
  double lon = 8.0;
  double alt_ft = 2000.0;
  double from_s = 0.0, to_s = 240.0, period = 4.0;
  std::function<double(double)> north_m;
  std::uint32_t address = 0;
};

std::vector<TrackReport> fly(const std::vector<Flight>& flights) {
  std::vector<TrackReport> out;
  for (const Flight& f : flights)
    for (double s = f.from_s; s <= f.to_s + 1e-9; s += f.period) {
      TrackReport r;
      r.t = kT0 + s;
      r.id = f.id;
      r.source = f.source;
      r.callsign = f.id;
      r.address = f.address;
      r.lat_deg = kLat0 + f.north_m(s) / meridional_m() / kDeg;
      r.lon_deg = f.lon;
      r.alt_ft = f.alt_ft;
      const double v = f.north_m(s + 0.5) - f.north_m(s - 0.5);  // m/s
      r.gs_kt = std::abs(v) / kKnot;
      r.trk_deg = v >= 0.0 ? 0.0 : 180.0;
      r.vr_fpm = 0.0;
      out.push_back(r);
    }
  std::stable_sort(out.begin(), out.end(), [](const TrackReport& a, const TrackReport& b) { return a.t < b.t; });
  return out;
}

// A 2 NM circle on (kLat0, lon), 0–3,000 ft.
volume::WatchedVolume circle(const std::string& name, double lon, double lookahead_s = 120.0) {
  volume::WatchedVolume v;
  v.name = name;
  v.kind = volume::VolumeKind::Watch;
  v.area = volume::Volume::circle({kLat0, lon}, 2 * kNm, {0.0, 3000.0}).volume;
  v.lookahead_s = lookahead_s;
  v.warning_s = std::min(60.0, lookahead_s);
  return v;
}

// At 100 m/s northbound from 10,050 m short of the 2 NM edge: outside at +100 s (50 m
// short), inside at +101 s (50 m in), out again after 174.58 s.
double through(double s) { return -2 * kNm - 10050.0 + 100.0 * s; }
// Northbound towards the same circle for 60 s, then back south: 4 km short at most.
double turns_away(double s) { return -2 * kNm - 10000.0 + 100.0 * std::min(s, 60.0) - 100.0 * std::max(0.0, s - 60.0); }

// HIT flies through WATCH (lon 8); TURN turns away short of it, later; MISS flies through
// SHORT (lon 9), whose look-ahead is 1 s: it is seen 50 m short of the edge, 0.5 s out.
std::vector<Flight> scenario() {
  Flight hit{"HIT", "test", 8.0, 2000.0, 0.0, 240.0, 4.0, through, 0xA00001};
  Flight turn{"TURN", "test", 8.0, 2000.0, 300.0, 420.0, 4.0, [](double s) { return turns_away(s - 300.0); },
              0xA00002};
  Flight miss{"MISS", "test", 9.0, 2000.0, 0.0, 240.0, 4.0, through, 0xA00003};
  return {hit, turn, miss};
}

AlertSpan apw_alert(const std::string& id, const std::string& volume, double opened,
                    std::optional<double> ended = {}) {
  AlertSpan s;
  s.id = id + "@" + volume;
  s.kind = AlertKind::Apw;
  s.a_source = "test";
  s.a_id = id;
  s.volume = volume;
  s.volume_kind = "watch";
  s.opened_t = opened;
  s.ended_t = ended;
  return s;
}

const AreaEntry& entry_of(const AreaTruth& areas, const Truth& truth, const std::string& id) {
  const TruthTrackId track = *truth.find_track("test", id);
  for (const AreaEntry& e : areas.entries())
    if (e.track == track) return e;
  throw std::runtime_error("no entry of " + id);
}

TEST(AreaTruth, AnEntryStartsAtTheFirstSecondInsideAndTurningAwayIsNone) {
  const std::vector<TrackReport> records = fly(scenario());
  const Truth truth(records, kNoAerodromes);
  const AreaTruth areas(truth, records, {circle("WATCH", 8.0), circle("SHORT", 9.0, 1.0)});
  ASSERT_EQ(areas.entries().size(), 2u);  // HIT and MISS; TURN stays 4 km short
  const AreaEntry& hit = entry_of(areas, truth, "HIT");
  EXPECT_EQ(hit.volume, 0u);
  EXPECT_EQ(hit.start_s, kS0 + 101);
  EXPECT_EQ(hit.end_s, kS0 + 174);  // 3,704 m past the centre at +174.58 s
  EXPECT_EQ(hit.inside_seconds, 74);
  EXPECT_EQ(hit.eligible_since_s, kS0);  // flying in the volume's traffic from its first record
  EXPECT_EQ(entry_of(areas, truth, "MISS").volume, 1u);
  const AircraftId turn = truth.aircraft_of(*truth.find_track("test", "TURN"));
  EXPECT_FALSE(areas.first_inside_second(0, turn, kS0, kS0 + 1000));
  EXPECT_FALSE(areas.any_close_second(0, turn, kS0, kS0 + 1000));  // 4 km short: beyond 1 NM
  // HIT is close from 1 NM short of the edge: +81.98 s on.
  const AircraftId a = truth.aircraft_of(hit.track);
  EXPECT_FALSE(areas.any_close_second(0, a, kS0, kS0 + 81));
  EXPECT_TRUE(areas.any_close_second(0, a, kS0 + 82, kS0 + 82));
}

TEST(AreaEvaluation, ClassifiesAHitANuisanceAndAMissedEntryWithTheirWarningTimes) {
  const std::vector<TrackReport> records = fly(scenario());
  const Truth truth(records, kNoAerodromes);
  const AreaTruth areas(truth, records, {circle("WATCH", 8.0), circle("SHORT", 9.0, 1.0)});
  // HIT warned 81 s ahead; TURN warned while it flew towards WATCH; MISS's only alert
  // opened 3 s after it entered SHORT (a look-ahead of 1 s: seen inside, then confirmed).
  const std::vector<AlertSpan> alerts = {apw_alert("HIT", "WATCH", kT0 + 20.0, kT0 + 190.0),
                                         apw_alert("TURN", "WATCH", kT0 + 308.0, kT0 + 372.0),
                                         apw_alert("MISS", "SHORT", kT0 + 104.0, kT0 + 180.0),
                                         apw_alert("NOBODY", "WATCH", kT0 + 20.0),
                                         apw_alert("HIT", "ELSEWHERE", kT0 + 20.0)};
  const AreaEvaluation e = evaluate_areas(truth, areas, alerts, 2);
  ASSERT_EQ(e.alerts.size(), 5u);
  EXPECT_EQ(e.alerts[0].cls, AlertClass::Hit);
  EXPECT_EQ(e.alerts[0].entry_s, kS0 + 101);
  EXPECT_EQ(e.alerts[1].cls, AlertClass::Nuisance);
  EXPECT_EQ(e.alerts[2].cls, AlertClass::Hit);  // a late alert is still right about its entry
  EXPECT_EQ(e.alerts[3].cls, AlertClass::Ineligible);
  EXPECT_EQ(e.alerts[3].reason, IneligibleReason::NoTruth);  // no such track
  EXPECT_EQ(e.alerts[4].reason, IneligibleReason::NoTruth);  // no such volume
  EXPECT_EQ(e.alerts[4].kind, volume::VolumeKind::Watch);    // its own volume_kind

  ASSERT_EQ(e.entries.size(), 2u);
  const std::size_t hit = areas.entries()[0].volume == 0 ? 0 : 1;
  EXPECT_EQ(e.entries[hit].outcome, LossOutcome::Detected);
  EXPECT_EQ(e.entries[hit].alert, 0u);
  EXPECT_DOUBLE_EQ(*e.entries[hit].warning_s, 81.0);  // entry kT0 + 101 − opening kT0 + 20
  EXPECT_EQ(e.entries[hit].eligible_for_s, 101);
  EXPECT_EQ(e.entries[1 - hit].outcome, LossOutcome::Missed);  // opened at +104 > +101 + 1 s
  EXPECT_FALSE(e.entries[1 - hit].warning_s);

  ASSERT_EQ(e.by_kind.size(), 1u);
  const AreaFigures& f = e.by_kind.at(volume::VolumeKind::Watch);
  EXPECT_EQ(f.volumes, 2u);
  EXPECT_EQ(f.alerts, 5u);
  EXPECT_EQ(f.hits, 2u);
  EXPECT_EQ(f.nuisances, 1u);
  EXPECT_EQ(f.ineligible_no_truth, 2u);
  EXPECT_DOUBLE_EQ(*f.undesirable_share, 0.6);
  EXPECT_EQ(f.entries, 2u);
  EXPECT_EQ(f.detected, 1u);
  EXPECT_EQ(f.missed, 1u);
  EXPECT_EQ(f.unwarnable, 0u);
  ASSERT_TRUE(f.warning);
  EXPECT_DOUBLE_EQ(f.warning->p10, 81.0);
  EXPECT_DOUBLE_EQ(f.warning->p50, 81.0);

  // The hit window is the volume's look-ahead + 30 s: 160 s ahead with T = 120 s, HIT is
  // only close (1 NM short at +150 s); with T = 180 s it is a hit.
  const std::vector<AlertSpan> early = {apw_alert("HIT", "WATCH", kT0 - 59.0)};
  EXPECT_EQ(evaluate_areas(truth, areas, early, 2).alerts[0].cls, AlertClass::CloseCall);
  const AreaTruth longer(truth, records, {circle("WATCH", 8.0, 180.0)});
  EXPECT_EQ(evaluate_areas(truth, longer, early, 2).alerts[0].cls, AlertClass::Hit);
}

TEST(AreaEvaluation, TheSchedulesStartAndTheTrafficFilterBoundTheTruth) {
  const std::vector<TrackReport> records = fly(scenario());
  const Truth truth(records, kNoAerodromes);
  // Active from Monday 14:15 UTC (kT0 + 100 s): HIT enters 1 s later, unwarnable.
  volume::WatchedVolume scheduled = circle("WATCH", 8.0);
  std::string error;
  scheduled.schedule = *volume::WeeklySchedule::parse({"Mon 1415-2359"}, error);
  const AreaTruth areas(truth, records, {scheduled});
  ASSERT_EQ(areas.entries().size(), 1u);
  EXPECT_EQ(areas.entries()[0].eligible_since_s, kS0 + 100);
  const AreaEvaluation e = evaluate_areas(truth, areas, {}, 2);
  EXPECT_EQ(e.entries[0].outcome, LossOutcome::Unwarnable);
  EXPECT_EQ(e.entries[0].eligible_for_s, 1);
  // Active until 14:15: HIT enters after the volume closed.
  scheduled.schedule = *volume::WeeklySchedule::parse({"Mon 1400-1415"}, error);
  EXPECT_TRUE(AreaTruth(truth, records, {scheduled}).entries().empty());
  // Only callsigns T*: TURN, which never enters.
  volume::WatchedVolume filtered = circle("WATCH", 8.0);
  filtered.traffic.callsigns = {"T*"};
  EXPECT_TRUE(AreaTruth(truth, records, {filtered}).entries().empty());
  filtered.traffic.callsigns = {"h?t"};
  EXPECT_EQ(AreaTruth(truth, records, {filtered}).entries().size(), 1u);
}

TEST(AreaEvaluation, AFollowedCircleIsEnteredRelativeToItsAircraftAndNeverByIt) {
  // HELI hovers at 1,000 ft on (kLat0, 10°), seen by two sources (one aircraft: one
  // address); INTR flies north at 1,200 ft into its 1 NM, ±500 ft circle at +50.5 s;
  // HIGH does the same 800 ft above it.
  const auto hover = [](double) { return 0.0; };
  const auto closing = [](double s) { return -kNm - 5050.0 + 100.0 * s; };
  Flight heli{"HELI", "s1", 10.0, 1000.0, 0.0, 120.0, 4.0, hover, 0xB00001};
  Flight heli2 = heli;
  heli2.source = "s2";
  Flight intruder{"INTR", "test", 10.0, 1200.0, 0.0, 120.0, 4.0, closing, 0xB00002};
  Flight high{"HIGH", "test", 10.0, 1800.0, 0.0, 120.0, 4.0, closing, 0xB00003};
  const std::vector<TrackReport> records = fly({heli, heli2, intruder, high});
  const Truth truth(records, kNoAerodromes);
  volume::WatchedVolume bubble;
  bubble.name = "BUBBLE";
  bubble.follow = "heli";
  bubble.follow_radius_m = kNm;
  bubble.follow_band = {-500.0, 500.0};
  const AreaTruth areas(truth, records, {bubble});
  ASSERT_EQ(areas.entries().size(), 1u);
  const AreaEntry& entry = areas.entries()[0];
  EXPECT_EQ(entry.track, *truth.find_track("test", "INTR"));
  EXPECT_EQ(entry.start_s, kS0 + 51);
  EXPECT_EQ(entry.centre, truth.find_track("s1", "HELI"));
  const AircraftId high_aircraft = truth.aircraft_of(*truth.find_track("test", "HIGH"));
  EXPECT_FALSE(areas.first_inside_second(0, high_aircraft, kS0, kS0 + 120));

  AlertSpan own = apw_alert("HELI", "BUBBLE", kT0 + 10.0);
  own.a_source = "s2";
  const std::vector<AlertSpan> alerts = {apw_alert("INTR", "BUBBLE", kT0 + 8.0), own};
  const AreaEvaluation e = evaluate_areas(truth, areas, alerts, 2);
  EXPECT_EQ(e.alerts[0].cls, AlertClass::Hit);
  EXPECT_EQ(e.alerts[1].cls, AlertClass::Ineligible);
  EXPECT_EQ(e.alerts[1].reason, IneligibleReason::OneAircraft);
  EXPECT_EQ(e.entries[0].outcome, LossOutcome::Detected);
  EXPECT_DOUBLE_EQ(*e.entries[0].warning_s, 43.0);
}

// The pipeline's own APW alerts on the scenario: HIT warned well ahead, TURN a nuisance,
// MISS missed for SHORT's look-ahead of 1 s, and warned with 120 s.
TEST(AreaEvaluation, ThePipelinesAlertsOnTheScenarioScoreAsDesigned) {
  const std::vector<TrackReport> records = fly(scenario());
  const Truth truth(records, kNoAerodromes);
  const auto run = [&](double short_lookahead_s) {
    PipelineConfig config;
    config.volumes = {circle("WATCH", 8.0), circle("SHORT", 9.0, short_lookahead_s)};
    Pipeline pipeline(config);
    AlertCollector collector;
    pipeline.set_alert_sink([&](const AlertEvent& event) { collector.add(event); });
    for (const TrackReport& r : records) pipeline.process(r);
    pipeline.end_of_input();
    EXPECT_TRUE(alerts_of_kind(collector.alerts(), AlertKind::Stca).empty());
    const std::vector<AlertSpan> alerts = alerts_of_kind(collector.alerts(), AlertKind::Apw);
    const AreaTruth areas(truth, records, config.volumes);
    return std::pair{alerts, evaluate_areas(truth, areas, alerts, config.alerts.confirm)};
  };
  const auto [alerts, e] = run(1.0);
  ASSERT_EQ(alerts.size(), 3u);
  for (std::size_t i = 0; i < alerts.size(); ++i) {
    const AlertClass expected = alerts[i].a_id == "TURN" ? AlertClass::Nuisance : AlertClass::Hit;
    EXPECT_EQ(e.alerts[i].cls, expected) << alerts[i].a_id;
  }
  const AreaFigures& f = e.by_kind.at(volume::VolumeKind::Watch);
  EXPECT_EQ(f.hits, 2u);
  EXPECT_EQ(f.nuisances, 1u);
  EXPECT_EQ(f.detected, 1u);
  EXPECT_EQ(f.missed, 1u);
  ASSERT_TRUE(f.warning);
  // Seen 100.5 s from the edge at its first record, inside the look-ahead of 120 s, and
  // confirmed at a later record: warned at least 90 s ahead.
  EXPECT_GE(f.warning->p50, 90.0);
  EXPECT_LE(f.warning->p50, 101.0);

  const auto [alerts_120, e_120] = run(120.0);
  const AreaFigures& g = e_120.by_kind.at(volume::VolumeKind::Watch);
  EXPECT_EQ(g.detected, 2u);
  EXPECT_EQ(g.missed, 0u);
  EXPECT_GE(g.warning->p10, 90.0);
}

}  // namespace
}  // namespace kew::replay
