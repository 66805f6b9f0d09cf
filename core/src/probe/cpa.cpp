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

// Up to three open intervals in increasing order (a piecewise-linear vertical
// distance has at most three pieces: before, between and after the two level-offs).
struct Intervals {
  Interval item[3];
  int n = 0;
  void add(Interval i) {
    if (i.empty()) return;
    // Pieces meet where the distance is continuous: intervals that touch are one.
    if (n > 0 && item[n - 1].hi >= i.lo) {
      item[n - 1].hi = std::max(item[n - 1].hi, i.hi);
      return;
    }
    item[n++] = i;
  }
};

// One aircraft's vertical prediction: z(s) = z + w·min(s, stop), stop = ∞ without a
// level-off (design §4.4, vertical intent).
struct VerticalMotion {
  double z = 0.0, w = 0.0, stop = kInfinity;
  double at(double s) const { return z + w * std::min(s, stop); }
  double rate(double s) const { return s < stop ? w : 0.0; }
};

// |zb(s) − za(s)|; for two straight lines, in the one rounding the figures always had.
double vertical_distance(const VerticalMotion& a, const VerticalMotion& b, double s) {
  if (a.stop == kInfinity && b.stop == kInfinity) return std::abs((b.z - a.z) + s * (b.w - a.w));
  return std::abs(b.at(s) - a.at(s));
}

VerticalMotion vertical_motion(const Kinematics& k) {
  if (!k.levels_off() || k.vertical_rate_mps == 0.0) return {k.altitude_m, k.vertical_rate_mps, kInfinity};
  return {k.altitude_m, k.vertical_rate_mps, std::max(0.0, (k.level_off_m - k.altitude_m) / k.vertical_rate_mps)};
}

// { s : |zb(s) − za(s)| < r }, piece by piece between the level-off times.
Intervals closer_than(const VerticalMotion& a, const VerticalMotion& b, double r) {
  double cuts[4] = {-kInfinity, a.stop, b.stop, kInfinity};
  if (cuts[1] > cuts[2]) std::swap(cuts[1], cuts[2]);
  Intervals out;
  for (int k = 0; k < 3; ++k) {
    const double from = cuts[k], to = cuts[k + 1];
    if (!(from < to)) continue;
    const double ref = std::isfinite(from) ? from : (std::isfinite(to) ? to : 0.0);
    const double d = b.at(ref) - a.at(ref);
    const double probe_s = std::isfinite(from) ? from : ref - 1.0;  // a time inside the piece
    const double slope = b.rate(probe_s) - a.rate(probe_s);
    Interval piece;
    if (slope == 0.0) {
      if (std::abs(d) < r) piece = {from, to};
    } else {
      double s1 = ref + (-r - d) / slope, s2 = ref + (r - d) / slope;
      if (s1 > s2) std::swap(s1, s2);
      piece = {std::max(s1, from), std::min(s2, to)};
    }
    out.add(piece);
  }
  return out;
}

// The vertical window of a pair with a level-off: the rule of vertical_interval() on the
// piecewise distance.
Intervals vertical_intervals(const VerticalMotion& a, const VerticalMotion& b, const SeparationMinima& m) {
  const double r = m.vertical_m;
  Intervals v = closer_than(a, b, r);
  if (std::abs(b.z - a.z) < r - kFeetRounding_m) return v;
  // Apart now: only a real loss within T_v counts, and the window starts no earlier than now.
  const Intervals real = closer_than(a, b, std::max(r - m.altimetry_tolerance_m, 0.0));
  double real_from = kInfinity;
  for (int k = 0; k < real.n; ++k)
    if (real.item[k].hi > 0.0) {
      real_from = std::max(real.item[k].lo, 0.0);
      break;
    }
  if (real_from >= m.vertical_lookahead_s) return {};
  Intervals clipped;
  for (int k = 0; k < v.n; ++k) clipped.add({std::max(v.item[k].lo, 0.0), v.item[k].hi});
  return clipped;
}

Intervals vertical_window(const Kinematics& a, const Kinematics& b, const SeparationMinima& m) {
  const VerticalMotion va = vertical_motion(a), vb = vertical_motion(b);
  if (va.stop == kInfinity && vb.stop == kInfinity) {
    Intervals v;
    v.add(vertical_interval(vb.z - va.z, vb.w - va.w, m.vertical_m, m.altimetry_tolerance_m, m.vertical_lookahead_s));
    return v;
  }
  return vertical_intervals(va, vb, m);
}

bool overlaps_lookahead(const Intervals& v, double T) {
  for (int k = 0; k < v.n; ++k)
    if (v.item[k].hi > 0.0 && v.item[k].lo < T) return true;
  return false;
}

bool contains_now(const Intervals& v) {
  for (int k = 0; k < v.n; ++k)
    if (v.item[k].lo < 0.0 && 0.0 < v.item[k].hi) return true;
  return false;
}

struct Window {
  bool in_conflict = false;
  bool lost_now = false;
  double lo = 0.0, hi = 0.0;
};

// The conflict window of the pair, shared by evaluate_pair and in_conflict so that the
// two agree bit for bit.
Window conflict_window(const Kinematics& a, const Kinematics& b, const SeparationMinima& m) {
  Window out;
  const Intervals v = vertical_window(a, b, m);
  // A vertical window wholly before now or after T cannot overlap [0, T].
  if (!overlaps_lookahead(v, m.lookahead_s)) return out;
  const Interval h = horizontal_interval(b.position - a.position, b.velocity - a.velocity, m.horizontal_m);
  if (h.empty()) return out;
  out.lost_now = h.lo < 0.0 && 0.0 < h.hi && contains_now(v);
  for (int k = 0; k < v.n; ++k) {
    const double lo = std::max({0.0, h.lo, v.item[k].lo});
    const double hi = std::min({m.lookahead_s, h.hi, v.item[k].hi});
    if (lo < hi) {
      out.lo = lo;
      out.hi = hi;
      out.in_conflict = true;
      return out;
    }
  }
  out.in_conflict = out.lost_now;
  return out;
}

}  // namespace

bool in_conflict(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima) {
  return conflict_window(a, b, minima).in_conflict;
}

ConflictGeometry evaluate_pair(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima) {
  ConflictGeometry g;
  const geometry::Vector2 d = b.position - a.position;
  const geometry::Vector2 w = b.velocity - a.velocity;
  const double T = minima.lookahead_s;
  const VerticalMotion va = vertical_motion(a), vb = vertical_motion(b);

  g.sep_h_m = geometry::norm(d);
  g.sep_v_m = std::abs(vb.z - va.z);
  const double ww = geometry::dot(w, w);
  g.t_cpa_s = ww > 0.0 ? std::clamp(-geometry::dot(d, w) / ww, 0.0, T) : 0.0;
  g.cpa_h_m = geometry::norm(d + g.t_cpa_s * w);
  g.cpa_v_m = vertical_distance(va, vb, g.t_cpa_s);
  g.level_off = std::min(va.stop, vb.stop) < T;

  const Window window = conflict_window(a, b, minima);
  g.lost_now = window.lost_now;
  if (!window.in_conflict) return g;
  g.in_conflict = true;
  g.t_los_s = window.lo;
  g.t_end_s = std::max(window.lo, window.hi);
  return g;
}

geometry::Point2 position_along_turn(const Kinematics& k, double s) {
  const double o = k.turn_rate_rps;
  if (o == 0.0) return k.position + s * k.velocity;
  // ∫₀ˢ R(o·u) du · v, R the rotation by o·u.
  const double c = std::cos(o * s), sn = std::sin(o * s);
  const geometry::Vector2 v = k.velocity;
  return k.position + (1.0 / o) * geometry::Vector2{sn * v.x + (c - 1.0) * v.y, (1.0 - c) * v.x + sn * v.y};
}

namespace {

double distance_after(const Kinematics& a, const Kinematics& b, double s) {
  return geometry::norm(position_along_turn(b, s) - position_along_turn(a, s));
}

// The boundary between [x, y) where the distance crosses r (one side below, the other
// not), to 1 ms.
double crossing(const Kinematics& a, const Kinematics& b, double r, double x, double y) {
  const bool below_at_x = distance_after(a, b, x) < r;
  while (y - x > 1e-3) {
    const double mid = 0.5 * (x + y);
    ((distance_after(a, b, mid) < r) == below_at_x ? x : y) = mid;
  }
  return y;
}

}  // namespace

namespace {

// The conflict window along the arcs: in_conflict, lost_now, t_los_s and t_end_s of `g`.
void turn_window(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima, ConflictGeometry& g) {
  const double T = minima.lookahead_s;
  const double r = minima.horizontal_m;
  const Intervals v = vertical_window(a, b, minima);
  g.lost_now = distance_after(a, b, 0.0) < r && contains_now(v);
  // |d/ds distance| ≤ the sum of the speeds: from a distance D ≥ r, nothing can come
  // within r sooner than (D − r) / that sum.
  const double closing_bound = geometry::norm(a.velocity) + geometry::norm(b.velocity);
  for (int k = 0; k < v.n && !g.in_conflict; ++k) {
    const double from = std::max(0.0, v.item[k].lo), to = std::min(T, v.item[k].hi);
    double s = from, previous = from;
    while (s < to) {
      const double d = distance_after(a, b, s);
      if (d < r) {
        g.in_conflict = true;
        g.t_los_s = s == from ? s : crossing(a, b, r, previous, s);
        break;
      }
      previous = s;
      s += closing_bound > 0.0 ? std::max((d - r) / closing_bound, kTurnStep_s) : to;
    }
    if (!g.in_conflict) continue;
    // The end of the window: step the same way inside it.
    s = g.t_los_s;
    for (;;) {
      const double d = distance_after(a, b, s);
      if (d >= r) {
        g.t_end_s = crossing(a, b, r, previous, s);
        break;
      }
      previous = s;
      const double next = s + (closing_bound > 0.0 ? std::max((r - d) / closing_bound, kTurnStep_s) : to);
      if (next >= to) {
        g.t_end_s = to;
        break;
      }
      s = next;
    }
  }
  if (!g.in_conflict && g.lost_now) g.in_conflict = true;
}

}  // namespace

bool in_turn_conflict(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima) {
  ConflictGeometry g;
  turn_window(a, b, minima, g);
  return g.in_conflict;
}

ConflictGeometry turn_conflict(const Kinematics& a, const Kinematics& b, const SeparationMinima& minima) {
  ConflictGeometry g;
  const double T = minima.lookahead_s;
  const VerticalMotion va = vertical_motion(a), vb = vertical_motion(b);
  g.sep_h_m = distance_after(a, b, 0.0);
  g.sep_v_m = std::abs(vb.z - va.z);
  g.level_off = std::min(va.stop, vb.stop) < T;
  turn_window(a, b, minima, g);
  if (!g.in_conflict) return g;
  // Closest approach: 1 s samples, then the best one refined by golden-section search.
  double best_s = 0.0, best_d = g.sep_h_m;
  for (double s = 1.0; s <= T; s += 1.0) {
    const double d = distance_after(a, b, s);
    if (d < best_d) best_d = d, best_s = s;
  }
  double lo = std::max(0.0, best_s - 1.0), hi = std::min(T, best_s + 1.0);
  while (hi - lo > 1e-3) {
    const double m1 = lo + 0.382 * (hi - lo), m2 = hi - 0.382 * (hi - lo);
    if (distance_after(a, b, m1) < distance_after(a, b, m2))
      hi = m2;
    else
      lo = m1;
  }
  g.t_cpa_s = distance_after(a, b, 0.5 * (lo + hi)) < best_d ? 0.5 * (lo + hi) : best_s;
  g.cpa_h_m = distance_after(a, b, g.t_cpa_s);
  g.cpa_v_m = vertical_distance(va, vb, g.t_cpa_s);
  return g;
}

}  // namespace kew::probe
