#pragma once
// The global scenario's network: great-circle routes between the real aerodromes of
// kew/replay/airports.hpp, drawn so that every run flies regional and long-haul routes,
// the North Atlantic, the polar caps and the antimeridian (replay/README.md).

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <GeographicLib/GeodesicLine.hpp>

#include "generator/flight.hpp"
#include "generator/random_stream.hpp"
#include "kew/replay/airports.hpp"

namespace kew::replay::detail {

/// Classes of routes; one route may belong to several (a polar route is also long-haul).
enum class RouteClass : std::uint8_t {
  Regional,       ///< 300 to 3,000 km
  LongHaul,       ///< 3,000 to 15,500 km
  NorthAtlantic,  ///< between Europe and North America
  Antimeridian,   ///< crossing ±180° of longitude
  Polar,          ///< passing within 5° of a pole (or ending there)
};
inline constexpr std::size_t kRouteClasses = 5;

/// A city pair of the selection (a < b, indices into the airports) and its great-circle
/// distance on the mean sphere, km (within about 0.5 % of the geodesic: enough to classify and
/// weight routes; the flights themselves fly the geodesic).
struct CityPair {
  std::uint16_t a = 0, b = 0;
  double sphere_km = 0;
};

class GlobalRoutes {
 public:
  /// Classifies every pair of `airports` (world_airports(); a few milliseconds for 240
  /// aerodromes); builds no geodesic yet. Throws std::logic_error if they leave a class
  /// of routes empty.
  explicit GlobalRoutes(std::vector<Airport> airports);
  GlobalRoutes(const GlobalRoutes&) = delete;
  GlobalRoutes& operator=(const GlobalRoutes&) = delete;

  /// A flight already under way at `t` (the start of the run): the route drawn as an
  /// aircraft seen at a random instant would be on it (by class share and, within a
  /// class, in proportion to the route's length), at a uniform point along it.
  Flight initial(double t, RandomStream& rng) const;

  /// A flight departing at `t` in place of one that ended, its route drawn so that the
  /// airborne mix stays that of initial().
  Flight successor(double t, RandomStream& rng) const;

 private:
  struct Route {
    GeographicLib::GeodesicLine line;  // from airport a to airport b
    double length_m;
    double course_from_b_deg;  // initial course of a flight from b to a, [0, 360)
  };
  struct Class {
    std::vector<std::uint32_t> pairs;   // indices into pairs_
    std::vector<double> cumulative_km;  // of the pairs' lengths, for length-weighted draws
  };

  const Route& route(std::uint32_t pair) const;
  Flight flight(std::uint32_t pair, bool from_a, double flown_m, double speed_mps, double t,
                RandomStream& rng) const;

  std::vector<Airport> airports_;
  std::vector<CityPair> pairs_;
  std::array<Class, kRouteClasses> classes_;
  // Class probabilities of successor() draws: the airborne mix, in flights started.
  std::array<double, kRouteClasses> departure_shares_{};
  // Built on first use and kept: Flight legs point into them, and the ~26,000 pairs would
  // take some 14 MB built up front where a run of a few hundred aircraft flies a few hundred.
  // The generator is single-threaded, so the lazy cache needs no lock.
  mutable std::vector<std::unique_ptr<const Route>> routes_;
};

}  // namespace kew::replay::detail
