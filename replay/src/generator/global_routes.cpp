// The global scenario's routes; described in global_routes.hpp and replay/README.md.
#include "generator/global_routes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/Math.hpp>

namespace kew::replay::detail {
namespace {

using GeographicLib::Geodesic;

constexpr unsigned kLineCaps =
    Geodesic::LATITUDE | Geodesic::LONGITUDE | Geodesic::AZIMUTH | Geodesic::DISTANCE_IN;
constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
constexpr double kMeanEarthRadiusKm = 6371.0088;  // IUGG mean radius R1

// Aerodromes closer than this (two of one city) are not linked; none farther apart than
// the longest scheduled flights (15,300–15,350 km), so no route is nearly antipodal.
constexpr double kMinRouteKm = 300;
constexpr double kRegionalMaxKm = 3000;
constexpr double kMaxRouteKm = 15'500;
constexpr double kPolarLatitudeDeg = 85;

// The airborne mix, in RouteClass order: half the aircraft on regional routes, a quarter
// on any long-haul route, and shares reserved for the North Atlantic, the antimeridian and
// the polar caps, so that every run flies them whatever the seed (the classes overlap, so
// long-haul traffic also crosses the oceans and the antimeridian beyond these shares).
constexpr std::array<double, kRouteClasses> kAirborneShares = {0.50, 0.25, 0.08, 0.12, 0.05};

constexpr double kMinKt = 420, kMaxKt = 500;
// Semicircular levels of RVSM airspace (ICAO Annex 2 Appendix 3), by the initial true
// course: 000–179° the odd levels FL290 … FL410, 180–359° the even ones FL300 … FL400.
constexpr double kLowestOddFt = 29'000, kLowestEvenFt = 30'000;
constexpr std::size_t kOddLevels = 7, kEvenLevels = 6;
// An aircraft appears 1,500 ft above its departure aerodrome and ends 1,500 ft above its
// destination (takeoffs and landings are not modelled; the tma arrivals end at that height
// too); it climbs on a 2.5° path (about 2,000 ft/min at its speed) and descends on a 3° one.
constexpr double kFieldClearanceFt = 1500;
constexpr double kClimbFtPerM = 0.0436609429085121 / kMetresPerFoot;    // tan 2.5°
constexpr double kDescentFtPerM = 0.0524077792830412 / kMetresPerFoot;  // tan 3°

/// Index drawn with the given probabilities (summing to 1; the last absorbs rounding).
std::size_t draw_class(const std::array<double, kRouteClasses>& shares, RandomStream& rng) {
  double u = rng.uniform();
  std::size_t k = 0;
  while (k + 1 < shares.size() && u >= shares[k]) u -= shares[k++];
  return k;
}

bool links(const Airport& a, const Airport& b, Continent one, Continent other) {
  return (a.continent == one && b.continent == other) || (a.continent == other && b.continent == one);
}

/// What the great circle between two aerodromes does, on the mean sphere.
struct GreatCircle {
  double length_km = 0;
  double highest_lat_deg = 0;  // highest latitude of the arc between the two ends
  double lowest_lat_deg = 0;   // lowest latitude likewise
  bool crosses_antimeridian = false;
};

GreatCircle great_circle(const Airport& from, const Airport& to) {
  const double dlon_deg = GeographicLib::Math::AngDiff(from.lon_deg, to.lon_deg);  // (−180, 180]
  const double lat1 = from.lat_deg / kDegreesPerRadian, lat2 = to.lat_deg / kDegreesPerRadian;
  const double dlon = dlon_deg / kDegreesPerRadian;
  const double s1 = std::sin(lat1), c1 = std::cos(lat1), s2 = std::sin(lat2), c2 = std::cos(lat2);
  const double sd = std::sin(dlon), cd = std::cos(dlon);
  // East and north components of the initial direction (unnormalised), and of the final one.
  const double east1 = c2 * sd, north1 = c1 * s2 - s1 * c2 * cd;
  const double north2 = -c2 * s1 + s2 * c1 * cd;

  GreatCircle g;
  // Vincenty's form of the central angle: accurate at every distance.
  g.length_km = std::atan2(std::hypot(east1, north1), s1 * s2 + c1 * c2 * cd) * kMeanEarthRadiusKm;
  g.highest_lat_deg = std::max(from.lat_deg, to.lat_deg);
  g.lowest_lat_deg = std::min(from.lat_deg, to.lat_deg);
  // Clairaut: cos(latitude)·sin(azimuth) is constant along a great circle, and the azimuth
  // is ±90° at its vertex. The arc passes the vertex when it sets out northwards and
  // arrives southwards (or the reverse, for the southern one).
  const double sin_azimuth1 = east1 / std::hypot(east1, north1);
  const double vertex_deg = std::acos(std::min(1.0, std::abs(c1 * sin_azimuth1))) * kDegreesPerRadian;
  if (north1 > 0 && north2 < 0) g.highest_lat_deg = vertex_deg;
  if (north1 < 0 && north2 > 0) g.lowest_lat_deg = -vertex_deg;
  // Longitude changes monotonically along the arc, by dlon: it crosses ±180° when the
  // unwrapped end lies beyond.
  g.crosses_antimeridian = std::abs(from.lon_deg + dlon_deg) > 180.0;
  return g;
}

}  // namespace

GlobalRoutes::GlobalRoutes(std::vector<Airport> airports) : airports_(std::move(airports)) {
  for (std::size_t a = 0; a < airports_.size(); ++a) {
    for (std::size_t b = a + 1; b < airports_.size(); ++b) {
      const GreatCircle g = great_circle(airports_[a], airports_[b]);
      if (g.length_km < kMinRouteKm || g.length_km > kMaxRouteKm) continue;
      const auto index = static_cast<std::uint32_t>(pairs_.size());
      pairs_.push_back({static_cast<std::uint16_t>(a), static_cast<std::uint16_t>(b), g.length_km});
      const auto add = [&](RouteClass c) { classes_[static_cast<std::size_t>(c)].pairs.push_back(index); };
      add(g.length_km < kRegionalMaxKm ? RouteClass::Regional : RouteClass::LongHaul);
      if (links(airports_[a], airports_[b], Continent::Europe, Continent::NorthAmerica)) add(RouteClass::NorthAtlantic);
      if (g.crosses_antimeridian) add(RouteClass::Antimeridian);
      if (g.highest_lat_deg >= kPolarLatitudeDeg || g.lowest_lat_deg <= -kPolarLatitudeDeg) add(RouteClass::Polar);
    }
  }
  routes_.resize(pairs_.size());

  // Flights of a class start at a rate that keeps its airborne share: the share over the
  // mean flight time, that is over the mean length of its routes (speeds do not depend on
  // the route).
  double departure_total = 0;
  for (std::size_t k = 0; k < kRouteClasses; ++k) {
    Class& c = classes_[k];
    if (c.pairs.empty()) throw std::logic_error("the aerodromes give a class of routes no city pair");
    double sum = 0;
    c.cumulative_km.reserve(c.pairs.size());
    for (const std::uint32_t p : c.pairs) c.cumulative_km.push_back(sum += pairs_[p].sphere_km);
    departure_shares_[k] = kAirborneShares[k] / (sum / static_cast<double>(c.pairs.size()));
    departure_total += departure_shares_[k];
  }
  for (double& share : departure_shares_) share /= departure_total;
}

const GlobalRoutes::Route& GlobalRoutes::route(std::uint32_t index) const {
  std::unique_ptr<const Route>& built = routes_[index];
  if (built == nullptr) {
    const Airport& a = airports_[pairs_[index].a];
    const Airport& b = airports_[pairs_[index].b];
    const GeographicLib::GeodesicLine line =
        Geodesic::WGS84().InverseLine(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, kLineCaps);
    double lat = 0, lon = 0, azimuth_at_b = 0;
    line.Position(line.Distance(), lat, lon, azimuth_at_b);
    built = std::make_unique<const Route>(Route{line, line.Distance(), wrap_360(azimuth_at_b + 180.0)});
  }
  return *built;
}

Flight GlobalRoutes::initial(double t, RandomStream& rng) const {
  // An aircraft seen at a random instant is on a route in proportion to the time flights
  // spend on it: within its class, in proportion to the route's length.
  const Class& c = classes_[draw_class(kAirborneShares, rng)];
  const double x = rng.uniform(0, c.cumulative_km.back());
  const auto found = std::upper_bound(c.cumulative_km.begin(), c.cumulative_km.end(), x);
  const std::uint32_t pair = c.pairs[std::min(static_cast<std::size_t>(found - c.cumulative_km.begin()),
                                              c.pairs.size() - 1)];
  const bool from_a = rng.chance(0.5);
  // Slower aircraft spend longer on a route: seen at an instant, speeds have a density
  // proportional to 1/v over [min, max], whose inverse distribution is min·(max/min)^u.
  const double speed_kt = kMinKt * std::pow(kMaxKt / kMinKt, rng.uniform());
  const double flown_m = rng.uniform() * route(pair).length_m;
  return flight(pair, from_a, flown_m, speed_kt * kMpsPerKnot, t, rng);
}

Flight GlobalRoutes::successor(double t, RandomStream& rng) const {
  const Class& c = classes_[draw_class(departure_shares_, rng)];
  const std::uint32_t pair = c.pairs[rng.index(c.pairs.size())];
  const bool from_a = rng.chance(0.5);
  const double speed_kt = rng.uniform(kMinKt, kMaxKt);
  return flight(pair, from_a, 0.0, speed_kt * kMpsPerKnot, t, rng);
}

Flight GlobalRoutes::flight(std::uint32_t pair, bool from_a, double flown_m, double speed_mps, double t,
                            RandomStream& rng) const {
  const Route& r = route(pair);
  const Airport& from = airports_[from_a ? pairs_[pair].a : pairs_[pair].b];
  const Airport& to = airports_[from_a ? pairs_[pair].b : pairs_[pair].a];
  const double course = from_a ? wrap_360(r.line.Azimuth()) : r.course_from_b_deg;
  const double cruise_ft = course < 180.0 ? kLowestOddFt + 2000.0 * static_cast<double>(rng.index(kOddLevels))
                                          : kLowestEvenFt + 2000.0 * static_cast<double>(rng.index(kEvenLevels));

  Flight f;
  f.begin_time = f.leg_start_time = t;
  f.leg.line = &r.line;
  f.leg.direction = from_a ? 1 : -1;
  f.leg.start_arc_m = from_a ? flown_m : r.length_m - flown_m;
  f.leg.length_m = r.length_m - flown_m;
  f.leg.speed = SpeedSchedule::constant(speed_mps);
  f.vertical = VerticalProfile::route(from.elevation_ft + kFieldClearanceFt, kClimbFtPerM, cruise_ft,
                                      to.elevation_ft + kFieldClearanceFt, kDescentFtPerM, r.length_m);
  f.end_time = f.leg_end_time();
  return f;
}

}  // namespace kew::replay::detail
