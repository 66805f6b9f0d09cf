#pragma once
// Exact linear closest-point-of-approach test of one pair (design §4.4).
// Both aircraft move in straight lines at constant velocity (horizontal in the plane,
// vertical by vertical rate). The pair is in conflict when, for some τ' in [0, T], the
// horizontal distance is below S_h and the vertical distance below S_v at the same τ',
// and, for a pair vertically apart now, the vertical rates bring it below S_v less the
// altimetry tolerance no later than T_v: the
// intersection of the two open time intervals, each from a quadratic or linear
// inequality solved in closed form, clipped to [0, T].

#include "kew/geometry/vector2.hpp"

namespace kew::probe {

/// One aircraft's state at the evaluation time, in the plane and SI units.
struct Kinematics {
  geometry::Point2 position;   ///< m
  geometry::Vector2 velocity;  ///< m/s
  double altitude_m = 0.0;
  double vertical_rate_mps = 0.0;
};

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
  double altimetry_tolerance_m = 200.0 * 0.3048;
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
};

/// Evaluates the pair (a, b). Symmetric: swapping a and b gives the same figures up to
/// rounding; callers that need bit-identical results order the pair canonically.
ConflictGeometry evaluate_pair(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima);

/// evaluate_pair(a, b, minima).in_conflict, computed the same way but without the
/// figures (no square roots unless the horizontal test needs one): the probe's fast
/// path for the many pairs that are clear.
bool in_conflict(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima);

/// True when the pair keeps its vertical separation for ever: the same vertical rate and
/// at least S_v apart. in_conflict() is then false, decided the same way (an empty
/// vertical interval), so callers may skip it; inline because most candidate pairs of
/// en-route traffic are level at different flight levels.
inline bool vertically_apart_for_ever(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima) {
  const double dz = b.altitude_m - a.altitude_m;
  const double wz = b.vertical_rate_mps - a.vertical_rate_mps;
  return wz == 0.0 && !(dz < minima.vertical_m && -dz < minima.vertical_m);
}

}  // namespace kew::probe
