#pragma once
// The true motion of one generated aircraft: closed-form functions of time, so a sample
// at any instant costs one evaluation and nothing is integrated step by step.

#include <memory>

#include <GeographicLib/GeodesicLine.hpp>
#include "kew/util/units.hpp"

namespace kew::replay::detail {

using units::kMetresPerFoot;
using units::kMetresPerNauticalMile;
using units::kMpsPerKnot;

/// What the aircraft really does at one instant.
struct TruthState {
  double lat_deg = 0;    ///< WGS84
  double lon_deg = 0;    ///< WGS84, [−180, 180]
  double alt_ft = 0;     ///< pressure altitude
  double gs_mps = 0;     ///< ground speed, ≥ 0
  double trk_deg = 0;    ///< true track, [0, 360)
  double vr_fpm = 0;     ///< vertical rate, positive climbing
};

/// Ground speed along a leg as a function of the distance still to fly on it: `far`
/// while more than `slow_down` remain, then falling linearly with the remaining distance
/// to `end` at the end of the leg (an arrival slowing down towards the runway). Solving
/// ds/dt = −(end + k·s) gives an exponential, so positions stay closed-form.
class SpeedSchedule {
 public:
  /// Constant speed, m/s > 0.
  static SpeedSchedule constant(double speed_mps);
  /// far_mps, end_mps > 0 (m/s); slow_down_m > 0 (metres before the end of the leg).
  static SpeedSchedule decelerating(double far_mps, double end_mps, double slow_down_m);

  /// Distance flown (m) and speed (m/s) `elapsed_s` ≥ 0 after a point `remaining_m` ≥ 0
  /// before the end of the leg; never flies past the end.
  void advance(double remaining_m, double elapsed_s, double& flown_m, double& speed_mps) const;

  /// Seconds to fly from `remaining_m` to `target_remaining_m` (0 ≤ target ≤ remaining).
  double time_between(double remaining_m, double target_remaining_m) const;

  double far_mps() const { return far_mps_; }

 private:
  double far_mps_ = 1.0;
  double end_mps_ = 1.0;
  double slow_down_m_ = 0.0;
  double rate_per_s_ = 0.0;  // k = (far − end)/slow_down, 1/s
};

/// A straight (geodesic) leg on a GeographicLib line that may be shared by many aircraft
/// (one airway, one arrival route): aircraft on it fly exactly the same track.
struct LineLeg {
  const GeographicLib::GeodesicLine* line = nullptr;
  double start_arc_m = 0;   ///< arc length along `line` where the leg starts
  int direction = 1;        ///< +1 towards increasing arc length, −1 the reverse
  double length_m = 0;      ///< leg length, ≥ 0
  SpeedSchedule speed = SpeedSchedule::constant(1.0);

  /// Arc length along `line` after flying `flown_m`.
  double arc_after(double flown_m) const { return start_arc_m + direction * flown_m; }
};

/// A right-hand holding racetrack (ICAO Doc 8168): inbound leg to the fix along
/// `inbound_course`, rate-one (3°/s) turns, 1-minute legs, flown at one speed by every
/// aircraft of the stack. Computed in a local east/north frame at the fix: a pattern
/// spans about 10 km, where that frame is within millimetres of the ellipsoid.
class Racetrack {
 public:
  /// fix: WGS84 degrees; inbound_course_deg: true course of the inbound leg, degrees;
  /// speed_mps > 0.
  Racetrack(double fix_lat_deg, double fix_lon_deg, double inbound_course_deg, double speed_mps);

  /// Position and track `loop_m` metres along the pattern from the fix (any value; taken
  /// modulo loop_length_m()).
  void at(double loop_m, double& lat_deg, double& lon_deg, double& trk_deg) const;

  double loop_length_m() const { return loop_m_; }
  double speed_mps() const { return speed_mps_; }
  double inbound_course_deg() const { return course_deg_; }
  double fix_lat_deg() const { return fix_lat_deg_; }
  double fix_lon_deg() const { return fix_lon_deg_; }

 private:
  double fix_lat_deg_, fix_lon_deg_, course_deg_, speed_mps_;
  double radius_m_, leg_m_, loop_m_;
  double along_e_, along_n_;   // unit vector of the inbound course (east, north)
  double degrees_per_metre_lat_, degrees_per_metre_lon_;
};

/// Altitude as a function of time (level, then a climb or descent at a constant rate to
/// a target level) or of the distance left on the leg (an arrival's descent path, capped
/// at its cruise level; a route's climb from its departure, cruise and descent).
struct VerticalProfile {
  enum class Kind { Scheduled, Glide, Route } kind = Kind::Scheduled;
  // Scheduled
  double start_ft = 0;          ///< altitude until change_time
  double change_time = 0;       ///< UTC s when the climb/descent starts (may be in the past)
  double rate_fpm = 0;          ///< signed; 0 = level throughout
  double target_ft = 0;         ///< altitude where the change stops
  // Glide: alt = min(cruise, floor + slope · remaining)
  double cruise_ft = 0;
  double floor_ft = 0;
  double slope_ft_per_m = 0;
  // Route: the glide's altitude, and also at most departure_floor + climb · (route − remaining)
  double departure_floor_ft = 0;
  double climb_ft_per_m = 0;
  double route_m = 0;           ///< length of the whole route; the leg flies its last part

  static VerticalProfile level(double alt_ft);
  static VerticalProfile change(double start_ft, double change_time, double rate_fpm, double target_ft);
  static VerticalProfile glide(double cruise_ft, double floor_ft, double slope_ft_per_m);
  /// From departure_floor_ft over the route's start, climbing climb_ft_per_m (> 0) feet per
  /// metre flown to cruise_ft, then descending slope_ft_per_m (> 0) feet per metre to
  /// floor_ft over its end, route_m (> 0) metres from its start. A route too short to
  /// reach its cruise level turns from the climb to the descent where the two meet.
  static VerticalProfile route(double departure_floor_ft, double climb_ft_per_m, double cruise_ft,
                               double floor_ft, double slope_ft_per_m, double route_m);
};

/// One aircraft from its appearance to its end: optionally a holding pattern until
/// `leg_start_time`, then a line leg; the vertical profile runs alongside.
class Flight {
 public:
  double begin_time = 0;        ///< UTC s when it appeared
  double end_time = 0;          ///< UTC s when it ends (+inf: not within any run)
  // Holding (when `hold` is set): loop position hold_start_m at begin_time.
  const Racetrack* hold = nullptr;
  double hold_start_m = 0;
  double leg_start_time = 0;    ///< UTC s when the leg begins (= begin_time without a hold)
  LineLeg leg;
  VerticalProfile vertical;
  /// Placed behind another aircraft of its airway, faster, to overtake it. Such a flight
  /// never leads another in-trail one, so speeds do not compound along a chain.
  bool in_trail = false;
  /// Owner of `leg.line` when no route shares it.
  std::unique_ptr<const GeographicLib::GeodesicLine> own_line;

  /// True state at `t` (begin_time ≤ t ≤ end_time).
  TruthState at(double t) const;

  /// Time the leg ends (its distance flown), UTC s.
  double leg_end_time() const;
};

/// Degrees of latitude and longitude per metre north and east near a latitude: the
/// WGS84 meridional and prime-vertical radii of curvature, for small offsets (noise,
/// holding patterns) where a local flat frame is exact to well below a metre.
struct LocalScale {
  double deg_lat_per_m = 0;
  double deg_lon_per_m = 0;
};
LocalScale local_scale(double lat_deg);

/// Moves a position (WGS84 degrees) by `east_m` and `north_m` metres, offsets of at most
/// tens of kilometres (measurement noise). The longitude may leave [−180, 180]; callers
/// normalise it. Beyond 85° of latitude, where a step east is no longer a change of
/// longitude alone (at the pole, not one at all), the step is taken in the plane tangent
/// at the point and projected back: positions near or at a pole move by the right
/// distance and keep their latitude within [−90, 90].
void offset_position(double& lat_deg, double& lon_deg, double east_m, double north_m);

/// Degrees wrapped into [0, 360).
double wrap_360(double deg);

/// Altitude and vertical rate of a scheduled profile at `t`.
void scheduled_altitude(const VerticalProfile& profile, double t, double& alt_ft, double& vr_fpm);

}  // namespace kew::replay::detail
