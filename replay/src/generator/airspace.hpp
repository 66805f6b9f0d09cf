#pragma once
// The fixed structure of a generated scenario (airways, holding stacks, arrival routes,
// the global scenario's city pairs) and the rules that place an aircraft in it, either
// already under way at the start of the run or appearing later to replace one that ended.

#include <cstdint>
#include <memory>
#include <vector>

#include <GeographicLib/GeodesicLine.hpp>

#include "generator/flight.hpp"
#include "generator/global_routes.hpp"
#include "generator/random_stream.hpp"
#include "kew/replay/traffic_generator.hpp"

namespace kew::replay::detail {

/// The kind of traffic one aircraft slot carries (Mixed picks one of the first four per
/// slot; Global flies between the world's aerodromes, with no region).
enum class FlightKind : std::uint8_t { Random, Airways, Stacks, Tma, Global };

/// What a slot is for. Stack slots own one level of one stack for the whole run.
struct SlotPlan {
  FlightKind kind = FlightKind::Random;
  std::uint32_t stack = 0;        ///< Stacks: index of the stack
  std::uint32_t stack_level = 0;  ///< Stacks: 0 = lowest level
};

/// Levels per holding stack (FL70 to FL180, 1000 ft apart).
inline constexpr std::uint32_t kStackLevels = 12;

class Airspace {
 public:
  /// Lays out the structures needed by `plans` (routes scale with the number of
  /// aircraft using them) around the config's centre, drawing from `layout`; classifies
  /// the world's city pairs when a plan is Global.
  Airspace(const GeneratorConfig& config, const std::vector<SlotPlan>& plans, RandomStream& layout);
  Airspace(const Airspace&) = delete;
  Airspace& operator=(const Airspace&) = delete;

  /// A flight already under way at `t` (the start of the run), drawn from `rng`.
  /// `airway_leader`: an Airways flight that this one may trail (faster, same track) to
  /// make overtakes; null for none.
  Flight initial(const SlotPlan& plan, double t, RandomStream& rng, const Flight* airway_leader) const;

  /// A flight appearing at `t` in place of one that ended: entering the region, an
  /// airway or the TMA at its edge, a stack at the slot's level, or departing an
  /// aerodrome of the world.
  Flight successor(const SlotPlan& plan, double t, RandomStream& rng) const;

 private:
  struct Stack {
    Racetrack pattern;
    GeographicLib::GeodesicLine exit_line;  // from the fix along the inbound course
    double column_m;                        // loop position of the stack's in-step column at t = 0
  };
  struct Route {
    GeographicLib::GeodesicLine line;
    double length_m;
  };

  Flight random_flight(double t, RandomStream& rng, bool under_way) const;
  Flight airway_flight(double t, RandomStream& rng, bool under_way) const;
  Flight trailing_flight(const Flight& leader, double t, RandomStream& rng) const;
  Flight holding_flight(const SlotPlan& plan, double t, RandomStream& rng, bool under_way) const;
  Flight arrival_flight(double t, RandomStream& rng, bool under_way) const;

  void lay_out_airways(std::size_t aircraft, RandomStream& layout);
  void lay_out_stacks(std::size_t stacks, bool near_terminal, RandomStream& layout);
  void lay_out_arrivals(std::size_t aircraft, RandomStream& layout);

  double center_lat_, center_lon_, radius_m_;
  double time_origin_;
  bool calibrated_;  // Scenario::Calibrated: its level rules (airspace.cpp)
  std::vector<Route> airways_;
  std::vector<Stack> stacks_;
  std::vector<Route> arrivals_;  // outbound from their terminal; length_m: where arrivals enter
  std::unique_ptr<GlobalRoutes> global_;  // Global plans only
};

}  // namespace kew::replay::detail
