// Closed-form aircraft motion; described in flight.hpp.
#include "generator/flight.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Math.hpp>

namespace kew::replay::detail {
namespace {

constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
// Rate-one turn of the holding procedures (ICAO Doc 8168): 3°/s.
constexpr double kRateOneTurnRadPerS = 3.0 / kDegreesPerRadian;
// Outbound/inbound leg of a hold: 1 minute (Doc 8168 uses 1.5 min above FL140; one
// value keeps every stack's pattern the same shape).
constexpr double kHoldLegSeconds = 60.0;
// Beyond this latitude offset_position steps in the tangent plane (flight.hpp).
constexpr double kPolarCapDeg = 85.0;

/// The WGS84 meridional and prime-vertical radii of curvature at a latitude, metres.
struct Radii {
  double meridional;
  double prime_vertical;
};

Radii radii_of_curvature(double lat_deg) {
  const double a = GeographicLib::Constants::WGS84_a();
  const double f = GeographicLib::Constants::WGS84_f();
  const double e2 = f * (2 - f);
  const double sin_lat = std::sin(lat_deg / kDegreesPerRadian);
  const double w = std::sqrt(1 - e2 * sin_lat * sin_lat);
  return {a * (1 - e2) / (w * w * w), a / w};
}

}  // namespace

double wrap_360(double deg) {
  double wrapped = std::fmod(deg, 360.0);
  if (wrapped < 0) wrapped += 360.0;
  return wrapped >= 360.0 ? 0.0 : wrapped;
}

LocalScale local_scale(double lat_deg) {
  const Radii radii = radii_of_curvature(lat_deg);
  const double cos_lat = std::cos(lat_deg / kDegreesPerRadian);
  return {kDegreesPerRadian / radii.meridional, kDegreesPerRadian / (radii.prime_vertical * cos_lat)};
}

void offset_position(double& lat_deg, double& lon_deg, double east_m, double north_m) {
  if (std::abs(lat_deg) <= kPolarCapDeg) {
    const LocalScale scale = local_scale(lat_deg);
    lat_deg += north_m * scale.deg_lat_per_m;
    lon_deg += east_m * scale.deg_lon_per_m;
    return;
  }
  // The point P and its unit east and north vectors E, N on the unit sphere, the step as
  // the angles it subtends (east over the prime-vertical radius of curvature, north over
  // the meridional one), and the stepped point P + e·E + n·N projected back onto the
  // sphere: exact to first order, like the flat step, and defined at the pole too, where
  // E and N follow the longitude given.
  const Radii radii = radii_of_curvature(lat_deg);
  const double e = east_m / radii.prime_vertical;
  const double n = north_m / radii.meridional;
  const double sin_lat = std::sin(lat_deg / kDegreesPerRadian), cos_lat = std::cos(lat_deg / kDegreesPerRadian);
  const double sin_lon = std::sin(lon_deg / kDegreesPerRadian), cos_lon = std::cos(lon_deg / kDegreesPerRadian);
  const double x = cos_lat * cos_lon - e * sin_lon - n * sin_lat * cos_lon;
  const double y = cos_lat * sin_lon + e * cos_lon - n * sin_lat * sin_lon;
  const double z = sin_lat + n * cos_lat;
  lat_deg = std::atan2(z, std::hypot(x, y)) * kDegreesPerRadian;
  lon_deg = std::atan2(y, x) * kDegreesPerRadian;
}

// ---------------------------------------------------------------- SpeedSchedule

SpeedSchedule SpeedSchedule::constant(double speed_mps) {
  SpeedSchedule s;
  s.far_mps_ = s.end_mps_ = speed_mps;
  return s;
}

SpeedSchedule SpeedSchedule::decelerating(double far_mps, double end_mps, double slow_down_m) {
  SpeedSchedule s;
  s.far_mps_ = far_mps;
  s.end_mps_ = end_mps;
  s.slow_down_m_ = slow_down_m;
  s.rate_per_s_ = (far_mps - end_mps) / slow_down_m;
  return s;
}

void SpeedSchedule::advance(double remaining_m, double elapsed_s, double& flown_m,
                            double& speed_mps) const {
  if (rate_per_s_ == 0.0) {
    flown_m = std::min(far_mps_ * elapsed_s, remaining_m);
    speed_mps = far_mps_;
    return;
  }
  double remaining = remaining_m;
  double time_left = elapsed_s;
  if (remaining > slow_down_m_) {
    const double until_slow_down = (remaining - slow_down_m_) / far_mps_;
    if (time_left <= until_slow_down) {
      flown_m = far_mps_ * time_left;
      speed_mps = far_mps_;
      return;
    }
    remaining = slow_down_m_;
    time_left -= until_slow_down;
  }
  // r(τ) = (r₀ + c)·e^(−kτ) − c with c = end/k solves dr/dτ = −(end + k·r).
  const double c = end_mps_ / rate_per_s_;
  const double r = std::max(0.0, (remaining + c) * std::exp(-rate_per_s_ * time_left) - c);
  flown_m = remaining_m - r;
  speed_mps = end_mps_ + rate_per_s_ * r;
}

double SpeedSchedule::time_between(double remaining_m, double target_remaining_m) const {
  if (rate_per_s_ == 0.0) return (remaining_m - target_remaining_m) / far_mps_;
  double seconds = 0;
  double remaining = remaining_m;
  if (remaining > slow_down_m_) {
    const double constant_until = std::max(slow_down_m_, target_remaining_m);
    seconds += (remaining - constant_until) / far_mps_;
    remaining = constant_until;
  }
  if (remaining > target_remaining_m) {
    const double c = end_mps_ / rate_per_s_;
    seconds += std::log((remaining + c) / (target_remaining_m + c)) / rate_per_s_;
  }
  return seconds;
}

// ---------------------------------------------------------------- Racetrack

Racetrack::Racetrack(double fix_lat_deg, double fix_lon_deg, double inbound_course_deg,
                     double speed_mps)
    : fix_lat_deg_(fix_lat_deg),
      fix_lon_deg_(fix_lon_deg),
      course_deg_(wrap_360(inbound_course_deg)),
      speed_mps_(speed_mps),
      radius_m_(speed_mps / kRateOneTurnRadPerS),
      leg_m_(speed_mps * kHoldLegSeconds),
      loop_m_(2 * leg_m_ + 2 * std::numbers::pi * radius_m_),
      along_e_(std::sin(inbound_course_deg / kDegreesPerRadian)),
      along_n_(std::cos(inbound_course_deg / kDegreesPerRadian)) {
  const LocalScale scale = local_scale(fix_lat_deg);
  degrees_per_metre_lat_ = scale.deg_lat_per_m;
  degrees_per_metre_lon_ = scale.deg_lon_per_m;
}

void Racetrack::at(double loop_m, double& lat_deg, double& lon_deg, double& trk_deg) const {
  double s = std::fmod(loop_m, loop_m_);
  if (s < 0) s += loop_m_;
  // u: along the inbound course; w: to its right, where a right-hand pattern lies.
  const double ue = along_e_, un = along_n_;
  const double we = un, wn = -ue;
  const double r = radius_m_;
  const double half_turn = std::numbers::pi * r;
  double along = 0, right = 0, turned_deg = 0;  // position in (u, w) and track − course
  if (s < half_turn) {  // outbound turn from the fix
    const double phi = s / r;
    along = r * std::sin(phi);
    right = r * (1 - std::cos(phi));
    turned_deg = phi * kDegreesPerRadian;
  } else if (s < half_turn + leg_m_) {  // outbound leg
    along = -(s - half_turn);
    right = 2 * r;
    turned_deg = 180;
  } else if (s < 2 * half_turn + leg_m_) {  // inbound turn
    const double phi = (s - half_turn - leg_m_) / r;
    along = -leg_m_ - r * std::sin(phi);
    right = r + r * std::cos(phi);
    turned_deg = 180 + phi * kDegreesPerRadian;
  } else {  // inbound leg back to the fix
    along = -leg_m_ + (s - 2 * half_turn - leg_m_);
    right = 0;
    turned_deg = 0;
  }
  const double east = along * ue + right * we;
  const double north = along * un + right * wn;
  lat_deg = fix_lat_deg_ + north * degrees_per_metre_lat_;
  lon_deg = GeographicLib::Math::AngNormalize(fix_lon_deg_ + east * degrees_per_metre_lon_);
  trk_deg = wrap_360(course_deg_ + turned_deg);
}

// ---------------------------------------------------------------- VerticalProfile

VerticalProfile VerticalProfile::level(double alt_ft) {
  return change(alt_ft, 0.0, 0.0, alt_ft);
}

VerticalProfile VerticalProfile::change(double start_ft, double change_time, double rate_fpm,
                                        double target_ft) {
  VerticalProfile p;
  p.kind = Kind::Scheduled;
  p.start_ft = start_ft;
  p.change_time = change_time;
  p.rate_fpm = rate_fpm;
  p.target_ft = target_ft;
  return p;
}

VerticalProfile VerticalProfile::glide(double cruise_ft, double floor_ft, double slope_ft_per_m) {
  VerticalProfile p;
  p.kind = Kind::Glide;
  p.cruise_ft = cruise_ft;
  p.floor_ft = floor_ft;
  p.slope_ft_per_m = slope_ft_per_m;
  return p;
}

VerticalProfile VerticalProfile::route(double departure_floor_ft, double climb_ft_per_m, double cruise_ft,
                                       double floor_ft, double slope_ft_per_m, double route_m) {
  VerticalProfile p = glide(cruise_ft, floor_ft, slope_ft_per_m);
  p.kind = Kind::Route;
  p.departure_floor_ft = departure_floor_ft;
  p.climb_ft_per_m = climb_ft_per_m;
  p.route_m = route_m;
  return p;
}

void scheduled_altitude(const VerticalProfile& profile, double t, double& alt_ft, double& vr_fpm) {
  alt_ft = profile.start_ft;
  vr_fpm = 0;
  if (profile.rate_fpm == 0.0 || t <= profile.change_time) return;
  const double moved = profile.start_ft + profile.rate_fpm * (t - profile.change_time) / 60.0;
  const bool reached = profile.rate_fpm > 0 ? moved >= profile.target_ft : moved <= profile.target_ft;
  alt_ft = reached ? profile.target_ft : moved;
  vr_fpm = reached ? 0.0 : profile.rate_fpm;
}

// ---------------------------------------------------------------- Flight

TruthState Flight::at(double t) const {
  TruthState state;
  double remaining_m = 0;
  if (hold != nullptr && t < leg_start_time) {
    hold->at(hold_start_m + hold->speed_mps() * (t - begin_time), state.lat_deg, state.lon_deg,
             state.trk_deg);
    state.gs_mps = hold->speed_mps();
  } else {
    double flown = 0, azimuth = 0;
    leg.speed.advance(leg.length_m, std::max(0.0, t - leg_start_time), flown, state.gs_mps);
    leg.line->Position(leg.arc_after(flown), state.lat_deg, state.lon_deg, azimuth);
    state.trk_deg = wrap_360(leg.direction > 0 ? azimuth : azimuth + 180.0);
    remaining_m = leg.length_m - flown;
  }
  if (vertical.kind == VerticalProfile::Kind::Scheduled) {
    scheduled_altitude(vertical, t, state.alt_ft, state.vr_fpm);
    return state;
  }
  const double on_path = vertical.floor_ft + vertical.slope_ft_per_m * remaining_m;
  // A glide never climbs: its climb lies above any altitude.
  const double climbing = vertical.kind == VerticalProfile::Kind::Route
                              ? vertical.departure_floor_ft + vertical.climb_ft_per_m * (vertical.route_m - remaining_m)
                              : std::numeric_limits<double>::infinity();
  state.alt_ft = std::min({vertical.cruise_ft, on_path, climbing});
  // Along the path: d(alt)/dt = ±slope · ground speed (ft/s → ft/min).
  if (on_path < vertical.cruise_ft && on_path <= climbing) {
    state.vr_fpm = -vertical.slope_ft_per_m * state.gs_mps * 60.0;
  } else if (climbing < vertical.cruise_ft) {
    state.vr_fpm = vertical.climb_ft_per_m * state.gs_mps * 60.0;
  } else {
    state.vr_fpm = 0.0;
  }
  return state;
}

double Flight::leg_end_time() const {
  return leg_start_time + leg.speed.time_between(leg.length_m, 0.0);
}

}  // namespace kew::replay::detail
