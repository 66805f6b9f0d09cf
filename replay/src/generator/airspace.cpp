// Scenario layouts and aircraft placement; described in airspace.hpp and replay/README.md.
#include "generator/airspace.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <GeographicLib/Geodesic.hpp>

namespace kew::replay::detail {
namespace {

using GeographicLib::Geodesic;

constexpr unsigned kLineCaps =
    Geodesic::LATITUDE | Geodesic::LONGITUDE | Geodesic::AZIMUTH | Geodesic::DISTANCE_IN;

const Geodesic& wgs84() { return Geodesic::WGS84(); }

double knots(double kt) { return kt * kMpsPerKnot; }
double flight_level(double fl) { return fl * 100.0; }

// ---- random: uniform positions, headings, FL100–FL400, some changing level
constexpr double kRandomMinKt = 250, kRandomMaxKt = 500;
constexpr double kRandomLowestFl = 100, kRandomHighestFl = 400;
constexpr double kRandomLevelChangeShare = 0.3;

// ---- airways: semicircular levels (one direction odd thousands, the other even)
constexpr double kAirwayLowestFl = 250;   // odd direction: FL250, 270 … 390
constexpr std::size_t kAirwayLevelsPerDirection = 8;
constexpr double kAirwayMinKt = 380, kAirwayMaxKt = 500;
constexpr double kAirwayLevelChangeShare = 0.2;
constexpr std::size_t kAircraftPerAirway = 100;
constexpr std::size_t kMinAirways = 4, kMaxAirways = 40;
// In-trail pairs: a share of the aircraft start 6–20 km behind another, 30–80 kt faster,
// at its level or 2000 ft away, so overtakes on exactly the same track happen in a run.
constexpr double kTrailingShare = 0.15;
constexpr double kTrailingSameLevelShare = 0.3;

// ---- stacks
constexpr double kStackLowestFl = 70;
constexpr double kHoldMinKt = 210, kHoldMaxKt = 230;
// Most aircraft of a stack fly the pattern nearly in step (within ±500 m of a common
// point, as after entering in a train over the fix): the many-aircraft-over-one-ground-
// point case a 2.5D triangulation must handle. The others are anywhere on the loop.
constexpr double kInStepShare = 0.6;
constexpr double kInStepSpreadM = 500;
constexpr double kHoldMaxSeconds = 1800;
constexpr double kExitLegM = 40'000;
constexpr double kExitTargetFt = 3000;
constexpr double kExitMinFpm = 1500, kExitMaxFpm = 2500;

// ---- TMA arrivals: converge on the centre along shared routes, slowing and descending
constexpr double kArrivalMaxExtentM = 250'000;
constexpr double kArrivalEndM = 4'000;           // the flight ends here (final approach)
constexpr double kArrivalMinStartM = kArrivalEndM + 5'000;
constexpr double kArrivalSlowDownM = 100'000;
constexpr double kArrivalFarMinKt = 420, kArrivalFarMaxKt = 480;
constexpr double kArrivalEndMinKt = 160, kArrivalEndMaxKt = 190;
constexpr double kArrivalLowestCruiseFl = 260;
constexpr std::size_t kArrivalCruiseLevels = 13;  // FL260–FL380
constexpr double kArrivalFloorFt = 1500;
// A 3° descent path: tan 3° feet of height per foot flown, per metre.
constexpr double kGlideFtPerM = 0.052407779283 / kMetresPerFoot;
constexpr std::size_t kAircraftPerArrivalRoute = 25;
constexpr std::size_t kMinArrivalRoutes = 8, kMaxArrivalRoutes = 72;

constexpr double kLevelChangeMinFpm = 1000, kLevelChangeMaxFpm = 2500;

// ---- calibrated (docs/performance.md, calibrated traffic): traffic below the airways climbs and descends
// on semicircular levels (ICAO Annex 2 Appendix 3: tracks 000–179° odd thousands,
// 180–359° even), at lower speeds than cruise.
constexpr double kLowerLowestFl = 50, kLowerHighestFl = 240;
constexpr double kLowerMinKt = 250, kLowerMaxKt = 420;
constexpr double kLowerLevelChangeShare = 0.6;
// Airways: each route and direction cruises on its own 2 of the direction's 8 levels (a
// flight-level allocation scheme, as ACCs separate crossing routes), so crossing routes
// share a level one time in four; level changes are rarer than on the mixed airways.
constexpr std::size_t kAllocationGroups = 4;
constexpr double kCalibratedAirwayLevelChangeShare = 0.1;
// Arrivals go to one terminal per 50 of them, not all to one: a busy hub has 40 arrivals
// an hour at its peak, each about 35 minutes on its last 250 km, so some 25 inbound at
// once; twice that is generous. The first terminal is the region's centre (its stacks sit
// around it); the others lie anywhere within half the radius, with four arrival routes
// each, no longer than the distance to the region's edge.
constexpr std::size_t kCalibratedArrivalsPerTerminal = 50;
constexpr std::size_t kCalibratedRoutesPerTerminal = 4;
constexpr double kCalibratedTerminalRadiusShare = 0.5;

/// Level `level_ft`, or with probability `share` a climb or descent of 1–3 `step_ft`
/// starting at a uniform time in [earliest, latest] and staying within [lowest, highest].
VerticalProfile maybe_change_level(double level_ft, double step_ft, double lowest_ft,
                                   double highest_ft, double earliest, double latest,
                                   double share, RandomStream& rng) {
  if (!rng.chance(share)) return VerticalProfile::level(level_ft);
  const double delta = step_ft * static_cast<double>(1 + rng.index(3));
  const bool climb = rng.chance(0.5);
  double target = level_ft + (climb ? delta : -delta);
  if (target > highest_ft || target < lowest_ft) target = level_ft + (climb ? -delta : delta);
  if (target > highest_ft || target < lowest_ft) return VerticalProfile::level(level_ft);
  const double rate = rng.uniform(kLevelChangeMinFpm, kLevelChangeMaxFpm);
  return VerticalProfile::change(level_ft, rng.uniform(earliest, latest),
                                 target > level_ft ? rate : -rate, target);
}

std::size_t count_of(const std::vector<SlotPlan>& plans, FlightKind kind) {
  return static_cast<std::size_t>(
      std::count_if(plans.begin(), plans.end(), [&](const SlotPlan& p) { return p.kind == kind; }));
}

}  // namespace

Airspace::Airspace(const GeneratorConfig& config, const std::vector<SlotPlan>& plans,
                   RandomStream& layout)
    : center_lat_(config.center_lat_deg),
      center_lon_(config.center_lon_deg),
      radius_m_(config.radius_km * 1000.0),
      time_origin_(config.start_time),
      calibrated_(config.scenario == Scenario::Calibrated) {
  lay_out_airways(count_of(plans, FlightKind::Airways), layout);
  std::uint32_t stacks = 0;
  for (const SlotPlan& p : plans)
    if (p.kind == FlightKind::Stacks) stacks = std::max(stacks, p.stack + 1);
  // In a mixed scenario the stacks feed the TMA, so they sit around its terminal.
  lay_out_stacks(stacks, config.scenario == Scenario::Mixed || calibrated_, layout);
  lay_out_arrivals(count_of(plans, FlightKind::Tma), layout);
  // validate() has checked that the table holds every aerodrome of the selection.
  if (count_of(plans, FlightKind::Global) > 0)
    global_ = std::make_unique<GlobalRoutes>(world_airports(*config.aerodromes));
}

void Airspace::lay_out_airways(std::size_t aircraft, RandomStream& layout) {
  if (aircraft == 0) return;
  const std::size_t count = std::clamp(aircraft / kAircraftPerAirway, kMinAirways, kMaxAirways);
  airways_.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    // Chords between two points of the region's edge at least 120° apart as seen from the
    // centre, so every airway passes within half a radius of it and airways cross.
    const double entry_bearing = layout.uniform(0, 360);
    const double exit_bearing = entry_bearing + layout.uniform(120, 240);
    double lat1, lon1, lat2, lon2, length, azimuth, unused;
    wgs84().Direct(center_lat_, center_lon_, entry_bearing, radius_m_, lat1, lon1);
    wgs84().Direct(center_lat_, center_lon_, exit_bearing, radius_m_, lat2, lon2);
    wgs84().Inverse(lat1, lon1, lat2, lon2, length, azimuth, unused);
    airways_.push_back({wgs84().Line(lat1, lon1, azimuth, kLineCaps), length});
  }
}

void Airspace::lay_out_stacks(std::size_t count, bool near_terminal, RandomStream& layout) {
  stacks_.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double bearing = layout.uniform(0, 360);
    const double distance = near_terminal ? radius_m_ * layout.uniform(0.1, 0.35)
                                          : radius_m_ * 0.8 * std::sqrt(layout.uniform());
    double fix_lat, fix_lon, back_azimuth;
    wgs84().Direct(center_lat_, center_lon_, bearing, distance, fix_lat, fix_lon, back_azimuth);
    // Inbound course towards the terminal: the direction in which aircraft leave the stack.
    double course = layout.uniform(0, 360);
    if (distance > 1000) {
      double unused1, unused2;
      wgs84().Inverse(fix_lat, fix_lon, center_lat_, center_lon_, unused1, course, unused2);
    }
    const Racetrack pattern(fix_lat, fix_lon, course, knots(layout.uniform(kHoldMinKt, kHoldMaxKt)));
    const double column = layout.uniform(0, pattern.loop_length_m());
    stacks_.push_back({pattern, wgs84().Line(fix_lat, fix_lon, course, kLineCaps), column});
  }
}

void Airspace::lay_out_arrivals(std::size_t aircraft, RandomStream& layout) {
  if (aircraft == 0) return;
  const auto add_terminal = [&](double lat, double lon, std::size_t routes, double extent_m) {
    const double rotation = layout.uniform(0, 360);
    for (std::size_t i = 0; i < routes; ++i) {
      const double bearing = rotation + 360.0 * static_cast<double>(i) / static_cast<double>(routes);
      arrivals_.push_back({wgs84().Line(lat, lon, bearing, kLineCaps), extent_m});
    }
  };
  if (!calibrated_) {  // one terminal at the centre, its routes scaled with the arrivals
    add_terminal(center_lat_, center_lon_,
                 std::clamp(aircraft / kAircraftPerArrivalRoute, kMinArrivalRoutes, kMaxArrivalRoutes),
                 std::min(radius_m_, kArrivalMaxExtentM));
    return;
  }
  const std::size_t terminals = (aircraft + kCalibratedArrivalsPerTerminal - 1) / kCalibratedArrivalsPerTerminal;
  for (std::size_t k = 0; k < terminals; ++k) {
    double lat = center_lat_, lon = center_lon_, distance = 0.0;
    if (k > 0) {  // area-uniform within the terminal radius
      const double bearing = layout.uniform(0, 360);
      distance = kCalibratedTerminalRadiusShare * radius_m_ * std::sqrt(layout.uniform());
      wgs84().Direct(center_lat_, center_lon_, bearing, distance, lat, lon);
    }
    add_terminal(lat, lon, kCalibratedRoutesPerTerminal, std::min(radius_m_ - distance, kArrivalMaxExtentM));
  }
}

Flight Airspace::initial(const SlotPlan& plan, double t, RandomStream& rng,
                         const Flight* airway_leader) const {
  switch (plan.kind) {
    case FlightKind::Random: return random_flight(t, rng, true);
    case FlightKind::Airways:
      if (airway_leader != nullptr && rng.chance(kTrailingShare)) {
        Flight trailing = trailing_flight(*airway_leader, t, rng);
        if (trailing.leg.line != nullptr) return trailing;
      }
      return airway_flight(t, rng, true);
    case FlightKind::Stacks: return holding_flight(plan, t, rng, true);
    case FlightKind::Tma: return arrival_flight(t, rng, true);
    case FlightKind::Global: return global_->initial(t, rng);
  }
  return random_flight(t, rng, true);
}

Flight Airspace::successor(const SlotPlan& plan, double t, RandomStream& rng) const {
  switch (plan.kind) {
    case FlightKind::Random: return random_flight(t, rng, false);
    case FlightKind::Airways: return airway_flight(t, rng, false);
    case FlightKind::Stacks: return holding_flight(plan, t, rng, false);
    case FlightKind::Tma: return arrival_flight(t, rng, false);
    case FlightKind::Global: return global_->successor(t, rng);
  }
  return random_flight(t, rng, false);
}

Flight Airspace::random_flight(double t, RandomStream& rng, bool under_way) const {
  // Area-uniform in the disk; a replacement too, so the density stays uniform.
  const double bearing = rng.uniform(0, 360);
  const double distance = radius_m_ * std::sqrt(rng.uniform());
  double lat, lon, outward;
  wgs84().Direct(center_lat_, center_lon_, bearing, distance, lat, lon, outward);
  const double heading = rng.uniform(0, 360);
  // Distance to the region's edge along the heading, in the plane tangent at the point:
  // with α the angle between heading and the outward radial, s = −d·cos α + √(R² − d²·sin² α).
  const double alpha = (heading - outward) * std::numbers::pi / 180.0;
  const double across = distance * std::sin(alpha);
  const double to_edge =
      std::max(0.0, -distance * std::cos(alpha) + std::sqrt(radius_m_ * radius_m_ - across * across));

  Flight f;
  f.begin_time = f.leg_start_time = t;
  f.own_line = std::make_unique<const GeographicLib::GeodesicLine>(wgs84().Line(lat, lon, heading, kLineCaps));
  f.leg.line = f.own_line.get();
  f.leg.length_m = to_edge;
  if (calibrated_) {
    f.leg.speed = SpeedSchedule::constant(knots(rng.uniform(kLowerMinKt, kLowerMaxKt)));
    f.end_time = f.leg_end_time();
    // Levels of the heading's parity, changed in steps of 2000 ft that keep it.
    const double lowest = flight_level(kLowerLowestFl) + (heading < 180.0 ? 0.0 : 1000.0);
    const auto levels = static_cast<std::size_t>((flight_level(kLowerHighestFl) - lowest) / 2000.0) + 1;
    const double level = lowest + 2000.0 * static_cast<double>(rng.index(levels));
    f.vertical = maybe_change_level(level, 2000, lowest, lowest + 2000.0 * static_cast<double>(levels - 1),
                                    under_way ? t - 120 : t, t + 300, kLowerLevelChangeShare, rng);
    return f;
  }
  f.leg.speed = SpeedSchedule::constant(knots(rng.uniform(kRandomMinKt, kRandomMaxKt)));
  const auto levels = static_cast<std::size_t>(kRandomHighestFl - kRandomLowestFl) / 10 + 1;
  const double level = flight_level(kRandomLowestFl + 10.0 * static_cast<double>(rng.index(levels)));
  f.vertical = maybe_change_level(level, 1000, flight_level(kRandomLowestFl),
                                  flight_level(kRandomHighestFl), under_way ? t - 120 : t, t + 300,
                                  kRandomLevelChangeShare, rng);
  f.end_time = f.leg_end_time();
  return f;
}

Flight Airspace::airway_flight(double t, RandomStream& rng, bool under_way) const {
  const std::size_t route_index = rng.index(airways_.size());
  const Route& route = airways_[route_index];
  const int direction = rng.chance(0.5) ? 1 : -1;
  const double start_arc = under_way ? rng.uniform(0, route.length_m) : (direction > 0 ? 0.0 : route.length_m);
  // Semicircular rule: one direction flies the odd thousands, the other the even ones.
  const double lowest = flight_level(kAirwayLowestFl) + (direction > 0 ? 0.0 : 1000.0);
  std::size_t level_index = rng.index(kAirwayLevelsPerDirection);
  if (calibrated_)  // the route's group of levels: index ≡ route (mod groups)
    level_index = level_index / kAllocationGroups * kAllocationGroups + route_index % kAllocationGroups;
  const double level = lowest + 2000.0 * static_cast<double>(level_index);
  const double highest = lowest + 2000.0 * static_cast<double>(kAirwayLevelsPerDirection - 1);

  Flight f;
  f.begin_time = f.leg_start_time = t;
  f.leg.line = &route.line;
  f.leg.start_arc_m = start_arc;
  f.leg.direction = direction;
  f.leg.length_m = direction > 0 ? route.length_m - start_arc : start_arc;
  f.leg.speed = SpeedSchedule::constant(knots(rng.uniform(kAirwayMinKt, kAirwayMaxKt)));
  // Level changes keep the direction's parity, crossing the other direction's levels.
  f.vertical = maybe_change_level(level, 2000, lowest - 4000, highest + 2000, under_way ? t - 60 : t, t + 600,
                                  calibrated_ ? kCalibratedAirwayLevelChangeShare : kAirwayLevelChangeShare, rng);
  f.end_time = f.leg_end_time();
  return f;
}

Flight Airspace::trailing_flight(const Flight& leader, double t, RandomStream& rng) const {
  Flight f;  // no line: the caller places the aircraft on its own instead
  const auto route = std::find_if(airways_.begin(), airways_.end(),
                                  [&](const Route& r) { return &r.line == leader.leg.line; });
  if (route == airways_.end()) return f;
  const double gap = rng.uniform(6'000, 20'000);
  const double start_arc = leader.leg.arc_after(-gap);
  if (start_arc < 0 || start_arc > route->length_m) return f;  // would start off the airway

  const int direction = leader.leg.direction;
  f.begin_time = f.leg_start_time = t;
  f.leg.line = leader.leg.line;
  f.leg.start_arc_m = start_arc;
  f.leg.direction = direction;
  f.leg.length_m = direction > 0 ? route->length_m - start_arc : start_arc;
  f.leg.speed = SpeedSchedule::constant(leader.leg.speed.far_mps() + knots(rng.uniform(30, 80)));
  // The same level (an overtake that is a conflict) or the next level of the same
  // direction (passing over or under it on exactly the same track).
  double level = leader.vertical.start_ft;
  // Calibrated: controllers do not let one overtake another at its level.
  if (calibrated_ || !rng.chance(kTrailingSameLevelShare)) {
    const double highest = flight_level(kAirwayLowestFl) + (direction > 0 ? 0.0 : 1000.0) +
                           2000.0 * static_cast<double>(kAirwayLevelsPerDirection - 1);
    level += level + 2000.0 <= highest ? 2000.0 : -2000.0;
  }
  f.vertical = VerticalProfile::level(level);
  f.end_time = f.leg_end_time();
  f.in_trail = true;
  return f;
}

Flight Airspace::holding_flight(const SlotPlan& plan, double t, RandomStream& rng, bool under_way) const {
  const Stack& stack = stacks_[plan.stack];
  const Racetrack& pattern = stack.pattern;
  const double loop = pattern.loop_length_m();
  const double speed = pattern.speed_mps();
  double start = rng.uniform(0, loop);
  if (rng.chance(kInStepShare)) {
    start = stack.column_m + speed * (t - time_origin_) + rng.uniform(-kInStepSpreadM, kInStepSpreadM);
  }
  start = std::fmod(start, loop);
  if (start < 0) start += loop;

  // Leaves at the first pass over the fix after its holding time, along the inbound
  // course, descending through the levels below.
  const double held = under_way ? rng.uniform(0, kHoldMaxSeconds) : rng.uniform(300, kHoldMaxSeconds);
  const double laps = std::ceil((start + speed * held) / loop);
  const double exit_time = t + (laps * loop - start) / speed;

  Flight f;
  f.begin_time = t;
  f.hold = &pattern;
  f.hold_start_m = start;
  f.leg_start_time = exit_time;
  f.leg.line = &stack.exit_line;
  f.leg.length_m = kExitLegM;
  f.leg.speed = SpeedSchedule::constant(speed);
  const double level = flight_level(kStackLowestFl) + 1000.0 * static_cast<double>(plan.stack_level);
  f.vertical = VerticalProfile::change(level, exit_time, -rng.uniform(kExitMinFpm, kExitMaxFpm),
                                       std::min(level, kExitTargetFt));
  f.end_time = f.leg_end_time();
  return f;
}

Flight Airspace::arrival_flight(double t, RandomStream& rng, bool under_way) const {
  const Route& route = arrivals_[rng.index(arrivals_.size())];
  const double start = under_way ? rng.uniform(kArrivalMinStartM, route.length_m) : route.length_m;
  const double leg_length = start - kArrivalEndM;
  const double slow_down = std::min(kArrivalSlowDownM, route.length_m - kArrivalEndM);

  Flight f;
  f.begin_time = f.leg_start_time = t;
  f.leg.line = &route.line;
  f.leg.start_arc_m = start;
  f.leg.direction = -1;  // inbound: the routes are drawn outbound from the terminal
  f.leg.length_m = leg_length;
  f.leg.speed = SpeedSchedule::decelerating(knots(rng.uniform(kArrivalFarMinKt, kArrivalFarMaxKt)),
                                            knots(rng.uniform(kArrivalEndMinKt, kArrivalEndMaxKt)),
                                            slow_down);
  const double cruise =
      flight_level(kArrivalLowestCruiseFl) + 1000.0 * static_cast<double>(rng.index(kArrivalCruiseLevels));
  f.vertical = VerticalProfile::glide(cruise, kArrivalFloorFt, kGlideFtPerM);
  f.end_time = f.leg_end_time();
  return f;
}

}  // namespace kew::replay::detail
