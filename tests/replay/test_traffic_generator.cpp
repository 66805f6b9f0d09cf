// TrafficGenerator (replay/include/kew/replay/traffic_generator.hpp): determinism, time
// order, sampling counts, plausible values per scenario, holding stacks over one ground
// point, and conflicts (5 NM / 1000 ft losses) arising in every regional scenario; the
// table of aerodromes (kew/replay/airports.hpp); the global scenario's coverage of the
// poles, the oceans and the antimeridian, its noise near the poles, and speeds and tracks
// that agree with the geodesics flown.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <GeographicLib/Geodesic.hpp>

#include "kew/config/aerodromes.hpp"
#include "kew/config/shared_config.hpp"
#include "kew/eligibility/eligibility.hpp"
#include "kew/replay/airports.hpp"
#include "kew/replay/traffic_generator.hpp"

namespace kew::replay {
namespace {

constexpr double kMetresPerNm = 1852.0;
constexpr double kMpsPerKnot = kMetresPerNm / 3600.0;
constexpr double kDegToRad = std::numbers::pi / 180.0;
// Mean Earth radius: enough for distances of a few km between nearby aircraft (the local
// frame below errs by well under 1 % there, against thresholds met with wide margins).
constexpr double kEarthRadiusM = 6'371'008.8;

// Scenarios that fly within the region of center_lat/lon_deg and radius_km.
const Scenario kRegionalScenarios[] = {Scenario::Random, Scenario::Airways, Scenario::Stacks,
                                       Scenario::Tma, Scenario::Mixed, Scenario::Calibrated};
const Scenario kAllScenarios[] = {Scenario::Random, Scenario::Airways, Scenario::Stacks, Scenario::Tma,
                                  Scenario::Mixed, Scenario::Calibrated, Scenario::Global};

/// kew's aerodrome table (data/aerodromes.csv), which the global scenario flies between.
std::shared_ptr<const eligibility::AerodromeTable> kew_aerodromes() {
  static const std::shared_ptr<const eligibility::AerodromeTable> table = config::load_default_aerodromes();
  return table;
}

std::vector<TrackReport> generate(const GeneratorConfig& config) {
  TrafficGenerator generator(config);
  std::vector<TrackReport> records;
  TrackReport record;
  while (generator.next(record)) records.push_back(record);
  return records;
}

/// The records are the true states (bar 1 cm, 1 ms and 0.01 ft rounding): no noise, no
/// jitter, no misses, no altitude quantisation.
GeneratorConfig truth_config(Scenario scenario, std::size_t aircraft, double duration_s) {
  GeneratorConfig config;
  config.scenario = scenario;
  config.aircraft = aircraft;
  config.duration_s = duration_s;
  config.seed = 7;
  config.jitter_s = 0;
  config.position_noise_m = 0;
  config.missed_update_probability = 0;
  config.altitude_quantum_ft = 0;
  config.aerodromes = kew_aerodromes();
  return config;
}

bool in_range(double value, double lo, double hi) { return std::isfinite(value) && value >= lo && value <= hi; }

bool identical(const TrackReport& a, const TrackReport& b) {
  return a.t == b.t && a.id == b.id && a.source == b.source && a.lat_deg == b.lat_deg &&
         a.lon_deg == b.lon_deg && a.alt_ft == b.alt_ft && a.gs_kt == b.gs_kt && a.trk_deg == b.trk_deg &&
         a.vr_fpm == b.vr_fpm && a.callsign == b.callsign && a.mode3a == b.mode3a &&
         a.address == b.address && a.on_ground == b.on_ground && a.coasting == b.coasting &&
         a.track_end == b.track_end;
}

double distance_from_centre_m(const GeneratorConfig& config, const TrackReport& r) {
  double s12 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(config.center_lat_deg, config.center_lon_deg, r.lat_deg,
                                           r.lon_deg, s12);
  return s12;
}

/// An aircraft dead-reckoned from its sample to a common instant, in a local east/north
/// frame (metres) around the region's centre.
struct Snapshot {
  std::string id;
  double east_m, north_m, alt_ft;
};

/// One snapshot per aircraft for every radar period: each sample (taken at its own phase
/// within the period) is moved with its reported velocity to the middle of the period, at
/// most half a period away, which errs by metres.
std::vector<std::vector<Snapshot>> snapshots_per_period(const GeneratorConfig& config,
                                                        const std::vector<TrackReport>& records) {
  const auto periods = static_cast<std::size_t>(std::ceil(config.duration_s / config.period_s));
  std::vector<std::vector<Snapshot>> out(periods);
  const double cos_centre = std::cos(config.center_lat_deg * kDegToRad);
  for (const TrackReport& r : records) {
    const auto k = static_cast<std::size_t>((r.t - config.start_time) / config.period_s);
    if (k >= periods) continue;
    const double dt = config.start_time + (static_cast<double>(k) + 0.5) * config.period_s - r.t;
    const double speed = r.gs_kt.value() * kMpsPerKnot;
    const double track = r.trk_deg.value() * kDegToRad;
    out[k].push_back({r.id,
                      (r.lon_deg - config.center_lon_deg) * kDegToRad * kEarthRadiusM * cos_centre +
                          speed * std::sin(track) * dt,
                      (r.lat_deg - config.center_lat_deg) * kDegToRad * kEarthRadiusM + speed * std::cos(track) * dt,
                      r.alt_ft + r.vr_fpm.value() * dt / 60.0});
  }
  return out;
}

/// Calls f(a, b, horizontal metres) for every pair of one snapshot within `radius_m`
/// horizontally: all pairs, pruned exactly by a sweep over the north coordinate.
template <typename F>
void for_each_close_pair(std::vector<Snapshot>& snapshot, double radius_m, F f) {
  std::sort(snapshot.begin(), snapshot.end(), [](const Snapshot& a, const Snapshot& b) { return a.north_m < b.north_m; });
  for (std::size_t i = 0; i < snapshot.size(); ++i) {
    for (std::size_t j = i + 1; j < snapshot.size() && snapshot[j].north_m - snapshot[i].north_m < radius_m; ++j) {
      const double h = std::hypot(snapshot[j].east_m - snapshot[i].east_m, snapshot[j].north_m - snapshot[i].north_m);
      if (h < radius_m) f(snapshot[i], snapshot[j], h);
    }
  }
}

// ------------------------------------------------------------------ names, config

TEST(TrafficGenerator, ScenarioNamesRoundTrip) {
  for (const Scenario scenario : kAllScenarios) {
    EXPECT_EQ(kScenarioNames.parse(to_string(scenario)), scenario) << to_string(scenario);
    EXPECT_TRUE(kScenarioNames.contains(scenario));
  }
  EXPECT_EQ(kScenarioNames.entries().size(), std::size(kAllScenarios));
  EXPECT_EQ(to_string(Scenario::Tma), "tma");
  EXPECT_FALSE(kScenarioNames.parse("Airways"));
  EXPECT_FALSE(kScenarioNames.parse(""));
  EXPECT_FALSE(kScenarioNames.contains(static_cast<Scenario>(99)));
}

TEST(TrafficGenerator, InvalidConfigurationIsRejectedWithItsReason) {
  EXPECT_TRUE(validate(GeneratorConfig{}).empty());
  GeneratorConfig no_aircraft;
  no_aircraft.aircraft = 0;
  EXPECT_NE(validate(no_aircraft).find("aircraft"), std::string::npos);
  EXPECT_THROW(TrafficGenerator{no_aircraft}, std::invalid_argument);
  GeneratorConfig wide_jitter;
  wide_jitter.jitter_s = 2.0;  // more than 0.45 × 4 s: samples could swap order
  EXPECT_NE(validate(wide_jitter).find("jitter"), std::string::npos);
  GeneratorConfig nan_duration;
  nan_duration.duration_s = std::nan("");
  EXPECT_NE(validate(nan_duration).find("duration"), std::string::npos);
  GeneratorConfig certain_miss;
  certain_miss.missed_update_probability = 1.0;
  EXPECT_NE(validate(certain_miss).find("missed"), std::string::npos);
  GeneratorConfig polar;
  polar.center_lat_deg = 85;
  EXPECT_NE(validate(polar).find("latitude"), std::string::npos);
  // The global scenario needs a table with every aerodrome it flies to.
  GeneratorConfig global;
  global.scenario = Scenario::Global;
  EXPECT_EQ(validate(global), "the global scenario needs an aerodrome table");
  global.aerodromes = std::make_shared<const eligibility::AerodromeTable>(
      std::vector<eligibility::Aerodrome>{{"EGLL", 51.4706, -0.4619, 83}});
  EXPECT_EQ(validate(global), "the aerodrome table has no EGCC, an aerodrome of the global scenario");
  EXPECT_THROW(TrafficGenerator{global}, std::invalid_argument);
  global.aerodromes = kew_aerodromes();
  EXPECT_EQ(validate(global), "");
}

// ------------------------------------------------------------------ determinism

TEST(TrafficGenerator, SameConfigurationGivesIdenticalRecordsAndAnotherSeedDiffers) {
  GeneratorConfig config;
  config.aircraft = 300;
  config.duration_s = 60;
  config.termination_probability_per_hour = 60;  // replacements are part of the determinism
  const std::vector<TrackReport> first = generate(config);
  const std::vector<TrackReport> second = generate(config);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) ASSERT_TRUE(identical(first[i], second[i])) << "record " << i;

  config.seed = 2;
  const std::vector<TrackReport> other = generate(config);
  std::set<std::string> first_ids, other_ids;
  for (const TrackReport& r : first) first_ids.insert(r.id);
  for (const TrackReport& r : other) other_ids.insert(r.id);
  EXPECT_NE(first_ids, other_ids);
  ASSERT_FALSE(other.empty());
  EXPECT_FALSE(identical(first.front(), other.front()));
}

TEST(TrafficGenerator, SamplingTimesAndAddressesMatchTheirRecordedValues) {
  // Sample times, addresses and callsigns use integer arithmetic and IEEE-754 basic
  // operations only, so they are the same on every platform. These values were printed
  // by this implementation (kew-gen --scenario mixed --aircraft 100 --seed 1) and pin
  // them: a change here changes every recording generated from a seed.
  GeneratorConfig config;  // mixed, 100 aircraft, seed 1
  TrafficGenerator generator(config);
  TrackReport r;
  ASSERT_TRUE(generator.next(r));
  EXPECT_EQ(r.id, "35A3BA");
  EXPECT_EQ(r.callsign, "DUN5322");
  EXPECT_EQ(r.t, 1714400000.028);
  ASSERT_TRUE(generator.next(r));
  EXPECT_EQ(r.id, "A554FF");
  EXPECT_EQ(r.t, 1714400000.039);
}

TEST(TrafficGenerator, ScenariosWithOneSeedDoNotShareTheirSampling) {
  // Each scenario mixes itself into the seed: otherwise phases and misses, and with them
  // the record count, would be the same for every scenario.
  std::set<std::size_t> counts;
  for (const Scenario scenario : kAllScenarios) {
    GeneratorConfig config;
    config.scenario = scenario;
    config.aircraft = 200;
    config.duration_s = 120;
    config.seed = 3;
    config.aerodromes = kew_aerodromes();
    counts.insert(generate(config).size());
  }
  EXPECT_GE(counts.size(), 4u);
}

TEST(TrafficGenerator, SensorSettingsLeaveTheTrueTrajectoriesUnchanged) {
  GeneratorConfig clean = truth_config(Scenario::Mixed, 200, 60);
  GeneratorConfig noisy = clean;
  noisy.position_noise_m = 30;
  noisy.missed_update_probability = 0.1;
  const std::vector<TrackReport> truth = generate(clean);
  const std::vector<TrackReport> measured = generate(noisy);
  ASSERT_GT(measured.size(), truth.size() * 8 / 10);
  ASSERT_LT(measured.size(), truth.size());
  // Misses only remove records: every measured one is a true one, moved by the noise.
  std::map<std::pair<std::string, double>, const TrackReport*> by_sample;
  for (const TrackReport& r : truth) by_sample[{r.id, r.t}] = &r;
  const double max_offset_deg = 6 * 30.0 / 111'000.0 / std::cos(51.0 * kDegToRad) + 1e-6;  // 6σ bound
  int moved = 0;
  for (const TrackReport& r : measured) {
    const auto found = by_sample.find({r.id, r.t});
    ASSERT_NE(found, by_sample.end()) << r.id << " at " << r.t;
    EXPECT_LE(std::abs(r.lat_deg - found->second->lat_deg), max_offset_deg);
    EXPECT_LE(std::abs(r.lon_deg - found->second->lon_deg), max_offset_deg);
    EXPECT_EQ(r.alt_ft, found->second->alt_ft);
    EXPECT_EQ(r.gs_kt, found->second->gs_kt);
    if (r.lat_deg != found->second->lat_deg) ++moved;
  }
  EXPECT_GT(moved, static_cast<int>(measured.size()) * 9 / 10);
}

// ------------------------------------------------------------------ sampling

TEST(TrafficGenerator, TimesAreNonDecreasingInsideTheRunAndEachAircraftOncePerPeriod) {
  GeneratorConfig config;
  config.aircraft = 500;
  config.duration_s = 200;
  config.period_s = 4;
  config.jitter_s = 1.5;  // wide jitter: the merge must still order the records
  const std::vector<TrackReport> records = generate(config);
  ASSERT_FALSE(records.empty());
  std::map<std::string, double> last_time;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const TrackReport& r = records[i];
    ASSERT_GE(r.t, config.start_time);
    ASSERT_LT(r.t, config.start_time + config.duration_s);
    if (i > 0) {
      ASSERT_LE(records[i - 1].t, r.t) << "record " << i;
    }
    const auto [it, first] = last_time.emplace(r.id, r.t);
    if (!first) {
      // Consecutive samples of one aircraft: one period ± twice the jitter, or a multiple
      // after misses.
      EXPECT_GE(r.t - it->second, config.period_s - 2 * config.jitter_s - 0.002) << r.id;
      it->second = r.t;
    }
  }
}

TEST(TrafficGenerator, RecordCountFollowsPeriodAndMissProbability) {
  GeneratorConfig config = truth_config(Scenario::Random, 1000, 400);
  config.missed_update_probability = 0.1;
  TrafficGenerator generator(config);
  TrackReport r;
  std::uint64_t count = 0;
  while (generator.next(r)) ++count;
  EXPECT_EQ(count, generator.records_produced());
  // Without jitter each aircraft is due exactly 100 times in 400 s at P = 4 s (one phase
  // rounded up to the period's end at most drops a sample).
  const std::uint64_t samples = generator.records_produced() + generator.samples_missed();
  EXPECT_LE(samples, 100'000u);
  EXPECT_GE(samples, 99'990u);
  // Binomial(100,000, 0.1): mean 10,000, σ ≈ 95.
  EXPECT_NEAR(static_cast<double>(generator.samples_missed()), 10'000.0, 500.0);

  config.missed_update_probability = 0;
  EXPECT_EQ(generate(config).size(), samples);
}

TEST(TrafficGenerator, TerminatedAircraftAreReplacedByNewAddresses) {
  GeneratorConfig config = truth_config(Scenario::Airways, 400, 600);
  config.termination_probability_per_hour = 6;  // 0.4 expected early ends per slot
  TrafficGenerator generator(config);
  TrackReport r;
  std::set<std::string> ids;
  std::map<std::string, std::string> callsign_of;
  std::size_t live_at_end = 0;
  while (generator.next(r)) {
    ids.insert(r.id);
    const auto [it, first] = callsign_of.emplace(r.id, r.callsign);
    EXPECT_EQ(it->second, r.callsign) << r.id;
    if (r.t >= config.start_time + config.duration_s - config.period_s) ++live_at_end;
  }
  // Poisson(160) early ends plus natural ones (airway exits).
  EXPECT_GT(generator.aircraft_started(), config.aircraft + 100);
  EXPECT_LE(ids.size(), generator.aircraft_started());
  EXPECT_GE(ids.size(), generator.aircraft_started() * 99 / 100);
  // A slot is never empty: the last period still sees every slot.
  EXPECT_EQ(live_at_end, config.aircraft);
  std::set<std::string> callsigns;
  for (const auto& [id, callsign] : callsign_of) callsigns.insert(callsign);
  EXPECT_EQ(callsigns.size(), ids.size());
}

TEST(TrafficGenerator, PositionsOnlyWhenVelocityIsNotReported) {
  GeneratorConfig config;
  config.aircraft = 20;
  config.duration_s = 20;
  config.report_velocity = false;
  const std::vector<TrackReport> records = generate(config);
  ASSERT_FALSE(records.empty());
  for (const TrackReport& r : records) {
    EXPECT_FALSE(r.gs_kt.has_value());
    EXPECT_FALSE(r.trk_deg.has_value());
    EXPECT_FALSE(r.vr_fpm.has_value());
  }
}

TEST(TrafficGenerator, HundredThousandAircraftStartAtOnce) {
  GeneratorConfig config;
  config.aircraft = 100'000;
  config.duration_s = 600;
  TrafficGenerator generator(config);
  TrackReport r;
  std::set<std::string> ids;
  double last = config.start_time;
  for (int i = 0; i < 2000; ++i) {
    ASSERT_TRUE(generator.next(r));
    ASSERT_GE(r.t, last);
    last = r.t;
    ids.insert(r.id);
  }
  // 100,000 phases spread over 4 s: 2,000 samples span about 0.08 s, all distinct aircraft.
  EXPECT_LT(last, config.start_time + 0.3);
  EXPECT_EQ(ids.size(), 2000u);
  EXPECT_EQ(generator.aircraft_started(), config.aircraft);
}

// ------------------------------------------------------------------ scenarios

struct Envelope {
  double min_kt, max_kt, min_ft, max_ft;
};

Envelope envelope_of(Scenario scenario) {
  switch (scenario) {
    case Scenario::Random: return {250, 500, 10'000, 40'000};
    case Scenario::Airways: return {380, 580, 21'000, 42'000};  // overtakers fly up to 80 kt faster
    case Scenario::Stacks: return {210, 230, 3'000, 18'000};
    case Scenario::Tma: return {160, 480, 1'500, 38'000};
    // From 1,500 ft above the aerodromes (Amsterdam lies 11 ft below sea level) to FL410.
    case Scenario::Global: return {420, 500, 1'475, 41'000};
    case Scenario::Mixed:
    case Scenario::Calibrated: break;
  }
  return {160, 580, 1'500, 42'000};
}

/// A record (with its velocity) within the envelope: altitude, ground speed, a track in
/// [0, 360) and a vertical rate of at most 3000 ft/min.
void expect_within(const Envelope& envelope, const TrackReport& r) {
  EXPECT_GE(r.alt_ft, envelope.min_ft) << r.id;
  EXPECT_LE(r.alt_ft, envelope.max_ft) << r.id;
  EXPECT_GE(*r.gs_kt, envelope.min_kt) << r.id;
  EXPECT_LE(*r.gs_kt, envelope.max_kt) << r.id;
  EXPECT_GE(*r.trk_deg, 0.0);
  EXPECT_LT(*r.trk_deg, 360.0);
  EXPECT_LE(std::abs(*r.vr_fpm), 3000.0) << r.id;
}

class ScenarioTest : public ::testing::TestWithParam<Scenario> {};

TEST_P(ScenarioTest, ValuesArePlausible) {
  GeneratorConfig config;
  config.scenario = GetParam();
  config.aircraft = 400;
  config.duration_s = 300;
  const Envelope envelope = envelope_of(GetParam());
  const std::vector<TrackReport> records = generate(config);
  ASSERT_GT(records.size(), 400u * 70u);
  int level_changes = 0;
  for (const TrackReport& r : records) {
    ASSERT_EQ(r.id.size(), 6u);
    for (const char c : r.id) ASSERT_TRUE(std::isdigit(c) || (c >= 'A' && c <= 'F')) << r.id;
    ASSERT_NE(r.id, "000000");
    ASSERT_GE(r.callsign.size(), 4u);
    ASSERT_LE(r.callsign.size(), 7u);
    for (std::size_t i = 0; i < r.callsign.size(); ++i)
      ASSERT_TRUE(i < 3 ? std::isupper(r.callsign[i]) != 0 : std::isdigit(r.callsign[i]) != 0) << r.callsign;
    EXPECT_EQ(r.source, "gen");
    EXPECT_FALSE(r.on_ground);
    EXPECT_LE(distance_from_centre_m(config, r), config.radius_km * 1000 * 1.02) << r.id;
    EXPECT_EQ(std::fmod(r.alt_ft, 25.0), 0.0) << "Mode S altitude quantum";
    ASSERT_TRUE(r.gs_kt && r.trk_deg && r.vr_fpm);
    expect_within(envelope, r);
    if (*r.vr_fpm != 0) ++level_changes;
  }
  EXPECT_GT(level_changes, 100) << "some aircraft climb or descend";
}

TEST_P(ScenarioTest, ConflictsOccurNaturally) {
  // 2,000 aircraft for 300 s, true positions: pairs that come within 5 NM horizontally
  // and 1000 ft vertically at the same instant, all pairs examined at every period.
  const GeneratorConfig config = truth_config(GetParam(), 2000, 300);
  std::vector<std::vector<Snapshot>> periods = snapshots_per_period(config, generate(config));
  std::set<std::pair<std::string, std::string>> pairs;
  for (std::vector<Snapshot>& snapshot : periods) {
    for_each_close_pair(snapshot, 5 * kMetresPerNm, [&](const Snapshot& a, const Snapshot& b, double) {
      if (std::abs(a.alt_ft - b.alt_ft) < 1000) pairs.insert(std::minmax(a.id, b.id));
    });
  }
  EXPECT_GE(pairs.size(), 20u) << to_string(GetParam());
}

INSTANTIATE_TEST_SUITE_P(RegionalScenarios, ScenarioTest, ::testing::ValuesIn(kRegionalScenarios),
                         [](const ::testing::TestParamInfo<Scenario>& param_info) {
                           return std::string(to_string(param_info.param));
                         });

TEST(TrafficGenerator, CalibratedTrafficHasTheRecordingsShape) {
  // docs/performance.md, calibrated traffic: the controlled-airspace recordings put most records at FL300
  // and above, a tenth to a third below FL100, and 14–57 % climbing or descending; mixed
  // traffic puts a sixth in holding stacks, calibrated traffic one in a hundred.
  GeneratorConfig config;
  config.scenario = Scenario::Calibrated;
  config.aircraft = 1000;
  config.duration_s = 120;
  std::size_t high = 0, low = 0, changing = 0, holding_speed = 0;
  const std::vector<TrackReport> records = generate(config);
  for (const TrackReport& r : records) {
    if (r.alt_ft >= 30'000) ++high;
    if (r.alt_ft < 10'000) ++low;
    if (std::abs(*r.vr_fpm) >= 500) ++changing;
    if (*r.gs_kt >= 210 && *r.gs_kt <= 230 && *r.vr_fpm == 0 && r.alt_ft <= 18'000) ++holding_speed;
  }
  const auto share = [&](std::size_t n) { return static_cast<double>(n) / static_cast<double>(records.size()); };
  EXPECT_GT(share(high), 0.4);
  EXPECT_LT(share(high), 0.65);
  EXPECT_GT(share(low), 0.03);
  EXPECT_LT(share(low), 0.25);
  EXPECT_GT(share(changing), 0.1);
  EXPECT_LT(share(changing), 0.35);
  EXPECT_LT(share(holding_speed), 0.05);
}

// Where the arrivals reach the bottom of their descent (below 2,000 ft only within a few
// km of their terminal), grouped greedily into places at least 30 km apart.
std::size_t arrival_places(const GeneratorConfig& config) {
  std::vector<std::pair<double, double>> places;  // lat, lon of each place's first record
  for (const TrackReport& r : generate(config)) {
    if (r.alt_ft >= 2000) continue;
    const bool known = std::any_of(places.begin(), places.end(), [&](const auto& place) {
      double s12 = 0;
      GeographicLib::Geodesic::WGS84().Inverse(place.first, place.second, r.lat_deg, r.lon_deg, s12);
      return s12 < 30'000;
    });
    if (!known) places.emplace_back(r.lat_deg, r.lon_deg);
  }
  return places.size();
}

TEST(TrafficGenerator, CalibratedArrivalsGoToSeveralTerminals) {
  // One terminal per 50 arrivals (replay/README.md): 1,000 aircraft, 200 arrivals, four
  // terminals, where the tma scenario sends every arrival to the centre.
  EXPECT_GE(arrival_places(truth_config(Scenario::Calibrated, 1000, 600)), 3u);
  EXPECT_EQ(arrival_places(truth_config(Scenario::Tma, 200, 600)), 1u);
}

TEST(TrafficGenerator, StacksPutManyLevelsOverOneGroundPoint) {
  // At some instant at least 5 aircraft lie within 1 km of one of them (so within 2 km of
  // each other), each at its own level.
  const GeneratorConfig config = truth_config(Scenario::Stacks, 240, 60);
  std::vector<std::vector<Snapshot>> periods = snapshots_per_period(config, generate(config));
  std::size_t largest_column = 0;
  for (std::vector<Snapshot>& snapshot : periods) {
    std::map<std::string, std::set<long>> levels_near;  // aircraft → levels within 1 km
    for (const Snapshot& s : snapshot) levels_near[s.id].insert(std::lround(s.alt_ft / 1000));
    for_each_close_pair(snapshot, 1000, [&](const Snapshot& a, const Snapshot& b, double) {
      levels_near[a.id].insert(std::lround(b.alt_ft / 1000));
      levels_near[b.id].insert(std::lround(a.alt_ft / 1000));
    });
    for (const auto& [id, levels] : levels_near) largest_column = std::max(largest_column, levels.size());
  }
  EXPECT_GE(largest_column, 5u);
}

TEST(TrafficGenerator, TmaArrivalsConvergeAndSlowDown) {
  const GeneratorConfig config = truth_config(Scenario::Tma, 300, 240);
  const std::vector<TrackReport> records = generate(config);
  std::map<std::string, const TrackReport*> previous;
  int closer = 0, farther = 0, slower = 0, faster = 0;
  for (const TrackReport& r : records) {
    const auto found = previous.find(r.id);
    if (found != previous.end()) {
      const TrackReport& p = *found->second;
      (distance_from_centre_m(config, r) < distance_from_centre_m(config, p) ? closer : farther)++;
      if (*r.gs_kt < *p.gs_kt) ++slower;
      if (*r.gs_kt > *p.gs_kt) ++faster;
      EXPECT_LE(r.alt_ft, p.alt_ft + 1e-6) << r.id << " arrivals never climb";
    }
    previous[r.id] = &r;
  }
  EXPECT_EQ(farther, 0);
  EXPECT_GT(closer, 10'000);
  EXPECT_GT(slower, 1000);
  EXPECT_EQ(faster, 0);
}

// ------------------------------------------------------------------ aerodromes

TEST(Airports, TheSelectionIsValidAndSpreadOverEveryContinent) {
  const std::vector<Airport> airports = world_airports(*kew_aerodromes());
  ASSERT_EQ(airports.size(), selected_airports().size());
  EXPECT_GE(airports.size(), 150u);
  EXPECT_LE(airports.size(), 250u);
  std::set<std::string_view> codes;
  std::map<Continent, int> per_continent;
  int arctic = 0;
  for (const Airport& a : airports) {
    ASSERT_EQ(a.ident.size(), 4u);
    for (const char c : a.ident) EXPECT_TRUE(c >= 'A' && c <= 'Z') << a.ident;
    EXPECT_TRUE(codes.insert(a.ident).second) << a.ident << " twice";
    EXPECT_TRUE(in_range(a.lat_deg, -90, 90)) << a.ident;
    EXPECT_TRUE(in_range(a.lon_deg, -180, 180)) << a.ident;
    EXPECT_TRUE(in_range(a.elevation_ft, -100, 14'000)) << a.ident;  // Amsterdam (−11 ft) to La Paz
    ++per_continent[a.continent];
    if (a.lat_deg >= 70) ++arctic;
  }
  for (const Continent continent : {Continent::Africa, Continent::Antarctica, Continent::Asia, Continent::Europe,
                                    Continent::NorthAmerica, Continent::Oceania, Continent::SouthAmerica}) {
    EXPECT_GE(per_continent[continent], 4) << static_cast<int>(continent);
  }
  EXPECT_GE(arctic, 8);
}

TEST(Airports, TheTableFindsTheAerodromesTheSelectionMeans) {
  // Aerodrome reference points and elevations as published (AIPs), one per hemisphere pair
  // at least, the ones either side of the antimeridian and the polar ones: the table's
  // figures (runway thresholds' centre, highest threshold) lie within 3 km and 60 ft of
  // them, so each ident names the aerodrome the selection means.
  struct Known {
    std::string_view ident;
    double lat_deg, lon_deg, elevation_ft;
  };
  const Known known[] = {
      {"EGLL", 51.47, -0.46, 83},      {"KJFK", 40.64, -73.78, 13},    {"RJTT", 35.55, 139.78, 35},
      {"YSSY", -33.95, 151.18, 21},    {"SCCI", -53.00, -70.85, 139},  {"NZCH", -43.49, 172.53, 123},
      {"PHNL", 21.32, -157.92, 13},    {"NFFN", -17.76, 177.44, 59},   {"NTAA", -17.55, -149.61, 5},
      {"BGTL", 76.53, -68.70, 251},    {"ENSB", 78.25, 15.47, 88},     {"PABR", 71.29, -156.77, 44},
      {"UHMA", 64.74, 177.74, 194},    {"FAOR", -26.14, 28.25, 5558},  {"SBGR", -23.44, -46.47, 2459},
      {"SLLP", -16.51, -68.19, 13325}, {"NZSP", -90.00, 0.00, 9300},   {"SPIM", -12.02, -77.11, 113},
  };
  const std::vector<Airport> airports = world_airports(*kew_aerodromes());
  for (const Known& k : known) {
    const auto found = std::find_if(airports.begin(), airports.end(), [&](const Airport& a) { return a.ident == k.ident; });
    ASSERT_NE(found, airports.end()) << k.ident;
    double distance_m = 0;
    GeographicLib::Geodesic::WGS84().Inverse(found->lat_deg, found->lon_deg, k.lat_deg, k.lon_deg, distance_m);
    EXPECT_LE(distance_m, 3000) << k.ident;
    EXPECT_NEAR(found->elevation_ft, k.elevation_ft, 60) << k.ident;
  }
}

TEST(Airports, TheGeneratorAndTheLowerLimitStandOnTheSameElevations) {
  // kew-gen's flights start and end above the aerodromes the lower limit of alerting stands
  // on: for every aerodrome of the global scenario, the elevation the generator uses is the
  // one lower_limit_at() reads there, from one table (the default configuration's).
  const config::SharedConfig shared = config::default_shared_config();
  eligibility::EligibilityConfig eligibility = shared.pipeline.eligibility;
  eligibility.lower_limit_ft = 0.0;  // so that every aerodrome's height sets the limit
  const eligibility::Rules rules(eligibility, shared.pipeline.minima);
  GeneratorConfig global;
  global.scenario = Scenario::Global;
  global.aerodromes = shared.pipeline.eligibility.aerodromes;
  ASSERT_EQ(validate(global), "");
  for (const Airport& a : world_airports(*global.aerodromes)) {
    const eligibility::Aerodrome* at = nullptr;
    const double limit_ft = rules.lower_limit_at(a.lat_deg, a.lon_deg, &at);
    ASSERT_NE(at, nullptr) << a.ident;
    EXPECT_EQ(at->ident, a.ident);
    EXPECT_EQ(limit_ft, a.elevation_ft + eligibility.aerodrome_height_ft) << a.ident;
    EXPECT_EQ(at->elevation_ft, a.elevation_ft) << a.ident;
  }
}

// ------------------------------------------------------------------ global

TEST(TrafficGenerator, GlobalIsDeterministicAndIgnoresTheRegion) {
  GeneratorConfig config;
  config.scenario = Scenario::Global;
  config.aerodromes = kew_aerodromes();
  config.aircraft = 500;
  config.duration_s = 120;
  config.termination_probability_per_hour = 30;  // replacements departing from the aerodromes
  const std::vector<TrackReport> first = generate(config);
  ASSERT_GT(first.size(), 500u * 25u);
  // No region: a centre and a radius out of every other scenario's range are neither
  // refused nor used.
  config.center_lat_deg = 89;
  config.center_lon_deg = -170;
  config.radius_km = 5;
  EXPECT_EQ(validate(config), "");
  const std::vector<TrackReport> second = generate(config);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) ASSERT_TRUE(identical(first[i], second[i])) << "record " << i;
}

TEST(TrafficGenerator, GlobalValuesArePlausible) {
  GeneratorConfig config;
  config.scenario = Scenario::Global;
  config.aerodromes = kew_aerodromes();
  config.aircraft = 2000;
  config.duration_s = 120;
  const Envelope envelope = envelope_of(Scenario::Global);
  TrafficGenerator generator(config);
  TrackReport r;
  std::size_t records = 0, cruising = 0, climbing = 0, descending = 0;
  while (generator.next(r)) {
    ++records;
    ASSERT_TRUE(in_range(r.lat_deg, -90, 90)) << r.id << " " << r.lat_deg;
    ASSERT_TRUE(in_range(r.lon_deg, -180, 180)) << r.id << " " << r.lon_deg;
    ASSERT_TRUE(r.gs_kt && r.trk_deg && r.vr_fpm);
    expect_within(envelope, r);
    if (r.alt_ft >= 29'000 && *r.vr_fpm == 0) {
      ++cruising;
      // Semicircular levels: whole thousands of feet from FL290.
      EXPECT_EQ(std::fmod(r.alt_ft, 1000.0), 0.0) << r.id;
    }
    if (*r.vr_fpm > 0) ++climbing;
    if (*r.vr_fpm < 0) ++descending;
  }
  // Spread along their routes from the start, not all departing: most cruise, and some
  // climb and descend near the aerodromes.
  const auto share = [&](std::size_t n) { return static_cast<double>(n) / static_cast<double>(records); };
  EXPECT_GT(share(cruising), 0.7);
  EXPECT_GT(share(climbing), 0.01);
  EXPECT_GT(share(descending), 0.01);
  EXPECT_GT(generator.aircraft_started(), config.aircraft) << "flights reaching their destination are replaced";
}

TEST(TrafficGenerator, GlobalNoiseMovesPositionsByTheRightDistanceAtThePoles) {
  // Near a pole a step east is no change of longitude alone (at the pole, none at all): the
  // noisy positions must stay within ±90° and ±180° and lie as far from the true ones as
  // the noise says, up to 6σ east and north, and with a mean square of 2σ². 20,000
  // aircraft put a few within 0.6° of a pole (three samples each, 10 s apart), where the
  // largest noise allowed (σ = 10 km) reaches across the pole.
  GeneratorConfig clean = truth_config(Scenario::Global, 20'000, 30);
  clean.period_s = 10;
  GeneratorConfig noisy = clean;
  noisy.position_noise_m = 10'000;
  std::map<std::pair<std::string, double>, std::pair<double, double>> truth;
  {
    TrafficGenerator generator(clean);
    TrackReport r;
    while (generator.next(r)) truth[{r.id, r.t}] = {r.lat_deg, r.lon_deg};
  }
  TrafficGenerator generator(noisy);
  TrackReport r;
  std::size_t in_caps = 0, near_poles = 0;
  double squares_in_caps = 0;
  while (generator.next(r)) {
    ASSERT_TRUE(in_range(r.lat_deg, -90, 90)) << r.id << " " << r.lat_deg;
    ASSERT_TRUE(in_range(r.lon_deg, -180, 180)) << r.id << " " << r.lon_deg;
    const auto found = truth.find({r.id, r.t});
    ASSERT_NE(found, truth.end()) << r.id << " at " << r.t;
    const auto [lat, lon] = found->second;
    double distance = 0;
    GeographicLib::Geodesic::WGS84().Inverse(lat, lon, r.lat_deg, r.lon_deg, distance);
    EXPECT_LE(distance, 6 * std::sqrt(2.0) * noisy.position_noise_m) << r.id << " at " << lat << ", " << lon;
    if (std::abs(lat) > 85) {
      ++in_caps;
      squares_in_caps += distance * distance;
    }
    if (std::abs(lat) > 89.4) ++near_poles;
  }
  EXPECT_GE(near_poles, 5u);
  ASSERT_GE(in_caps, 200u);
  const double sigma2 = noisy.position_noise_m * noisy.position_noise_m;
  EXPECT_NEAR(squares_in_caps / static_cast<double>(in_caps) / (2 * sigma2), 1.0, 0.2);
}

TEST(TrafficGenerator, GlobalTrafficFliesThePolesTheOceansAndTheAntimeridian) {
  const GeneratorConfig config = truth_config(Scenario::Global, 2000, 600);
  TrafficGenerator generator(config);
  TrackReport r;
  std::map<std::string, double> last_lon;
  std::set<std::string> polar, north_atlantic, north_pacific, crossing;
  while (generator.next(r)) {
    if (r.lat_deg > 80) polar.insert(r.id);
    if (r.lat_deg >= 30 && r.lat_deg <= 50 && r.lon_deg >= -50 && r.lon_deg <= -20) north_atlantic.insert(r.id);
    if (r.lat_deg >= 10 && r.lat_deg <= 40 && (r.lon_deg >= 165 || r.lon_deg <= -165)) north_pacific.insert(r.id);
    const auto [it, first] = last_lon.emplace(r.id, r.lon_deg);
    // One aircraft's consecutive records either side of ±180°: a crossing, not a jump.
    if (!first && ((it->second > 170 && r.lon_deg < -170) || (it->second < -170 && r.lon_deg > 170))) {
      crossing.insert(r.id);
    }
    it->second = r.lon_deg;
  }
  EXPECT_GE(polar.size(), 10u);
  EXPECT_GE(north_atlantic.size(), 10u);
  EXPECT_GE(north_pacific.size(), 5u);
  EXPECT_GE(crossing.size(), 3u);
}

TEST(TrafficGenerator, GlobalSpeedsAndTracksAgreeWithTheGeodesicsFlown) {
  // Consecutive true samples of one aircraft lie on its geodesic: their distance over
  // their time is its ground speed, and the geodesic between them sets out on its track.
  // A longitude jump at the antimeridian or a wrong azimuth near a pole shows here.
  const GeneratorConfig config = truth_config(Scenario::Global, 2000, 300);
  TrafficGenerator generator(config);
  TrackReport r;
  std::map<std::string, TrackReport> previous;
  std::size_t pairs = 0, near_pole = 0, across_antimeridian = 0;
  while (generator.next(r)) {
    const auto found = previous.find(r.id);
    if (found != previous.end()) {
      const TrackReport& p = found->second;
      double distance = 0, azimuth1 = 0, azimuth2 = 0;
      GeographicLib::Geodesic::WGS84().Inverse(p.lat_deg, p.lon_deg, r.lat_deg, r.lon_deg, distance, azimuth1,
                                               azimuth2);
      const double speed_kt = distance / (r.t - p.t) / kMpsPerKnot;
      // 1 ms time rounding over 4 s and 0.1 kt speed rounding: a few tenths of a knot.
      EXPECT_NEAR(speed_kt, *r.gs_kt, 0.5) << r.id << " at " << r.lat_deg << ", " << r.lon_deg;
      const double track_error = std::remainder(azimuth1 - *p.trk_deg, 360.0);
      EXPECT_NEAR(track_error, 0.0, 0.05) << r.id << " at " << p.lat_deg << ", " << p.lon_deg;
      ++pairs;
      if (std::abs(r.lat_deg) > 85) ++near_pole;
      if (std::abs(r.lon_deg - p.lon_deg) > 180) ++across_antimeridian;
    }
    previous[r.id] = r;
  }
  EXPECT_GT(pairs, 2000u * 70u);
  EXPECT_GT(near_pole, 100u);
  EXPECT_GE(across_antimeridian, 1u);
}

}  // namespace
}  // namespace kew::replay
