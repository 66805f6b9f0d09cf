#pragma once
// Exact linear closest-point-of-approach test of one pair (design §4.4).
// Both aircraft move in straight lines at constant velocity (horizontal in the plane,
// vertical by vertical rate). The pair is in conflict when, for some τ' in [0, T], the
// horizontal distance is below S_h and the vertical distance below S_v at the same τ',
// and, for a pair vertically apart now, the vertical rates bring it below S_v less the
// altimetry tolerance no later than T_v: the
// intersection of the two open time intervals, each from a quadratic or linear
// inequality solved in closed form, clipped to [0, T].

#include <limits>

#include "kew/geometry/vector2.hpp"
#include "kew/util/units.hpp"

namespace kew::probe {

/// One aircraft's state at the evaluation time, in the plane and SI units.
struct Kinematics {
  geometry::Point2 position;   ///< m
  geometry::Vector2 velocity;  ///< m/s
  double altitude_m = 0.0;
  double vertical_rate_mps = 0.0;
  /// Vertical intent (design §4.4): the altitude (m) at which the climb or descent stops,
  /// reached in (level_off_m − altitude_m) / vertical_rate_mps > 0 s; NaN: none, the
  /// vertical prediction is linear. Set only for an aircraft moving towards it.
  double level_off_m = std::numeric_limits<double>::quiet_NaN();
  /// Turn hypothesis (design §4.4): rate at which the velocity turns in the plane (rad/s,
  /// counter-clockwise positive); 0: none. Read only by turn_conflict().
  double turn_rate_rps = 0.0;

  bool levels_off() const { return level_off_m == level_off_m; }  // not NaN
};

/// The fields of `k` in checkpoint order (util/checkpoint_io.hpp: `io` is a
/// CheckpointWriter or CheckpointReader): the one list every checkpoint holding a
/// Kinematics writes and reads.
template <class Io, class K>
void checkpoint_fields(Io& io, K& k) {
  io.field(k.position.x);
  io.field(k.position.y);
  io.field(k.velocity.x);
  io.field(k.velocity.y);
  io.field(k.altitude_m);
  io.field(k.vertical_rate_mps);
  io.field(k.level_off_m);
  io.field(k.turn_rate_rps);
}

/// `k` moved on by dt ≥ 0 s: horizontally in a straight line (as the kinetic engine
/// moves its points), vertically up to the level-off altitude, where it stays.
inline Kinematics extrapolated(const Kinematics& k, double dt) {
  Kinematics out = k;
  out.position = k.position + dt * k.velocity;
  out.altitude_m += dt * k.vertical_rate_mps;
  if (k.levels_off() && k.vertical_rate_mps != 0.0 && (out.altitude_m - k.level_off_m) * k.vertical_rate_mps >= 0.0) {
    out.altitude_m = k.level_off_m;
    out.vertical_rate_mps = 0.0;
    out.level_off_m = std::numeric_limits<double>::quiet_NaN();  // levelled: plain level flight
  }
  return out;
}

struct SeparationMinima {
  double horizontal_m = 9260.0;  ///< S_h (> 0); default 5 NM
  double vertical_m = 304.8;     ///< S_v (> 0); default 1,000 ft
  double lookahead_s = 120.0;    ///< T (≥ 0)
  /// T_v (≥ 0, s): a pair vertically apart now is in conflict only when its vertical
  /// rates bring it below S_v − altimetry_tolerance_m (a real loss, not the adjacent
  /// level) within T_v (design §4.4). Aircraft level off at cleared levels kew does not
  /// know; a climb carried on for two minutes through the level above is the commonest
  /// nuisance alert. A pair already within S_v is predicted linearly for the whole
  /// look-ahead (a divergence is trusted). With altimetry_tolerance_m = 0 and T_v ≥ T:
  /// the plain linear prediction.
  double vertical_lookahead_s = 30.0;
  /// Altimetry tolerance (≥ 0, m; default 200 ft): aircraft at adjacent levels read as
  /// little as S_v − this apart (altimetry error, 25 ft and 100 ft rounding), and are
  /// separated. Also the level-pair rule's (design §4.5).
  double altimetry_tolerance_m = 200.0 * units::kMetresPerFoot;
};

struct ConflictGeometry {
  bool in_conflict = false;
  /// Horizontal and vertical separation both below minima now (τ' = 0).
  bool lost_now = false;
  /// Start of the first interval in [0, T] with both separations below minima (s); only
  /// meaningful when in_conflict.
  double t_los_s = 0.0;
  /// End of that interval (s), ≤ T.
  double t_end_s = 0.0;
  /// Time of minimum horizontal distance, clamped to [0, T] (s).
  double t_cpa_s = 0.0;
  double cpa_h_m = 0.0;  ///< horizontal distance at t_cpa (m)
  double cpa_v_m = 0.0;  ///< vertical distance at t_cpa (m, ≥ 0)
  double sep_h_m = 0.0;  ///< horizontal distance now (m)
  double sep_v_m = 0.0;  ///< vertical distance now (m, ≥ 0)
  /// The vertical prediction of either aircraft levels off within the look-ahead.
  bool level_off = false;
};

/// Evaluates the pair (a, b). Symmetric: swapping a and b gives the same figures up to
/// rounding; callers that need bit-identical results order the pair canonically.
ConflictGeometry evaluate_pair(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima);

/// evaluate_pair(a, b, minima).in_conflict, computed the same way but without the
/// figures (no square roots unless the horizontal test needs one): the probe's fast
/// path for the many pairs that are clear.
bool in_conflict(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima);

/// The turn hypothesis (design §4.4): the pair under evaluate_pair()'s vertical model,
/// with each aircraft whose turn_rate_rps ≠ 0 flying an arc at constant speed and rate of
/// turn for the whole look-ahead instead of a straight line. The horizontal window is
/// found by stepping with the bound |d/ds distance| ≤ |v_a| + |v_b|, never more than
/// kTurnStep_s at a time where the distance is within that bound of S_h: a window shorter
/// than kTurnStep_s can be missed. Figures: t_cpa to within 1 ms of the sampled minimum.
ConflictGeometry turn_conflict(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima);
/// turn_conflict(a, b, minima).in_conflict, decided the same way without the figures.
bool in_turn_conflict(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima);
inline constexpr double kTurnStep_s = 0.05;

/// Position after s ≥ 0 seconds along the arc of turn_rate_rps (a straight line when 0).
geometry::Point2 position_along_turn(const Kinematics& k, double s);

/// When a turning aircraft is also predicted along its arc (design §4.4).
struct TurnHypothesis {
  bool enabled = false;
  /// Turning: |rate of turn| at least this (deg/s, > 0). A rate-one turn is 3 deg/s; an
  /// airliner banked 25° at cruise speed turns about 1.5 deg/s.
  double min_rate_dps = 1.0;
};

/// True when the pair keeps its vertical separation for ever: the same vertical rate, no
/// level-off, and at least S_v apart. in_conflict() is then false, decided the same way
/// (an empty vertical interval), so callers may skip it; inline because most candidate
/// pairs of en-route traffic are level at different flight levels.
inline bool vertically_apart_for_ever(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima) {
  const double dz = b.altitude_m - a.altitude_m;
  const double wz = b.vertical_rate_mps - a.vertical_rate_mps;
  return wz == 0.0 && !a.levels_off() && !b.levels_off() && !(dz < minima.vertical_m && -dz < minima.vertical_m);
}

}  // namespace kew::probe
