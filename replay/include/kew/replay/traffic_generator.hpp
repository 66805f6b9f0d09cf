#pragma once
// Synthetic radar traffic for tests, benchmarks and `kew-gen` (design §5.6).
//
// A fixed number of aircraft "slots" fly scenario-specific paths (great circles on
// WGS84, holding racetracks, converging arrivals, routes between the world's
// aerodromes) and are sampled like a radar: every slot is seen once per period at its
// own phase, with jitter, position and altitude noise, and missed updates. Records come
// out one at a time in non-decreasing time order (a heap merges the slots' sample
// times), so 100,000 aircraft for an hour never need more than one pending sample per
// aircraft in memory. See replay/README.md for the scenarios and the sampling model.
//
// Determinism: the same GeneratorConfig gives the same records, bit for bit, on the same
// platform. Every random draw uses only integer arithmetic and IEEE-754 basic operations
// (SplitMix64 streams seeded from std::mt19937_64, an Irwin–Hall Gaussian), so the draws
// are identical everywhere; positions go through GeographicLib and the C library's
// sin/cos, and outputs are rounded (1e-7°, 1 ms, 25 ft, 0.1 kt, 0.01°, 1 ft/min), so
// other platforms give the same records unless a value lies within a last-bit
// difference of a rounding boundary. The scenario is mixed into the seed, so scenarios
// run with one seed do not share their sampling draws. Each aircraft's true path comes
// from its own random stream, separate from the measurement stream (phase, jitter,
// noise, misses), so changing only the noise or sampling settings leaves the true
// trajectories unchanged.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "kew/eligibility/aerodromes.hpp"
#include "kew/track/track_report.hpp"
#include "kew/util/name_table.hpp"

namespace kew::replay {

enum class Scenario {
  Random,   ///< uniform positions and headings in the region, FL100–FL400
  Airways,  ///< crossing great-circle routes, both directions, semicircular levels
  Stacks,   ///< holding racetracks, one aircraft per level, 1000 ft apart
  Tma,      ///< arrivals converging on the region centre, descending and slowing
  Mixed,    ///< each aircraft drawn from the four above
  /// Shaped like the shared recordings of controlled airspace (docs/performance.md, calibrated traffic):
  /// cruise on airways with route-allocated levels, lower traffic climbing and
  /// descending on semicircular levels, TMA arrivals, a few small holding stacks.
  Calibrated,
  /// Worldwide: great-circle routes between 240 real aerodromes (kew/replay/airports.hpp,
  /// their figures from GeneratorConfig::aerodromes),
  /// regional and long-haul, over the oceans, the polar caps and the antimeridian, at
  /// semicircular levels FL290–FL410, 420–500 kt. No region: center and radius are unused.
  Global,
};

/// The names of `kew-gen --scenario` (exact, lower case).
inline constexpr util::NameTable<Scenario, 7> kScenarioNames({{
    {Scenario::Random, "random"},
    {Scenario::Airways, "airways"},
    {Scenario::Stacks, "stacks"},
    {Scenario::Tma, "tma"},
    {Scenario::Mixed, "mixed"},
    {Scenario::Calibrated, "calibrated"},
    {Scenario::Global, "global"},
}});
constexpr std::string_view to_string(Scenario scenario) { return kScenarioNames.name(scenario); }

struct GeneratorConfig {
  Scenario scenario = Scenario::Mixed;
  /// Aircraft airborne at every instant (a terminated one is replaced), 1 to 1,000,000.
  std::size_t aircraft = 100;
  /// Records are produced for start_time ≤ t < start_time + duration_s; (0, 30 days].
  double duration_s = 600;
  /// Any value; 0 is a valid seed.
  std::uint64_t seed = 1;
  /// Radar sampling period, seconds in [0.1, 3600]. Each aircraft is seen once per
  /// period at its own phase (as if at its own antenna azimuth).
  double period_s = 4.0;
  /// Each sample time moves by a uniform offset in [−jitter_s, +jitter_s];
  /// seconds in [0, 0.45·period_s] so an aircraft's samples never swap order.
  double jitter_s = 0.05;
  /// Gaussian σ of the reported position, metres, independently east and north;
  /// [0, 10,000]. The Gaussian is Irwin–Hall (sum of 12 uniforms): bounded at ±6σ.
  double position_noise_m = 30.0;
  /// Gaussian σ of the reported altitude before quantisation, feet, [0, 5,000].
  double altitude_noise_ft = 0.0;
  /// Reported altitudes are rounded to this step, feet, [0, 1000]; 25 like Mode S
  /// (100 for Mode C); 0 keeps 0.01 ft resolution.
  double altitude_quantum_ft = 25.0;
  /// Probability that a sample is not reported, [0, 1).
  double missed_update_probability = 0.02;
  /// Rate of tracks ending early (e.g. leaving coverage), per aircraft per hour,
  /// [0, 3600]. Whenever an aircraft ends — early or at the natural end of its path
  /// (leaving the region, landing, the end of a descent out of a stack) — a new aircraft
  /// with a new address takes its place at once, so `aircraft` stay airborne.
  double termination_probability_per_hour = 0.0;
  /// UTC seconds of the start of the first radar period; finite, ≥ 0.
  double start_time = 1714400000.0;
  /// Centre of the region (WGS84 degrees): latitude in [−80, 80], longitude in
  /// [−180, 180]. TMA arrivals converge on it. Not used, nor checked, by Scenario::Global.
  double center_lat_deg = 50.0;
  double center_lon_deg = 8.0;
  /// Radius of the region, km in [20, 2000]. Not used, nor checked, by Scenario::Global.
  double radius_km = 400;
  /// Records carry gs_kt, trk_deg and vr_fpm (the true velocity) when true; positions
  /// only when false.
  bool report_velocity = true;
  /// The aerodrome table Scenario::Global takes its aerodromes' positions and elevations
  /// from (kew-gen: that of its configuration, [eligibility] aerodromes_file), so that its
  /// flights start and end where the lower limit of alerting stands. Global needs one that
  /// holds every aerodrome of the selection (selected_airports()); the others ignore it.
  std::shared_ptr<const eligibility::AerodromeTable> aerodromes;
};

/// Empty when `config` is valid, otherwise a message naming the first field out of range.
std::string validate(const GeneratorConfig& config);

class TrafficGenerator {
 public:
  /// Lays out the scenario and places every aircraft at start_time. Throws
  /// std::invalid_argument with validate()'s message when the config is invalid.
  explicit TrafficGenerator(const GeneratorConfig& config);
  ~TrafficGenerator();
  TrafficGenerator(TrafficGenerator&&) noexcept;
  TrafficGenerator& operator=(TrafficGenerator&&) noexcept;
  TrafficGenerator(const TrafficGenerator&) = delete;
  TrafficGenerator& operator=(const TrafficGenerator&) = delete;

  /// The next record, in non-decreasing `t` (ties in a fixed order). Returns false, and
  /// leaves `out` unchanged, once every record of the run has been produced.
  /// Records: id = 6 upper-case hex digits (a pseudo 24-bit address, unique for the
  /// first 16,777,215 aircraft of a run), source "gen", callsign 3 letters + 1–4
  /// digits derived from the address, on_ground false, mode3a and address absent,
  /// coasting and track_end false.
  bool next(TrackReport& out);

  /// Aircraft that have existed so far: the initial `aircraft`, plus one per
  /// replacement made up to the time of the last record.
  std::size_t aircraft_started() const;
  /// Records produced so far.
  std::uint64_t records_produced() const;
  /// Samples dropped by missed_update_probability so far.
  std::uint64_t samples_missed() const;

  const GeneratorConfig& config() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kew::replay
