#include "kew/replay/state_based.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>

#include <GeographicLib/Constants.hpp>
#include <fmt/format.h>
#include "kew/util/units.hpp"

namespace kew::replay {

namespace {

constexpr double kDegree = M_PI / 180.0;

struct State {
  std::string source, id, callsign;
  double t = 0.0, lat = 0.0, lon = 0.0, alt_m = 0.0;
  double ve = 0.0, vn = 0.0, vz = 0.0;  // m/s east, north, up
  bool has_velocity = false;
  bool seen = false;
};

/// East and north of b from a (m), on the plane tangent at their mean latitude.
void offset_m(double lat_a, double lon_a, double lat_b, double lon_b, double& east, double& north) {
  static const double a = GeographicLib::Constants::WGS84_a();
  static const double f = GeographicLib::Constants::WGS84_f();
  static const double e2 = f * (2.0 - f);
  const double phi = 0.5 * (lat_a + lat_b) * kDegree;
  const double s = std::sin(phi);
  const double w = std::sqrt(1.0 - e2 * s * s);
  double dlon = lon_b - lon_a;
  if (dlon > 180.0) dlon -= 360.0;
  if (dlon < -180.0) dlon += 360.0;
  east = a / w * std::cos(phi) * dlon * kDegree;
  north = a * (1.0 - e2) / (w * w * w) * (lat_b - lat_a) * kDegree;
}

void update(State& s, const TrackReport& r) {
  double ve = 0.0, vn = 0.0;
  bool velocity = false;
  if (r.gs_kt && r.trk_deg) {
    ve = *r.gs_kt * units::kMpsPerKnot * std::sin(*r.trk_deg * kDegree);
    vn = *r.gs_kt * units::kMpsPerKnot * std::cos(*r.trk_deg * kDegree);
    velocity = true;
  } else if (s.seen && r.t > s.t) {
    double east = 0.0, north = 0.0;
    offset_m(s.lat, s.lon, r.lat_deg, r.lon_deg, east, north);
    ve = east / (r.t - s.t);
    vn = north / (r.t - s.t);
    velocity = true;
  }
  double vz = 0.0;
  if (r.vr_fpm)
    vz = *r.vr_fpm * units::kMetresPerFoot / 60.0;
  else if (s.seen && r.t > s.t)
    vz = (r.alt_ft * units::kMetresPerFoot - s.alt_m) / (r.t - s.t);
  s.t = r.t;
  s.lat = r.lat_deg;
  s.lon = r.lon_deg;
  s.alt_m = r.alt_ft * units::kMetresPerFoot;
  s.ve = ve;
  s.vn = vn;
  s.vz = vz;
  s.has_velocity = velocity;
  s.seen = true;
  if (!r.callsign.empty()) s.callsign = r.callsign;
}

struct Verdict {
  bool conflict = false;
  bool lost_now = false;
  double t_in = 0.0;
};

/// BlueSky's state-based test of one pair at `now`.
Verdict test_pair(const State& i, const State& j, double now, const StateBasedConfig& c) {
  double east = 0.0, north = 0.0;
  offset_m(i.lat, i.lon, j.lat, j.lon, east, north);
  // Both states moved on to now in straight lines.
  const double dx = east + j.ve * (now - j.t) - i.ve * (now - i.t);
  const double dy = north + j.vn * (now - j.t) - i.vn * (now - i.t);
  const double dz = (j.alt_m + j.vz * (now - j.t)) - (i.alt_m + i.vz * (now - i.t));
  const double du = j.ve - i.ve, dv = j.vn - i.vn, dvz = j.vz - i.vz;
  const double r = c.horizontal_m, h = c.vertical_ft * units::kMetresPerFoot, T = c.lookahead_s;
  const double reach = std::hypot(i.ve, i.vn) + std::hypot(j.ve, j.vn);
  const double d2 = dx * dx + dy * dy;
  if (d2 > (r + reach * T) * (r + reach * T)) return {};
  const double v2 = std::max(du * du + dv * dv, 1e-9);
  const double t_cpa = -(dx * du + dy * dv) / v2;
  const double dcpa2 = std::max(0.0, d2 - t_cpa * t_cpa * v2);
  if (dcpa2 >= r * r) return {};
  const double half = std::sqrt((r * r - dcpa2) / v2);
  const double in_h = t_cpa - half, out_h = t_cpa + half;
  double in_v = -1e9, out_v = 1e9;
  if (std::abs(dvz) > 1e-9) {
    const double a = (-h - dz) / dvz, b = (h - dz) / dvz;
    in_v = std::min(a, b);
    out_v = std::max(a, b);
  } else if (std::abs(dz) >= h) {
    return {};
  }
  const double in = std::max(in_h, in_v), out = std::min(out_h, out_v);
  Verdict v;
  v.conflict = in < out && out > 0.0 && in < T;
  v.lost_now = v.conflict && in <= 0.0;
  v.t_in = std::max(0.0, in);
  return v;
}

}  // namespace

std::vector<AlertSpan> state_based_alerts(std::span<const TrackReport> records, const StateBasedConfig& config) {
  std::vector<AlertSpan> alerts;
  std::vector<State> states;
  std::unordered_map<std::string, std::size_t> index;  // source + '\x1f' + id
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> open;  // state pair → alert
  std::uint64_t serial = 0;
  double next_step = -1.0;
  std::vector<std::size_t> live;

  const auto evaluate_at = [&](double now) {
    live.clear();
    double fastest = 0.0;
    for (std::size_t k = 0; k < states.size(); ++k) {
      const State& s = states[k];
      if (!s.seen || !s.has_velocity || now - s.t > config.timeout_s) continue;
      live.push_back(k);
      fastest = std::max(fastest, std::hypot(s.ve, s.vn));
    }
    // Pairs farther apart in latitude than any pair can close within T are clear: the
    // tracks in latitude order (the last report's, which is within timeout·v of now's).
    std::sort(live.begin(), live.end(), [&](std::size_t x, std::size_t y) {
      return states[x].lat != states[y].lat ? states[x].lat < states[y].lat : x < y;
    });
    constexpr double kMetresPerDegreeLatitude = 110000.0;  // below the meridian's 110,574 m at the equator
    const double reach_deg =
        (config.horizontal_m + 2.0 * fastest * (config.lookahead_s + config.timeout_s)) / kMetresPerDegreeLatitude;
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> still;
    for (std::size_t x = 0; x < live.size(); ++x) {
      for (std::size_t y = x + 1; y < live.size(); ++y) {
        if (states[live[y]].lat - states[live[x]].lat > reach_deg) break;
        const bool x_first = live[x] < live[y];  // pair keys and the test in a fixed order
        const State& i = states[x_first ? live[x] : live[y]];
        const State& j = states[x_first ? live[y] : live[x]];
        const Verdict v = test_pair(i, j, now, config);
        if (!v.conflict) continue;
        const std::pair<std::size_t, std::size_t> key{std::min(live[x], live[y]), std::max(live[x], live[y])};
        const Severity severity = v.lost_now ? Severity::Loss : v.t_in <= 60.0 ? Severity::Warning : Severity::Caution;
        auto it = open.find(key);
        if (it == open.end()) {
          const bool i_first = std::tie(i.source, i.id) < std::tie(j.source, j.id);
          const State& a = i_first ? i : j;
          const State& b = i_first ? j : i;
          AlertSpan span;
          span.id = fmt::format("sb{}", ++serial);
          span.a_source = a.source;
          span.a_id = a.id;
          span.a_callsign = a.callsign;
          span.b_source = b.source;
          span.b_id = b.id;
          span.b_callsign = b.callsign;
          span.opened_t = now;
          span.max_severity = severity;
          span.events = 1;
          alerts.push_back(std::move(span));
          still.emplace(key, alerts.size() - 1);
        } else {
          AlertSpan& span = alerts[it->second];
          if (static_cast<int>(severity) > static_cast<int>(span.max_severity)) span.max_severity = severity;
          still.emplace(key, it->second);
          open.erase(it);
        }
      }
    }
    for (const auto& [key, alert] : open) {  // clear now, or a party gone
      alerts[alert].ended_t = now;
      alerts[alert].end_reason = AlertEndReason::Cleared;
      ++alerts[alert].events;
    }
    open = std::move(still);
  };

  for (const TrackReport& r : records) {
    if (!(std::isfinite(r.t) && std::isfinite(r.lat_deg) && std::isfinite(r.lon_deg) && std::isfinite(r.alt_ft)))
      continue;
    if (next_step < 0.0) next_step = std::floor(r.t / config.step_s) * config.step_s + config.step_s;
    // The steps the data time passed, the latest of them only: a gap holds no records.
    if (r.t >= next_step) {
      const double step = std::floor(r.t / config.step_s) * config.step_s;
      evaluate_at(step);
      next_step = step + config.step_s;
    }
    std::string key = r.source;
    key += '\x1f';
    key += r.id;
    auto [it, inserted] = index.try_emplace(std::move(key), states.size());
    if (inserted) {
      states.emplace_back();
      states.back().source = r.source;
      states.back().id = r.id;
    }
    State& s = states[it->second];
    if (s.seen && r.t <= s.t) continue;
    update(s, r);
  }
  return alerts;
}

}  // namespace kew::replay
