// kew-eval's library (design §2.6, replay/README.md "kew-eval"): the hindsight truth of
// a recording (interpolation, airborne, losses, one aircraft, flight hours) and the
// scoring of alerts against it, on hand-made tracks whose geometry is known exactly.
#include "kew/replay/evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geodesic.hpp>

#include "kew/replay/truth.hpp"

namespace kew::replay {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kNm = 1852.0;
constexpr double kT0 = 1714400000.0;  // a whole second
constexpr double kLat0 = 50.0;
constexpr double kSpeed_mps = 250.0;  // 485.96 kt
// The truth's aerodromes: none but where a test says (the tracks lie far from any).
const eligibility::AerodromeTable kNoAerodromes(std::vector<eligibility::Aerodrome>{});

// WGS84 radii of curvature at kLat0, so that tracks laid out with them have exactly the
// distances local_distance_m() measures when they are symmetric about kLat0.
double meridional_m() {
  const double a = GeographicLib::Constants::WGS84_a(), f = GeographicLib::Constants::WGS84_f();
  const double e2 = f * (2 - f), s = std::sin(kLat0 * kDeg);
  return a * (1 - e2) / std::pow(1 - e2 * s * s, 1.5);
}
double east_m_per_rad() {
  const double a = GeographicLib::Constants::WGS84_a(), f = GeographicLib::Constants::WGS84_f();
  const double e2 = f * (2 - f), s = std::sin(kLat0 * kDeg);
  return a / std::sqrt(1 - e2 * s * s) * std::cos(kLat0 * kDeg);
}

// A straight, level (or not) flight sampled every `period` seconds from t0 to t1: north
// of kLat0 by north0_m at t0, moving north at north_mps; east of lon0 by east_m.
struct Flight {
  std::string source = "test";
  std::string id;
  double t0 = kT0, t1 = kT0 + 240.0, period = 4.0;
  double north0_m = 0.0, north_mps = 0.0;
  double lon0 = 8.0, east_m = 0.0;
  double alt_ft = 30000.0;
  std::optional<double> gs_kt;  // default: |north_mps| in knots
  bool on_ground = false;
  std::optional<std::uint32_t> address;
  std::optional<std::uint16_t> mode3a;
};

std::vector<TrackReport> fly(const Flight& f) {
  std::vector<TrackReport> out;
  for (double t = f.t0; t <= f.t1 + 1e-9; t += f.period) {
    TrackReport r;
    r.t = t;
    r.id = f.id;
    r.source = f.source;
    r.lat_deg = kLat0 + (f.north0_m + f.north_mps * (t - f.t0)) / meridional_m() / kDeg;
    r.lon_deg = f.lon0 + f.east_m / east_m_per_rad() / kDeg;
    r.alt_ft = f.alt_ft;
    r.gs_kt = f.gs_kt ? *f.gs_kt : std::abs(f.north_mps) / (kNm / 3600.0);
    r.trk_deg = f.north_mps >= 0 ? 0.0 : 180.0;
    r.on_ground = f.on_ground;
    r.address = f.address;
    r.mode3a = f.mode3a;
    r.callsign = "CS" + f.id;
    out.push_back(r);
  }
  return out;
}

// Two aircraft head-on along the meridian at lon0, symmetric about kLat0: 59,510 m apart
// at kT0, closing at 500 m/s. Horizontal distance 59,510 − 500·(t − kT0) m, so below
// 5 NM (9,260 m) for t − kT0 in (100.5, 137.54): loss seconds kT0+101 … kT0+137, closest
// at kT0+119 (10 m).
std::vector<Flight> head_on(const std::string& a, const std::string& b, double lon0, double alt_b_ft = 30000.0) {
  Flight x, y;
  x.id = a;
  y.id = b;
  x.north0_m = -59510.0 / 2;
  x.north_mps = kSpeed_mps;
  y.north0_m = 59510.0 / 2;
  y.north_mps = -kSpeed_mps;
  x.lon0 = y.lon0 = lon0;
  y.alt_ft = alt_b_ft;
  return {x, y};
}
constexpr std::int64_t kLossStart = static_cast<std::int64_t>(kT0) + 101;
constexpr std::int64_t kLossEnd = static_cast<std::int64_t>(kT0) + 137;

std::vector<TrackReport> records_of(const std::vector<Flight>& flights) {
  std::vector<TrackReport> out;
  for (const Flight& f : flights)
    for (TrackReport& r : fly(f)) out.push_back(std::move(r));
  return out;
}

TEST(LocalDistance, AgreesWithTheGeodesicWithin20Nm) {
  const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> lat(-75.0, 75.0), lon(-180.0, 180.0), azimuth(0.0, 360.0),
      length(100.0, 20.0 * kNm);
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double lat1 = lat(random), lon1 = lon(random), s12 = length(random);
    double lat2, lon2;
    geodesic.Direct(lat1, lon1, azimuth(random), s12, lat2, lon2);
    worst = std::max(worst, std::abs(local_distance_m(lat1, lon1, lat2, lon2) - s12) / s12);
  }
  EXPECT_LT(worst, 5e-5);  // 0.005 %: the bound documented up to 80°; 0.5 % is allowed
  // Across the antimeridian the short way round.
  EXPECT_NEAR(local_distance_m(0.0, 179.99, 0.0, -179.99), 0.02 * 111319.49, 1.0);
}

TEST(Truth, PlantedCrossingAtOneLevelIsOneLossEventWithItsStartSecond) {
  const Truth truth(records_of(head_on("A", "B", 8.0)), kNoAerodromes);
  ASSERT_EQ(truth.loss_events().size(), 1u);
  const LossEvent& loss = truth.loss_events()[0];
  EXPECT_EQ(loss.start_s, kLossStart);
  EXPECT_EQ(loss.end_s, kLossEnd);
  EXPECT_EQ(loss.loss_seconds, kLossEnd - kLossStart + 1);
  EXPECT_NEAR(loss.min_horizontal_m, 10.0, 0.01);
  EXPECT_EQ(loss.vertical_at_min_ft, 0.0);
  EXPECT_EQ(truth.track(loss.track_a).id, "A");
  EXPECT_EQ(truth.track(loss.track_b).id, "B");
  EXPECT_EQ(truth.figures().tracks, 2u);
  EXPECT_EQ(truth.figures().aircraft, 2u);
  // Both airborne at every whole second from kT0 to kT0 + 240.
  EXPECT_EQ(truth.figures().airborne_seconds, 2 * 241);
  EXPECT_DOUBLE_EQ(truth.figures().flight_hours(), 482.0 / 3600.0);
  const auto a = truth.aircraft_of(loss.track_a), b = truth.aircraft_of(loss.track_b);
  EXPECT_EQ(truth.first_loss_second(a, b, 0, kLossStart + 5), kLossStart);
  EXPECT_EQ(truth.first_loss_second(b, a, kLossStart + 5, kLossStart + 6), kLossStart + 5);
  EXPECT_FALSE(truth.first_loss_second(a, b, kLossEnd + 1, kLossEnd + 100));
  EXPECT_TRUE(truth.any_close_second(a, b, kLossEnd + 1, kLossEnd + 3));   // within 6 NM
  EXPECT_FALSE(truth.any_close_second(a, b, kLossEnd + 8, kLossEnd + 30));  // beyond
}

TEST(Truth, SamplesAreInterpolatedOnWholeSecondsAndNeverAcrossGaps) {
  std::vector<TrackReport> records;
  TrackReport r;
  r.id = "G";
  r.alt_ft = 10000;
  r.gs_kt = 300;
  for (const double t : {kT0 + 0.5, kT0 + 10.5, kT0 + 40.5, kT0 + 41.0}) {
    r.t = t;
    r.lat_deg = 50.0 + (t - kT0) * 1e-3;
    r.alt_ft += 100;
    records.push_back(r);
  }
  const Truth truth(records, kNoAerodromes);
  const TruthTrackId g = *truth.find_track("", "G");
  EXPECT_FALSE(truth.sample(g, static_cast<std::int64_t>(kT0)));
  const auto mid = truth.sample(g, static_cast<std::int64_t>(kT0) + 5);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->lat_deg, 50.005, 1e-12);
  EXPECT_NEAR(mid->alt_ft, 10145.0, 1e-9);
  EXPECT_TRUE(mid->airborne);
  EXPECT_TRUE(truth.sample(g, static_cast<std::int64_t>(kT0) + 10));
  // 30 s between kT0+10.5 and kT0+40.5: no samples in the gap, none extrapolated.
  EXPECT_FALSE(truth.sample(g, static_cast<std::int64_t>(kT0) + 11));
  EXPECT_FALSE(truth.sample(g, static_cast<std::int64_t>(kT0) + 40));
  EXPECT_TRUE(truth.sample(g, static_cast<std::int64_t>(kT0) + 41));
  EXPECT_FALSE(truth.sample(g, static_cast<std::int64_t>(kT0) + 42));
  const auto nearest = truth.nearest_sample(g, kT0 + 14.0, 10.0);
  ASSERT_TRUE(nearest);
  EXPECT_EQ(nearest->first, static_cast<std::int64_t>(kT0) + 10);
  EXPECT_FALSE(truth.nearest_sample(g, kT0 + 25.5, 10.0));
  EXPECT_EQ(truth.track(g).median_interval_s, 0.5);  // of 10 and 0.5: the lower median
  EXPECT_EQ(truth.airborne_since(g, static_cast<std::int64_t>(kT0) + 7), static_cast<std::int64_t>(kT0) + 1);
  EXPECT_EQ(truth.airborne_since(g, static_cast<std::int64_t>(kT0) + 41), static_cast<std::int64_t>(kT0) + 41);
}

TEST(Truth, AdjacentLevelsWithinTheAltimetryToleranceAreSeparated) {
  EXPECT_TRUE(Truth(records_of(head_on("A", "B", 8.0, 30975.0)), kNoAerodromes).loss_events().empty());
  EXPECT_TRUE(Truth(records_of(head_on("A", "B", 8.0, 30800.0)), kNoAerodromes).loss_events().empty());
  EXPECT_EQ(Truth(records_of(head_on("A", "B", 8.0, 30700.0)), kNoAerodromes).loss_events().size(), 1u);
  // The standard is an option of the evaluation: with S_v = 2,000 ft, 975 ft is a loss.
  SeparationStandard wide;
  wide.vertical_ft = 2000.0;
  EXPECT_EQ(Truth(records_of(head_on("A", "B", 8.0, 30975.0)), kNoAerodromes, wide).loss_events().size(), 1u);
}

TEST(Truth, PairsBelowTheLowerLimitSlowOrOnTheGroundLoseNoSeparation) {
  auto low = head_on("A", "B", 8.0);
  low[0].alt_ft = low[1].alt_ft = 1400.0;
  EXPECT_TRUE(Truth(records_of(low), kNoAerodromes).loss_events().empty());
  low[0].alt_ft = low[1].alt_ft = 1500.0;  // at the limit: airborne
  EXPECT_EQ(Truth(records_of(low), kNoAerodromes).loss_events().size(), 1u);

  // 1,000 ft above an aerodrome of the table (2,000 ft) within 5 NM: aerodrome traffic.
  low[0].alt_ft = low[1].alt_ft = 2500.0;
  EXPECT_EQ(Truth(records_of(low), kNoAerodromes).loss_events().size(), 1u);
  const eligibility::AerodromeTable hill({{"HILL", kLat0, 8.0, 2000.0}});
  EXPECT_TRUE(Truth(records_of(low), hill).loss_events().empty());

  // Two targets 2 NM apart at one level, not flying: reported 40 kt, or no speed and
  // no movement (derived 0 kt), or flagged on the ground.
  Flight x, y;
  x.id = "X";
  y.id = "Y";
  y.north0_m = 2 * kNm;
  x.gs_kt = y.gs_kt = 40.0;
  EXPECT_TRUE(Truth(records_of({x, y}), kNoAerodromes).loss_events().empty());
  x.gs_kt = y.gs_kt = 60.0;
  EXPECT_EQ(Truth(records_of({x, y}), kNoAerodromes).loss_events().size(), 1u);
  std::vector<TrackReport> still = records_of({x, y});
  for (TrackReport& r : still) r.gs_kt.reset();
  EXPECT_TRUE(Truth(still, kNoAerodromes).loss_events().empty());
  EXPECT_EQ(Truth(still, kNoAerodromes).figures().airborne_seconds, 0);
  x.on_ground = true;
  EXPECT_TRUE(Truth(records_of({x, y}), kNoAerodromes).loss_events().empty());
  // Implausible altitude.
  x.on_ground = false;
  x.alt_ft = y.alt_ft = 71900.0;
  EXPECT_TRUE(Truth(records_of({x, y}), kNoAerodromes).loss_events().empty());
}

TEST(Truth, SpeedIsDerivedFromPositionsWhenNotReported) {
  std::vector<TrackReport> records = records_of(head_on("A", "B", 8.0));
  for (TrackReport& r : records) r.gs_kt.reset();
  const Truth truth(records, kNoAerodromes);
  ASSERT_EQ(truth.loss_events().size(), 1u);
  EXPECT_EQ(truth.loss_events()[0].start_s, kLossStart);
  const auto s = truth.sample(*truth.find_track("test", "A"), kLossStart);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->speed_kt, kSpeed_mps / (kNm / 3600.0), 0.1);
}

// Two tracks 0.5 NM and 100 ft apart flying side by side.
std::vector<Flight> twins(double seconds, std::optional<std::uint32_t> a = {}, std::optional<std::uint32_t> b = {}) {
  Flight x, y;
  x.id = "T1";
  y.id = "T2";
  y.source = "other";
  x.north_mps = y.north_mps = kSpeed_mps;
  x.t1 = y.t1 = kT0 + seconds;
  y.east_m = 0.5 * kNm;
  y.alt_ft = x.alt_ft + 100;
  x.address = a;
  y.address = b;
  return {x, y};
}

TEST(Truth, TwoTracksWithOneCodeTogetherForAMinuteAreOneAircraft) {
  std::vector<Flight> squawking = twins(90);
  for (Flight& f : squawking) f.mode3a = 04711;
  const Truth together(records_of(squawking), kNoAerodromes);
  EXPECT_EQ(together.figures().tracks, 2u);
  EXPECT_EQ(together.figures().aircraft, 1u);
  EXPECT_EQ(together.figures().merged_by_proximity, 1u);
  EXPECT_TRUE(together.loss_events().empty());
  EXPECT_EQ(together.aircraft_of(0), together.aircraft_of(1));
  EXPECT_EQ(together.figures().airborne_seconds, 89);  // flown once (samples kT0 … kT0+88)

  // 40 s side by side is not long enough: two aircraft losing separation.
  std::vector<Flight> brief_pair = twins(40);
  for (Flight& f : brief_pair) f.mode3a = 04711;
  const Truth brief(records_of(brief_pair), kNoAerodromes);
  EXPECT_EQ(brief.figures().aircraft, 2u);
  ASSERT_EQ(brief.loss_events().size(), 1u);
  EXPECT_EQ(brief.loss_events()[0].start_s, static_cast<std::int64_t>(kT0));

  // Closeness alone is no identity: without a code in common, or with a conspicuity code
  // (7000) in common, two tracks together for minutes are two aircraft (a formation).
  const Truth formation_no_codes(records_of(twins(180)), kNoAerodromes);
  EXPECT_EQ(formation_no_codes.figures().aircraft, 2u);
  EXPECT_EQ(formation_no_codes.loss_events().size(), 1u);
  std::vector<Flight> vfr = twins(180);
  for (Flight& f : vfr) f.mode3a = 07000;
  EXPECT_EQ(Truth(records_of(vfr), kNoAerodromes).figures().aircraft, 2u);

  // The same address is one aircraft wherever the tracks are; two addresses are two.
  auto apart = twins(40, 0x4CA123, 0x4CA123);
  apart[1].east_m = 50 * kNm;
  EXPECT_EQ(Truth(records_of(apart), kNoAerodromes).figures().aircraft, 1u);
  EXPECT_EQ(Truth(records_of(apart), kNoAerodromes).figures().merged_by_address, 1u);
  std::vector<Flight> formation = twins(90, 0x4CA123, 0x4CA124);
  for (Flight& f : formation) f.mode3a = 04711;
  EXPECT_EQ(Truth(records_of(formation), kNoAerodromes).figures().aircraft, 2u);
  EXPECT_EQ(Truth(records_of(formation), kNoAerodromes).loss_events().size(), 1u);
}

TEST(Truth, RefusesUnusableRecordsAndSplitsAtTrackEnd) {
  std::vector<TrackReport> records = records_of(head_on("A", "B", 8.0));
  TrackReport bad = records[0];
  bad.lat_deg = std::nan("");
  records.push_back(bad);
  bad = records[0];
  bad.lon_deg = 200;
  records.push_back(bad);
  EXPECT_EQ(Truth(records, kNoAerodromes).figures().records_refused, 2u);
  EXPECT_EQ(Truth(records, kNoAerodromes).figures().records, records.size() - 2);

  // A's track ends at kT0+100; its id reappears at once as another aircraft (reused
  // number): no samples between kT0+100 and kT0+104, so no airborne second there.
  for (TrackReport& r : records)
    if (r.id == "A" && r.t == kT0 + 100) r.track_end = true;
  const Truth truth(records, kNoAerodromes);
  const TruthTrackId a = *truth.find_track("test", "A");
  EXPECT_TRUE(truth.sample(a, kLossStart - 1));
  EXPECT_FALSE(truth.sample(a, kLossStart));
  EXPECT_TRUE(truth.sample(a, kLossStart + 3));
  EXPECT_EQ(truth.airborne_since(a, kLossStart + 3), kLossStart + 3);
}

AlertEvent event(const std::string& id, AlertState state, double t, double opened, const std::string& a,
                 const std::string& b, Severity severity = Severity::Caution) {
  AlertEvent e;
  e.id = id;
  e.state = state;
  e.t = t;
  e.opened_t = opened;
  e.severity = severity;
  e.a.source = e.b.source = "test";
  e.a.id = a;
  e.b.id = b;
  if (state == AlertState::End) e.end_reason = AlertEndReason::Cleared;
  return e;
}

// An alert of pair (a, b) opened at `opened`, ended at `ended` unless empty.
AlertSpan alert(const std::string& a, const std::string& b, double opened, std::optional<double> ended = {}) {
  AlertCollector collector;
  collector.add(event("x", AlertState::New, opened, opened, a, b));
  if (ended) collector.add(event("x", AlertState::End, *ended, opened, a, b));
  return collector.alerts().front();
}

TEST(AlertCollector, GroupsEventsIntoAlerts) {
  AlertCollector c;
  c.add(event("1", AlertState::New, 10, 10, "A", "B"));
  c.add(event("2", AlertState::Update, 12, 5, "C", "D", Severity::Loss));  // its New was before the log
  c.add(event("1", AlertState::Update, 14, 10, "A", "B", Severity::Warning));
  c.add(event("1", AlertState::End, 20, 10, "A", "B", Severity::None));
  c.add(event("1", AlertState::New, 30, 30, "A", "B"));  // an id seen again after its End
  ASSERT_EQ(c.alerts().size(), 3u);
  EXPECT_EQ(c.alerts()[0].opened_t, 10);
  EXPECT_EQ(c.alerts()[0].ended_t, 20);
  EXPECT_EQ(c.alerts()[0].max_severity, Severity::Warning);
  EXPECT_EQ(c.alerts()[0].events, 3u);
  EXPECT_EQ(c.alerts()[0].end_reason, AlertEndReason::Cleared);
  EXPECT_EQ(c.alerts()[1].opened_t, 5);
  EXPECT_FALSE(c.alerts()[1].ended_t);
  EXPECT_EQ(c.alerts()[1].a_id, "C");
  EXPECT_EQ(c.alerts()[2].opened_t, 30);
}

// Five pairs side by side, 1° of longitude apart: a loss (A/B), a close call passing
// 5.5 NM apart at one level (C/D), 975 ft apart (E/F), below 1,500 ft (G/H), one
// aircraft as two tracks (T1/T2).
std::vector<TrackReport> five_pairs() {
  std::vector<Flight> flights = head_on("A", "B", 8.0);
  auto close = head_on("C", "D", 9.0);
  close[1].east_m = 5.5 * kNm;
  auto level = head_on("E", "F", 10.0, 30975.0);
  auto low = head_on("G", "H", 11.0);
  low[0].alt_ft = low[1].alt_ft = 1000.0;
  auto same = twins(240);
  for (Flight& f : same) {
    f.lon0 = 12.0;
    f.mode3a = 04711;  // one code in common: the evidence of one aircraft
  }
  for (auto* group : {&close, &level, &low, &same}) flights.insert(flights.end(), group->begin(), group->end());
  return records_of(flights);
}

TEST(Evaluation, ClassifiesAlertsIntoEachClass) {
  const Truth truth(five_pairs(), kNoAerodromes);
  ASSERT_EQ(truth.loss_events().size(), 1u);
  const double opened = kT0 + 20.0;
  std::vector<AlertSpan> alerts = {
      alert("A", "B", opened),                       // loss at kT0+101 within [open − 10, open + 150]
      alert("A", "B", kLossStart + 19.5),            // opened after the loss began: still a hit
      alert("A", "B", kT0 + 152.0),                  // window [142, 302]: past the loss and 6 NM
      alert("C", "D", opened),                       // 5.5 NM at one level: close call
      alert("E", "F", opened),                       // 975 ft: nuisance
      alert("G", "H", opened),                       // 1,000 ft: ineligible, not airborne
      alert("T1", "T2", opened),                     // one aircraft
      alert("A", "nobody", opened),                  // not in the recording
      alert("G", "H", kT0 - 30.0),                   // before G and H are seen: no truth
  };
  alerts[6].b_source = "other";
  alerts[7].b_source = "elsewhere";
  const Evaluation e = evaluate(truth, alerts, {120.0, 2});
  ASSERT_EQ(e.alerts.size(), alerts.size());
  EXPECT_EQ(e.alerts[0].cls, AlertClass::Hit);
  EXPECT_EQ(e.alerts[0].loss_s, kLossStart);
  EXPECT_EQ(e.alerts[1].cls, AlertClass::Hit);
  EXPECT_EQ(e.alerts[1].loss_s, kLossStart + 10);  // the first loss second of the window
  EXPECT_EQ(e.alerts[2].cls, AlertClass::Nuisance);
  EXPECT_EQ(e.alerts[3].cls, AlertClass::CloseCall);
  EXPECT_EQ(e.alerts[4].cls, AlertClass::Nuisance);
  EXPECT_EQ(e.alerts[5].cls, AlertClass::Ineligible);
  EXPECT_EQ(e.alerts[5].reason, IneligibleReason::NotAirborne);
  EXPECT_EQ(e.alerts[6].cls, AlertClass::Ineligible);
  EXPECT_EQ(e.alerts[6].reason, IneligibleReason::OneAircraft);
  EXPECT_EQ(e.alerts[7].reason, IneligibleReason::NoTruth);
  EXPECT_EQ(e.alerts[8].reason, IneligibleReason::NoTruth);

  const EvaluationFigures& f = e.figures;
  EXPECT_EQ(f.alerts, 9u);
  EXPECT_EQ(f.hits, 2u);
  EXPECT_EQ(f.close_calls, 1u);
  EXPECT_EQ(f.nuisances, 2u);
  EXPECT_EQ(f.ineligible, 4u);
  EXPECT_EQ(f.ineligible_not_airborne, 1u);
  EXPECT_EQ(f.ineligible_one_aircraft, 1u);
  EXPECT_EQ(f.ineligible_no_truth, 2u);
  EXPECT_DOUBLE_EQ(*f.undesirable_share, 6.0 / 9.0);
  // 8 airborne tracks of 241 s and one aircraft of two tracks of 241 s (G, H not airborne).
  EXPECT_DOUBLE_EQ(f.flight_hours, 7 * 241 / 3600.0);
  EXPECT_DOUBLE_EQ(*f.alerts_per_100_flight_hours, 900.0 / (7 * 241 / 3600.0));

  // A shorter look-ahead narrows the window: opened 92.5 s before the loss with T = 60,
  // [open − 10, open + 90] ends before it, but within 6 NM (from kT0 + 97).
  const std::vector<AlertSpan> early = {alert("A", "B", kLossStart - 92.5)};
  EXPECT_EQ(evaluate(truth, early, {60.0, 2}).alerts[0].cls, AlertClass::CloseCall);
  EXPECT_EQ(evaluate(truth, early, {120.0, 2}).alerts[0].cls, AlertClass::Hit);

  const Evaluation none = evaluate(truth, {}, {120.0, 2});
  EXPECT_FALSE(none.figures.undesirable_share);
  EXPECT_FALSE(none.figures.warning);
  EXPECT_EQ(none.figures.missed, 1u);
}

// Scores alerts of pair A/B against the planted loss; returns its ScoredLoss.
ScoredLoss loss_outcome(const std::vector<AlertSpan>& alerts, const std::vector<TrackReport>& records) {
  const Truth truth(records, kNoAerodromes);
  EXPECT_EQ(truth.loss_events().size(), 1u);
  return evaluate(truth, alerts, {120.0, 2}).losses.at(0);
}

TEST(Evaluation, LossesAreDetectedMissedOrUnwarnableWithExactWarningTimes) {
  const std::vector<TrackReport> records = records_of(head_on("A", "B", 8.0));
  const double start = static_cast<double>(kLossStart);

  ScoredLoss l = loss_outcome({alert("A", "B", start - 73.25)}, records);
  EXPECT_EQ(l.outcome, LossOutcome::Detected);
  EXPECT_EQ(l.warning_s, 73.25);
  EXPECT_EQ(l.alert, 0u);
  EXPECT_EQ(l.eligible_for_s, 101);

  l = loss_outcome({alert("A", "B", start + 1.0)}, records);  // the sampling tolerance
  EXPECT_EQ(l.outcome, LossOutcome::Detected);
  EXPECT_EQ(l.warning_s, -1.0);
  EXPECT_EQ(loss_outcome({alert("A", "B", start + 1.5)}, records).outcome, LossOutcome::Missed);

  // Ended 29 s before the loss: still the warning; 31 s before: forgotten.
  l = loss_outcome({alert("A", "B", start - 200.0, start - 29.0)}, records);
  EXPECT_EQ(l.outcome, LossOutcome::Detected);
  EXPECT_EQ(l.warning_s, 200.0);
  EXPECT_EQ(loss_outcome({alert("A", "B", start - 200.0, start - 31.0)}, records).outcome, LossOutcome::Missed);

  // The earliest alert still relevant gives the warning time.
  l = loss_outcome({alert("A", "B", start - 90.0, start - 40.0), alert("A", "B", start - 50.0),
                    alert("A", "B", start - 60.0, start - 10.0)},
                   records);
  EXPECT_EQ(l.outcome, LossOutcome::Detected);
  EXPECT_EQ(l.alert, 2u);
  EXPECT_EQ(l.warning_s, 60.0);

  // Another pair's alert does not detect it.
  EXPECT_EQ(loss_outcome({alert("A", "C", start - 60.0)}, records).outcome, LossOutcome::Missed);

  // B first seen 5 s before the loss began (records every 4 s, confirm 2: 8 s): no
  // alert could have been confirmed. 9 s before: warnable, and missed without an alert.
  auto late = head_on("A", "B", 8.0);
  late[1].t0 = start - 5.0;
  late[1].north0_m -= kSpeed_mps * (late[1].t0 - kT0);
  l = loss_outcome({alert("A", "B", start - 2.0)}, records_of(late));
  EXPECT_EQ(l.outcome, LossOutcome::Unwarnable);
  EXPECT_EQ(l.eligible_for_s, 5);
  EXPECT_EQ(l.warning_s, 2.0);  // covered, but not counted as detected
  late[1].t0 = start - 9.0;
  late[1].north0_m = 59510.0 / 2 - kSpeed_mps * (late[1].t0 - kT0);
  l = loss_outcome({}, records_of(late));
  EXPECT_EQ(l.outcome, LossOutcome::Missed);
  EXPECT_EQ(l.eligible_for_s, 9);

  const Truth truth(records_of(late), kNoAerodromes);
  const Evaluation e = evaluate(truth, {}, {120.0, 4});  // confirm 4: 16 s
  EXPECT_EQ(e.losses[0].outcome, LossOutcome::Unwarnable);
  EXPECT_EQ(e.figures.unwarnable, 1u);
  EXPECT_EQ(e.figures.missed, 0u);
  EXPECT_EQ(e.figures.detected, 0u);
}

TEST(Evaluation, WarningTimePercentilesAreNearestRank) {
  const std::vector<double> v = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  EXPECT_EQ(nearest_rank_percentile(v, 0), 1);
  EXPECT_EQ(nearest_rank_percentile(v, 10), 1);
  EXPECT_EQ(nearest_rank_percentile(v, 50), 5);
  EXPECT_EQ(nearest_rank_percentile(v, 90), 9);
  EXPECT_EQ(nearest_rank_percentile(v, 100), 10);
  const std::vector<double> one = {42};
  EXPECT_EQ(nearest_rank_percentile(one, 90), 42);

  // Two losses (A/B and C/D), warned 80 s and 30 s ahead.
  std::vector<Flight> flights = head_on("A", "B", 8.0);
  const auto other = head_on("C", "D", 9.0);
  flights.insert(flights.end(), other.begin(), other.end());
  const Truth truth(records_of(flights), kNoAerodromes);
  const double start = static_cast<double>(kLossStart);
  const std::vector<AlertSpan> alerts = {alert("A", "B", start - 80.0), alert("C", "D", start - 30.0)};
  const Evaluation e = evaluate(truth, alerts, {120.0, 2});
  ASSERT_TRUE(e.figures.warning);
  EXPECT_EQ(e.figures.detected, 2u);
  EXPECT_EQ(e.figures.warning->min, 30.0);
  EXPECT_EQ(e.figures.warning->p50, 30.0);
  EXPECT_EQ(e.figures.warning->p90, 80.0);
  EXPECT_EQ(e.figures.warning->max, 80.0);
  EXPECT_DOUBLE_EQ(*e.figures.undesirable_share, 0.0);
}

}  // namespace
}  // namespace kew::replay
