#include "kew/probe/cpa.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kew::probe {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Interval {
  double lo = 0.0;
  double hi = -1.0;  // empty unless lo < hi
  bool empty() const { return !(lo < hi); }
};

// { s : |d + w·s| < r } for the 2D relative motion d + w·s.
Interval horizontal_interval(geometry::Vector2 d, geometry::Vector2 w, double r) {
  const double a = geometry::dot(w, w);
  const double b = geometry::dot(d, w);
  const double c = geometry::dot(d, d) - r * r;
  if (a == 0.0) return c < 0.0 ? Interval{-kInfinity, kInfinity} : Interval{};
  const double discriminant = b * b - a * c;
  if (discriminant <= 0.0) return {};
  // Roots of a s² + 2 b s + c; the numerically stable pair avoids cancellation.
  const double root = std::sqrt(discriminant);
  const double q = b >= 0.0 ? -(b + root) : -(b - root);
  double s1 = q / a;
  double s2 = q != 0.0 ? c / q : -s1;
  if (s1 > s2) std::swap(s1, s2);
  return {s1, s2};
}

// Altitudes arrive in feet and are compared in metres, where FL350 − FL340 reads a few
// 1e-14 m under 1,000 ft (35 of the 45 such pairs from 0 to 44,000 ft do). A separation
// at the minimum exactly is separation, so the test "apart now" allows this much rounding,
// far below the 1 ft resolution of every input.
constexpr double kFeetRounding_m = 1e-6;

// { s : |dz + wz·s| < r }, with the vertical look-ahead of design §4.4: a pair vertically
// apart now counts only when its vertical rates bring it below r − tolerance, a real loss
// rather than the adjacent level, within tv; its interval then starts no earlier than now.
// A pair already within r keeps its interval: a divergence is trusted for the whole
// look-ahead.
Interval vertical_interval(double dz, double wz, double r, double tolerance, double tv) {
  const bool apart_now = std::abs(dz) >= r - kFeetRounding_m;
  if (wz == 0.0) return apart_now ? Interval{} : Interval{-kInfinity, kInfinity};
  double s1 = (-r - dz) / wz;
  double s2 = (r - dz) / wz;
  if (s1 > s2) std::swap(s1, s2);
  if (apart_now) {
    const bool closing = dz * wz < 0.0;
    if (!closing) return {};
    const double real_loss = std::max(r - tolerance, 0.0);
    const double real_loss_from = (std::abs(dz) - real_loss) / std::abs(wz);
    if (real_loss_from >= tv) return {};
    s1 = std::max(s1, 0.0);
  }
  return {s1, s2};
}

struct Window {
  bool in_conflict = false;
  bool lost_now = false;
  double lo = 0.0, hi = 0.0;
};

// The conflict window of the pair, shared by evaluate_pair and in_conflict so that the
// two agree bit for bit.
Window conflict_window(geometry::Vector2 d, geometry::Vector2 w, double dz, double wz, const SeparationMinima& m) {
  Window out;
  const Interval v = vertical_interval(dz, wz, m.vertical_m, m.altimetry_tolerance_m, m.vertical_lookahead_s);
  // A vertical window wholly before now or after T cannot overlap [0, T].
  if (v.empty() || v.hi <= 0.0 || v.lo >= m.lookahead_s) return out;
  const Interval h = horizontal_interval(d, w, m.horizontal_m);
  if (h.empty()) return out;
  out.lo = std::max({0.0, h.lo, v.lo});
  out.hi = std::min({m.lookahead_s, h.hi, v.hi});
  out.lost_now = h.lo < 0.0 && 0.0 < h.hi && v.lo < 0.0 && 0.0 < v.hi;
  out.in_conflict = out.lo < out.hi || out.lost_now;
  return out;
}

}  // namespace

bool in_conflict(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima) {
  return conflict_window(b.position - a.position, b.velocity - a.velocity, b.altitude_m - a.altitude_m,
                         b.vertical_rate_mps - a.vertical_rate_mps, minima)
      .in_conflict;
}

ConflictGeometry evaluate_pair(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima) {
  ConflictGeometry g;
  const geometry::Vector2 d = b.position - a.position;
  const geometry::Vector2 w = b.velocity - a.velocity;
  const double dz = b.altitude_m - a.altitude_m;
  const double wz = b.vertical_rate_mps - a.vertical_rate_mps;
  const double T = minima.lookahead_s;

  g.sep_h_m = geometry::norm(d);
  g.sep_v_m = std::abs(dz);
  const double ww = geometry::dot(w, w);
  g.t_cpa_s = ww > 0.0 ? std::clamp(-geometry::dot(d, w) / ww, 0.0, T) : 0.0;
  g.cpa_h_m = geometry::norm(d + g.t_cpa_s * w);
  g.cpa_v_m = std::abs(dz + g.t_cpa_s * wz);

  const Window window = conflict_window(d, w, dz, wz, minima);
  g.lost_now = window.lost_now;
  if (!window.in_conflict) return g;
  g.in_conflict = true;
  g.t_los_s = window.lo;
  g.t_end_s = std::max(window.lo, window.hi);
  return g;
}

}  // namespace kew::probe
