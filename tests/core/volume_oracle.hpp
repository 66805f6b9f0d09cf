#pragma once
// Brute force for kew_volume's entry(): steps along the look-ahead, tests each position
// with a point-in-volume test of its own, and bisects where the answer changes.
//
// Independence. Nothing here uses the gnomonic projection or kew_volume's crossings.
// A polygon's point test is exact for geodesic edges on the ellipsoid: a ray from P along
// the geodesic through P heading north is crossed by edge AB iff A and B are on opposite
// sides of that geodesic (east and west of P by the azimuths P→A, P→B) and P is on the
// south side of AB (the azimuths at A of A→B and A→P). A circle's test is the geodesic
// distance. P is on an edge (so inside) when its cross-track distance s_AP·|sin α| from
// the edge, α the angle at A between A→B and A→P, is at most kOnEdge_m and its along-track
// distance s_AP·cos α is within the edge: that is for a path laid along an edge, and is
// far below entry()'s kBoundaryTolerance_m, which entry() applies only at its exact
// crossing points and at t = 0. The altitude is computed here from
// the motion's fields.
//
// Steps. From a position where the aircraft is outside, nothing can be inside before a
// lower bound on the time to reach the volume: horizontally the distance to the
// boundary in a central projection (through the Earth's centre onto the plane tangent
// at the volume's centre, which draws great ellipses straight; a great ellipse and a
// geodesic of 200 km differ by metres, covered by a 20 m margin and a factor 0.5), or
// the geodesic distance to the centre less the extent; vertically the height to the band
// at the current rate. The step is that bound, never less than `min_step_s`: an inside
// stretch shorter than min_step_s (a graze) can be missed. Transitions are bisected to
// 1 µs.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geodesic.hpp>

#include "kew/volume/entry.hpp"
#include "kew/volume/volume.hpp"

namespace kew::test {

struct OracleResult {
  bool inside_now = false;
  std::optional<double> entry_s;
  std::optional<double> exit_s;  ///< first time after entry_s it is outside, if before T
  int evaluations = 0;
};

class VolumeOracle {
 public:
  explicit VolumeOracle(const volume::Volume& v) : v_(v) {
    const auto& g = GeographicLib::Geodesic::WGS84();
    for (const volume::Ring& ring : v.rings()) {
      std::vector<double> azimuths, lengths;
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const volume::LatLon a = ring[i], b = ring[(i + 1) % ring.size()];
        double s12 = 0.0, azi1 = 0.0, azi2 = 0.0;
        g.Inverse(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, s12, azi1, azi2);
        azimuths.push_back(azi1);
        lengths.push_back(s12);
      }
      edge_azimuths_.push_back(azimuths);
      edge_lengths_.push_back(lengths);
    }
    // The central projection's frame at the centre.
    centre_ = ecef(v.centre());
    radius_ = std::sqrt(dot3(centre_, centre_));
    for (double& x : centre_) x /= radius_;
    const double lon = v.centre().lon_deg * kDeg;
    e1_ = {-std::sin(lon), std::cos(lon), 0.0};
    e2_ = {centre_[1] * e1_[2] - centre_[2] * e1_[1], centre_[2] * e1_[0] - centre_[0] * e1_[2],
           centre_[0] * e1_[1] - centre_[1] * e1_[0]};
    for (const volume::Ring& ring : v.rings()) {
      std::vector<std::array<double, 2>> plane;
      for (const volume::LatLon& p : ring) plane.push_back(*central(p));
      plane_.push_back(plane);
    }
  }

  bool inside_area(volume::LatLon p) const {
    const double d = distance_from_centre(p);
    if (v_.is_circle()) return d <= v_.extent_m();
    if (d > v_.extent_m() + 1000.0) return false;
    bool inside = true;
    for (std::size_t r = 0; r < v_.rings().size(); ++r) {
      const int where = in_ring(p, r);
      if (where == 0) return true;  // on a boundary
      inside = inside && (where > 0) == (r == 0);
    }
    return inside;
  }

  double altitude(const volume::Motion& m, double t) const {
    double z = m.alt_ft + m.vr_fpm * t / 60.0;
    if (m.sel_ft && ((m.vr_fpm > 0.0 && m.alt_ft < *m.sel_ft && z > *m.sel_ft) ||
                     (m.vr_fpm < 0.0 && m.alt_ft > *m.sel_ft && z < *m.sel_ft)))
      z = *m.sel_ft;
    return z;
  }

  volume::LatLon position(const volume::Motion& m, double t) const {
    volume::LatLon p;
    GeographicLib::Geodesic::WGS84().Direct(m.start.lat_deg, m.start.lon_deg, m.track_deg,
                                            m.gs_kt * 1852.0 / 3600.0 * t, p.lat_deg, p.lon_deg);
    return p;
  }

  bool inside(const volume::Motion& m, double t) const {
    const double z = altitude(m, t);
    return v_.band().floor_ft <= z && z <= v_.band().ceiling_ft && inside_area(position(m, t));
  }

  /// First entry in [0, T] (and the exit after it), stepping at least `min_step_s`.
  OracleResult run(const volume::Motion& m, double horizon_s, double min_step_s = 0.01) const {
    OracleResult out;
    const auto test = [&](double t) {
      ++out.evaluations;
      return inside(m, t);
    };
    double t = 0.0;
    if (test(0.0)) {
      out.inside_now = true;
      out.entry_s = 0.0;
    }
    while (!out.entry_s && t < horizon_s) {
      const double next = std::min(horizon_s, t + std::max(min_step_s, time_to_change(m, t, false)));
      if (test(next)) out.entry_s = bisect(test, t, next);
      t = next;
    }
    if (!out.entry_s) return out;
    t = *out.entry_s;
    while (t < horizon_s) {
      const double next = std::min(horizon_s, t + std::max(min_step_s, time_to_change(m, t, true)));
      if (!test(next)) {
        out.exit_s = bisect([&](double x) { return !test(x); }, t, next);
        break;
      }
      t = next;
    }
    return out;
  }

 private:
  static constexpr double kDeg = 3.14159265358979323846 / 180.0;
  static constexpr double kOnEdge_m = 1e-6;
  using V3 = std::array<double, 3>;
  static double dot3(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

  static V3 ecef(volume::LatLon p) {
    const double a = GeographicLib::Constants::WGS84_a(), f = GeographicLib::Constants::WGS84_f();
    const double e2 = f * (2.0 - f);
    const double lat = p.lat_deg * kDeg, lon = p.lon_deg * kDeg;
    const double n = a / std::sqrt(1.0 - e2 * std::sin(lat) * std::sin(lat));
    return {n * std::cos(lat) * std::cos(lon), n * std::cos(lat) * std::sin(lon), n * (1.0 - e2) * std::sin(lat)};
  }

  // Plane coordinates (m) of p in the central projection, or none on the far side.
  std::optional<std::array<double, 2>> central(volume::LatLon p) const {
    const V3 x = ecef(p);
    const double along = dot3(x, centre_);
    if (along <= 0.0) return std::nullopt;
    return std::array<double, 2>{radius_ * dot3(x, e1_) / along, radius_ * dot3(x, e2_) / along};
  }

  double distance_from_centre(volume::LatLon p) const {
    double s12 = 0.0;
    GeographicLib::Geodesic::WGS84().Inverse(v_.centre().lat_deg, v_.centre().lon_deg, p.lat_deg, p.lon_deg, s12);
    return s12;
  }

  // +1 inside ring r, −1 outside, 0 on an edge.
  int in_ring(volume::LatLon p, std::size_t r) const {
    const auto& g = GeographicLib::Geodesic::WGS84();
    const volume::Ring& ring = v_.rings()[r];
    bool inside = false;
    double first_azimuth = 0.0, first_back = 0.0, first_distance = 0.0;
    double azimuth_a = 0.0, back_a = 0.0, distance_a = 0.0;  // P→A at P, A→P at A, |PA|
    for (std::size_t i = 0; i <= ring.size(); ++i) {
      const volume::LatLon b = ring[i % ring.size()];
      double s12 = 0.0, azimuth_b = 0.0, arrival = 0.0;
      if (i < ring.size()) {
        g.Inverse(p.lat_deg, p.lon_deg, b.lat_deg, b.lon_deg, s12, azimuth_b, arrival);
      } else {
        azimuth_b = first_azimuth;
        arrival = first_back - 180.0;
        s12 = first_distance;
      }
      const double back_b = arrival + 180.0;
      if (i == 0) {
        first_azimuth = azimuth_b;
        first_back = back_b;
        first_distance = s12;
      } else {
        const double angle = (back_a - edge_azimuths_[r][i - 1]) * kDeg;
        const double along = distance_a * std::cos(angle);
        if (distance_a * std::abs(std::sin(angle)) <= kOnEdge_m && along >= 0.0 &&
            along <= edge_lengths_[r][i - 1])
          return 0;
        const bool east_a = std::sin(azimuth_a * kDeg) > 0.0, east_b = std::sin(azimuth_b * kDeg) > 0.0;
        if (east_a != east_b) {
          const bool right = std::sin((back_a - edge_azimuths_[r][i - 1]) * kDeg) > 0.0;
          if (east_b ? right : !right) inside = !inside;
        }
      }
      azimuth_a = azimuth_b;
      back_a = back_b;
      distance_a = s12;
    }
    return inside ? 1 : -1;
  }

  // A lower bound (s) on the time until the state can change: entering (`inside` false)
  // or leaving.
  double time_to_change(const volume::Motion& m, double t, bool inside) const {
    const double infinity = std::numeric_limits<double>::infinity();
    const double z = altitude(m, t);
    const double floor = v_.band().floor_ft, ceiling = v_.band().ceiling_ft;
    const double rate = std::abs(m.vr_fpm) / 60.0;  // ft/s, never exceeded
    double vertical = 0.0;
    if (z < floor || z > ceiling) {
      const bool towards = (z < floor && m.vr_fpm > 0.0) || (z > ceiling && m.vr_fpm < 0.0);
      vertical = towards ? std::min(std::abs(floor - z), std::abs(ceiling - z)) / rate : infinity;
    } else {
      vertical = rate > 0.0 ? std::min(z - floor, ceiling - z) / rate : infinity;
    }
    const double speed = m.gs_kt * 1852.0 / 3600.0;
    const volume::LatLon p = position(m, t);
    double metres = std::abs(distance_from_centre(p) - v_.extent_m());  // circle; polygon from outside
    if (!v_.is_circle()) {
      if (distance_from_centre(p) <= v_.extent_m() + 1000.0) metres = 0.0;
      if (const auto q = central(p)) metres = std::max(metres, 0.5 * plane_distance(*q) - 20.0);
    } else {
      metres *= 0.9;
    }
    const double horizontal = speed > 0.0 ? std::max(0.0, metres) / speed : infinity;
    if (inside) return std::min(vertical, horizontal);
    const bool vertical_in = !(z < floor || z > ceiling);
    const bool horizontal_in = inside_area(p);
    return std::max(vertical_in ? 0.0 : vertical, horizontal_in ? 0.0 : horizontal);
  }

  double plane_distance(const std::array<double, 2>& q) const {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& ring : plane_) {
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto& a = ring[i];
        const auto& b = ring[(i + 1) % ring.size()];
        const double dx = b[0] - a[0], dy = b[1] - a[1];
        const double u = std::clamp(((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
        best = std::min(best, std::hypot(q[0] - a[0] - u * dx, q[1] - a[1] - u * dy));
      }
    }
    return best;
  }

  template <class Test>
  static double bisect(Test test, double lo, double hi) {  // false at lo, true at hi
    while (hi - lo > 1e-6) {
      const double m = 0.5 * (lo + hi);
      (test(m) ? hi : lo) = m;
    }
    return hi;
  }

  const volume::Volume& v_;
  std::vector<std::vector<double>> edge_azimuths_, edge_lengths_;
  V3 centre_{}, e1_{}, e2_{};
  double radius_ = 0.0;
  std::vector<std::vector<std::array<double, 2>>> plane_;
};

}  // namespace kew::test
