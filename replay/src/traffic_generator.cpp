// Radar-like sampling of generated traffic; described in traffic_generator.hpp and
// replay/README.md.
#include "kew/replay/traffic_generator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <GeographicLib/Math.hpp>

#include "generator/airspace.hpp"
#include "kew/replay/airports.hpp"
#include "generator/flight.hpp"
#include "generator/random_stream.hpp"

namespace kew::replay {
namespace {

using detail::Airspace;
using detail::Flight;
using detail::FlightKind;
using detail::RandomStream;
using detail::SlotPlan;

// Shares of random, airways, stacks and TMA traffic (in FlightKind order).
using KindShares = std::array<double, 4>;
constexpr KindShares kMixedShares = {0.25, 0.40, 0.15, 0.20};
// Calibrated (docs/performance.md, calibrated traffic): two thirds cruise on airways, a fifth arrives in
// the TMA, the rest climbs or descends below the airways, and stacks are rare (one
// holding aircraft in a hundred, not a sixth of the sky).
constexpr KindShares kCalibratedShares = {0.15, 0.64, 0.01, 0.20};

FlightKind draw_kind(const KindShares& shares, RandomStream& kinds) {
  double u = kinds.uniform();
  std::size_t k = 0;
  while (k + 1 < shares.size() && u >= shares[k]) u -= shares[k++];
  return static_cast<FlightKind>(k);
}

constexpr std::uint32_t kAddressMask = 0xFFFFFF;

/// A bijection of the 24-bit integers (add, multiply by odd, xor-shift: each invertible),
/// so serial numbers map to distinct, scattered addresses.
std::uint32_t scramble24(std::uint32_t x, std::uint32_t key) {
  x = (x + key) & kAddressMask;
  x = (x * 0x5BD1E9u) & kAddressMask;
  x ^= x >> 13;
  x = (x * 0x2C9277u + 0x1B873u) & kAddressMask;
  x ^= x >> 11;
  return x;
}

/// Pseudo 24-bit address of the aircraft with this serial number. The address 000000
/// is not valid (ICAO Annex 10), so the one serial that would get it takes the address
/// of serial 2²⁴−1 instead: unique for the first 2²⁴−1 aircraft.
std::uint32_t address_of(std::uint64_t serial, std::uint32_t key) {
  const auto s = static_cast<std::uint32_t>(serial & kAddressMask);
  const std::uint32_t address = scramble24(s, key);
  return address != 0 ? address : scramble24(kAddressMask, key);
}

/// Callsign derived from the address, so it is unique too: 3 letters from the address's
/// high part (multiplied by a number prime to 26³ to spread them) and its last 4 decimal
/// digits without leading zeros.
void write_callsign(std::uint32_t address, std::string& out) {
  const std::uint32_t letters = (address / 10000 * 7919u) % (26u * 26u * 26u);
  char text[8] = {static_cast<char>('A' + letters / 676), static_cast<char>('A' + letters / 26 % 26),
                  static_cast<char>('A' + letters % 26)};
  std::size_t length = 3;
  std::uint32_t number = address % 10000;
  char digits[4];
  std::size_t count = 0;
  do {
    digits[count++] = static_cast<char>('0' + number % 10);
    number /= 10;
  } while (number != 0);
  while (count > 0) text[length++] = digits[--count];
  out.assign(text, length);
}

void write_address(std::uint32_t address, std::string& out) {
  constexpr std::string_view kHex = "0123456789ABCDEF";
  char text[6];
  for (int i = 5; i >= 0; --i, address >>= 4) text[i] = kHex[address & 0xF];
  out.assign(text, 6);
}

double round_to(double value, double step) { return std::round(value / step) * step + 0.0; }

/// Rounds to a multiple of 10^-digits through the decimal scale (so 1e-7 gives the
/// nearest double to a 7-decimal number, which prints short). + 0.0 turns −0 into 0.
double round_decimals(double value, double scale) { return std::round(value * scale) / scale + 0.0; }

bool in_range(double value, double lo, double hi) { return std::isfinite(value) && value >= lo && value <= hi; }

/// Seed of the master generator: the user's seed mixed with the scenario. Without the
/// scenario, every scenario run with one seed would share its sampling draws (phases,
/// jitter, misses) and so give exactly the same record count. For one scenario the
/// mapping is a bijection of the 64-bit seeds (xor, then SplitMix64's bijective step).
std::uint64_t master_seed(std::uint64_t seed, Scenario scenario) {
  const auto salt = (static_cast<std::uint64_t>(scenario) + 1) * 0xD1B54A32D192ED03ULL;
  return RandomStream(seed ^ salt).bits();
}

}  // namespace

std::string validate(const GeneratorConfig& c) {
  if (!kScenarioNames.contains(c.scenario)) return "unknown scenario";
  if (c.aircraft < 1 || c.aircraft > 1'000'000) return fmt::format("aircraft must be 1 to 1,000,000 (got {})", c.aircraft);
  if (!in_range(c.duration_s, 0, 30 * 86400.0) || c.duration_s == 0)
    return fmt::format("duration must be > 0 and at most 30 days (got {} s)", c.duration_s);
  if (!in_range(c.period_s, 0.1, 3600)) return fmt::format("period must be 0.1 to 3600 s (got {})", c.period_s);
  if (!in_range(c.jitter_s, 0, 0.45 * c.period_s))
    return fmt::format("jitter must be 0 to 0.45 × period = {} s (got {})", 0.45 * c.period_s, c.jitter_s);
  if (!in_range(c.position_noise_m, 0, 10'000))
    return fmt::format("position noise must be 0 to 10000 m (got {})", c.position_noise_m);
  if (!in_range(c.altitude_noise_ft, 0, 5'000))
    return fmt::format("altitude noise must be 0 to 5000 ft (got {})", c.altitude_noise_ft);
  if (!in_range(c.altitude_quantum_ft, 0, 1'000))
    return fmt::format("altitude quantum must be 0 to 1000 ft (got {})", c.altitude_quantum_ft);
  if (!in_range(c.missed_update_probability, 0, 1) || c.missed_update_probability == 1)
    return fmt::format("missed update probability must be in [0, 1) (got {})", c.missed_update_probability);
  if (!in_range(c.termination_probability_per_hour, 0, 3600))
    return fmt::format("termination rate must be 0 to 3600 per hour (got {})", c.termination_probability_per_hour);
  if (!in_range(c.start_time, 0, 1e11)) return fmt::format("start time must be 0 to 1e11 s (got {})", c.start_time);
  if (c.scenario == Scenario::Global) {  // flies the whole world: no region to check, but its aerodromes
    if (!c.aerodromes) return "the global scenario needs an aerodrome table";
    try {
      world_airports(*c.aerodromes);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return {};
  }
  if (!in_range(c.center_lat_deg, -80, 80))
    return fmt::format("centre latitude must be -80 to 80 degrees (got {})", c.center_lat_deg);
  if (!in_range(c.center_lon_deg, -180, 180))
    return fmt::format("centre longitude must be -180 to 180 degrees (got {})", c.center_lon_deg);
  if (!in_range(c.radius_km, 20, 2000)) return fmt::format("radius must be 20 to 2000 km (got {})", c.radius_km);
  return {};
}

// ------------------------------------------------------------------------ Impl

class TrafficGenerator::Impl {
 public:
  explicit Impl(const GeneratorConfig& config);
  bool next(TrackReport& out);

  GeneratorConfig config;
  std::uint64_t aircraft_started = 0;
  std::uint64_t records = 0;
  std::uint64_t missed = 0;

 private:
  /// One aircraft at a time: when it ends, its successor takes the slot.
  struct Slot {
    SlotPlan plan;
    RandomStream path;         // everything about the true trajectories
    RandomStream sensor;       // phase, jitter, noise, misses
    double phase_s = 0;        // offset of its samples in the radar period, [0, period)
    std::uint64_t serial = 0;  // of the current aircraft
    Flight flight;
  };
  /// The random part of one radar sample: its errors in units of their σ.
  struct Measurement {
    bool missed = false;
    double north_sigmas = 0, east_sigmas = 0, altitude_sigmas = 0;
  };
  struct Pending {
    double t;
    std::uint32_t slot;
    // Earliest first, then lowest slot: a total order, so ties come out the same every run.
    bool operator>(const Pending& other) const {
      return t > other.t || (t == other.t && slot > other.slot);
    }
  };

  std::vector<SlotPlan> plan_slots(std::mt19937_64& master) const;
  void start_flight(Slot& slot, Flight flight);
  /// Nominal (unjittered) time of the next sample of the phase-ordered stream.
  double stream_nominal() const;
  /// Moves the next sample of the stream into the heap of pending samples.
  void take_from_stream();
  void fill(const Slot& slot, double t, const Measurement& measurement, TrackReport& out);

  std::unique_ptr<Airspace> airspace_;  // flights point into it: never moved
  std::vector<Slot> slots_;             // in order of phase
  // Samples in the order of their nominal times (period after period, slots by phase)
  // are almost sorted: jitter moves each by at most jitter_s. So only the samples whose
  // nominal time is within that margin of the earliest pending one wait in a heap (a few
  // thousand at 100,000 aircraft, in cache), not one per aircraft.
  std::uint64_t stream_period_ = 0;
  std::size_t stream_slot_ = 0;
  bool stream_done_ = false;
  double stream_margin_s_;  // jitter plus the millisecond rounding of sample times
  std::vector<Pending> heap_;
  double end_time_;
  std::uint32_t address_key_;
};

TrafficGenerator::Impl::Impl(const GeneratorConfig& c)
    : config(c), stream_margin_s_(c.jitter_s + 1e-3), end_time_(c.start_time + c.duration_s) {
  std::mt19937_64 master(master_seed(c.seed, c.scenario));
  address_key_ = static_cast<std::uint32_t>(master() & kAddressMask);
  RandomStream layout(master());
  std::vector<SlotPlan> plans = plan_slots(master);
  airspace_ = std::make_unique<Airspace>(c, plans, layout);

  slots_.resize(plans.size());
  const Flight* last_airway = nullptr;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    Slot& slot = slots_[i];
    slot.plan = plans[i];
    slot.path = RandomStream(master());
    slot.sensor = RandomStream(master());
    slot.phase_s = slot.sensor.uniform(0, c.period_s);
    start_flight(slot, airspace_->initial(slot.plan, c.start_time, slot.path, last_airway));
    if (slot.plan.kind == FlightKind::Airways && !slot.flight.in_trail) last_airway = &slot.flight;
  }
  // Ties of equal phase keep the slot order (stable), so the order is reproducible.
  std::stable_sort(slots_.begin(), slots_.end(),
                   [](const Slot& a, const Slot& b) { return a.phase_s < b.phase_s; });
}

std::vector<SlotPlan> TrafficGenerator::Impl::plan_slots(std::mt19937_64& master) const {
  RandomStream kinds(master());
  std::vector<SlotPlan> plans(config.aircraft);
  std::uint32_t stack_slots = 0;
  for (SlotPlan& plan : plans) {
    switch (config.scenario) {
      case Scenario::Random: plan.kind = FlightKind::Random; break;
      case Scenario::Airways: plan.kind = FlightKind::Airways; break;
      case Scenario::Stacks: plan.kind = FlightKind::Stacks; break;
      case Scenario::Tma: plan.kind = FlightKind::Tma; break;
      case Scenario::Mixed: plan.kind = draw_kind(kMixedShares, kinds); break;
      case Scenario::Calibrated: plan.kind = draw_kind(kCalibratedShares, kinds); break;
      case Scenario::Global: plan.kind = FlightKind::Global; break;
    }
    if (plan.kind == FlightKind::Stacks) {
      // Stacks are filled level by level, one aircraft per level.
      plan.stack = stack_slots / detail::kStackLevels;
      plan.stack_level = stack_slots % detail::kStackLevels;
      ++stack_slots;
    }
  }
  return plans;
}

void TrafficGenerator::Impl::start_flight(Slot& slot, Flight flight) {
  if (config.termination_probability_per_hour > 0) {
    const double lifetime = slot.path.exponential(3600.0 / config.termination_probability_per_hour);
    flight.end_time = std::min(flight.end_time, flight.begin_time + lifetime);
  }
  slot.flight = std::move(flight);
  slot.serial = aircraft_started++;
}

double TrafficGenerator::Impl::stream_nominal() const {
  return config.start_time + slots_[stream_slot_].phase_s +
         static_cast<double>(stream_period_) * config.period_s;
}

void TrafficGenerator::Impl::take_from_stream() {
  const double nominal = stream_nominal();
  if (nominal - stream_margin_s_ >= end_time_) {  // every later sample is later still
    stream_done_ = true;
    return;
  }
  Slot& slot = slots_[stream_slot_];
  const double jitter = slot.sensor.uniform(-1.0, 1.0) * config.jitter_s;
  // Millisecond times: what recorders keep, and short to print.
  const double t = round_decimals(nominal + jitter, 1e3);
  if (t < end_time_) {
    heap_.push_back({t, static_cast<std::uint32_t>(stream_slot_)});
    std::push_heap(heap_.begin(), heap_.end(), std::greater<>{});
  }
  if (++stream_slot_ == slots_.size()) {
    stream_slot_ = 0;
    ++stream_period_;
  }
}

bool TrafficGenerator::Impl::next(TrackReport& out) {
  for (;;) {
    // A stream sample can still come before the earliest pending one only while its
    // nominal time is within the margin of it.
    while (!stream_done_ && (heap_.empty() || stream_nominal() - stream_margin_s_ <= heap_.front().t)) {
      take_from_stream();
    }
    if (heap_.empty()) return false;
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<>{});
    const Pending due = heap_.back();
    heap_.pop_back();
    if (due.t < config.start_time) continue;  // a first sample jittered before the start
    Slot& slot = slots_[due.slot];
    while (due.t >= slot.flight.end_time) {
      start_flight(slot, airspace_->successor(slot.plan, slot.flight.end_time, slot.path));
    }
    // The same draws for every sample whatever the settings, so that changing a noise level
    // or the miss probability changes nothing else.
    Measurement measurement;
    measurement.missed = slot.sensor.chance(config.missed_update_probability);
    measurement.north_sigmas = slot.sensor.gaussian();
    measurement.east_sigmas = slot.sensor.gaussian();
    measurement.altitude_sigmas = slot.sensor.gaussian();
    if (measurement.missed) {
      ++missed;
      continue;
    }
    fill(slot, due.t, measurement, out);
    ++records;
    return true;
  }
}

void TrafficGenerator::Impl::fill(const Slot& slot, double t, const Measurement& measurement,
                                  TrackReport& out) {
  const detail::TruthState truth = slot.flight.at(t);
  double lat = truth.lat_deg, lon = truth.lon_deg;
  if (config.position_noise_m > 0) {
    detail::offset_position(lat, lon, measurement.east_sigmas * config.position_noise_m,
                            measurement.north_sigmas * config.position_noise_m);
  }
  const double alt = truth.alt_ft + measurement.altitude_sigmas * config.altitude_noise_ft;

  const std::uint32_t address = address_of(slot.serial, address_key_);
  out.t = t;
  write_address(address, out.id);
  out.source = "gen";
  // 1e-7° is about 1 cm: far below any radar's resolution, and short to print.
  out.lat_deg = round_decimals(lat, 1e7);
  out.lon_deg = round_decimals(GeographicLib::Math::AngNormalize(lon), 1e7);
  out.alt_ft = config.altitude_quantum_ft > 0 ? round_to(alt, config.altitude_quantum_ft) : round_decimals(alt, 1e2);
  if (config.report_velocity) {
    out.gs_kt = round_decimals(truth.gs_mps / detail::kMpsPerKnot, 10);
    out.trk_deg = detail::wrap_360(round_decimals(truth.trk_deg, 100));
    out.vr_fpm = round_decimals(truth.vr_fpm, 1);
  } else {
    out.gs_kt.reset();
    out.trk_deg.reset();
    out.vr_fpm.reset();
  }
  write_callsign(address, out.callsign);
  out.mode3a.reset();
  // Cleared, not set (`out` may be a reused report): every generated aircraft is one
  // track of one source, so an address attribute would tell the rules nothing more.
  out.address.reset();
  out.on_ground = false;
  out.coasting = false;
  out.track_end = false;
}

// ------------------------------------------------------------------------ facade

TrafficGenerator::TrafficGenerator(const GeneratorConfig& config) {
  if (std::string problem = validate(config); !problem.empty()) throw std::invalid_argument(problem);
  impl_ = std::make_unique<Impl>(config);
}

TrafficGenerator::~TrafficGenerator() = default;
TrafficGenerator::TrafficGenerator(TrafficGenerator&&) noexcept = default;
TrafficGenerator& TrafficGenerator::operator=(TrafficGenerator&&) noexcept = default;

bool TrafficGenerator::next(TrackReport& out) { return impl_->next(out); }
std::size_t TrafficGenerator::aircraft_started() const { return static_cast<std::size_t>(impl_->aircraft_started); }
std::uint64_t TrafficGenerator::records_produced() const { return impl_->records; }
std::uint64_t TrafficGenerator::samples_missed() const { return impl_->missed; }
const GeneratorConfig& TrafficGenerator::config() const { return impl_->config; }

}  // namespace kew::replay
