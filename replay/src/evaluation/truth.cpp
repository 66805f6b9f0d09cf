#include "kew/replay/truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include <GeographicLib/Constants.hpp>

#include "kew/eligibility/eligibility.hpp"
#include "evaluation/truth_support.hpp"

namespace kew::replay {

namespace {

using namespace truth_rules;

constexpr double kDegree = 3.14159265358979323846 / 180.0;
using units::kMpsPerKnot;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::uint64_t pair_key(std::uint32_t i, std::uint32_t j) {
  if (i > j) std::swap(i, j);
  return (static_cast<std::uint64_t>(i) << 32) | j;
}
std::uint32_t key_first(std::uint64_t key) { return static_cast<std::uint32_t>(key >> 32); }
std::uint32_t key_second(std::uint64_t key) { return static_cast<std::uint32_t>(key & 0xffffffffu); }

// Longitude difference lon2 − lon1 in [−180, 180] (degrees), so lines across the
// antimeridian are short.
double longitude_difference(double lon1, double lon2) {
  double d = lon2 - lon1;
  if (d > 180.0) d -= 360.0;
  if (d < -180.0) d += 360.0;
  return d;
}

// Union–find over tracks. The root of a set is its lowest track, so the result does
// not depend on the order of the unions.
class Components {
 public:
  explicit Components(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  /// False when x and y were already one set.
  bool join(std::uint32_t x, std::uint32_t y) {
    x = find(x);
    y = find(y);
    if (x == y) return false;
    parent_[std::max(x, y)] = std::min(x, y);
    return true;
  }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace

double local_distance_m(double lat1_deg, double lon1_deg, double lat2_deg, double lon2_deg) {
  static const double a = GeographicLib::Constants::WGS84_a();
  static const double f = GeographicLib::Constants::WGS84_f();
  static const double e2 = f * (2.0 - f);
  const double phi = 0.5 * (lat1_deg + lat2_deg) * kDegree;
  const double s = std::sin(phi);
  const double w = std::sqrt(1.0 - e2 * s * s);
  const double prime_vertical = a / w;                     // N
  const double meridional = a * (1.0 - e2) / (w * w * w);  // M
  const double east = prime_vertical * std::cos(phi) * longitude_difference(lon1_deg, lon2_deg) * kDegree;
  const double north = meridional * (lat2_deg - lat1_deg) * kDegree;
  return std::hypot(east, north);
}

Truth::Truth(std::span<const TrackReport> records, const eligibility::AerodromeTable& aerodromes,
             SeparationStandard standard)
    : standard_(standard) {
  if (!(standard_.horizontal_m > 0.0 && standard_.horizontal_m <= 100.0 * kNauticalMile_m))
    throw std::invalid_argument("separation standard: horizontal minimum outside (0, 100 NM]");
  if (!(standard_.vertical_ft > kAltimetryTolerance_ft && standard_.vertical_ft <= 10000.0))
    throw std::invalid_argument("separation standard: vertical minimum outside (200, 10000] ft");
  add_records(records, aerodromes);
  for (Track& track : tracks_) prepare_track(track);
  std::unordered_map<std::uint64_t, PairTrace> found;
  sweep(found);
  // Content order from here on: the hash map's order must not reach any output.
  std::vector<std::pair<std::uint64_t, const PairTrace*>> traces;
  traces.reserve(found.size());
  for (const auto& [key, trace] : found) traces.emplace_back(key, &trace);
  std::sort(traces.begin(), traces.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  merge_aircraft(traces);
  build_losses(traces);
}

// The truth's lower limit at a position (TruthSample::lower_limit_ft).
static double lower_limit_at(const eligibility::AerodromeTable& aerodromes, double lat_deg, double lon_deg) {
  const eligibility::Aerodrome* aerodrome = aerodromes.nearest(lat_deg, lon_deg, kAerodromeRadius_m);
  return aerodrome ? std::max(kLowerLimit_ft, aerodrome->elevation_ft + kAerodromeHeight_ft) : kLowerLimit_ft;
}

void Truth::add_records(std::span<const TrackReport> records, const eligibility::AerodromeTable& aerodromes) {
  std::string key;
  for (const TrackReport& r : records) {
    const bool usable = std::isfinite(r.t) && std::isfinite(r.lat_deg) && std::isfinite(r.lon_deg) &&
                        std::isfinite(r.alt_ft) && std::abs(r.lat_deg) <= 90.0 && std::abs(r.lon_deg) <= 180.0;
    if (!usable) {
      ++figures_.records_refused;
      continue;
    }
    key.assign(r.source);
    key += '\x1f';
    key += r.id;
    auto [it, inserted] = index_.try_emplace(key, static_cast<TruthTrackId>(tracks_.size()));
    if (inserted) {
      tracks_.emplace_back();
      tracks_.back().info.source = r.source;
      tracks_.back().info.id = r.id;
    }
    Track& track = tracks_[it->second];
    if (!r.callsign.empty()) track.info.callsign = r.callsign;
    if (!track.info.address && r.address) track.info.address = r.address;
    if (r.mode3a && eligibility::is_discrete_mode3a(*r.mode3a) &&
        std::find(track.codes.begin(), track.codes.end(), *r.mode3a) == track.codes.end())
      track.codes.push_back(*r.mode3a);
    const double speed = r.gs_kt && std::isfinite(*r.gs_kt) && *r.gs_kt >= 0.0 ? *r.gs_kt : kNaN;
    track.points.push_back({r.t, r.lat_deg, r.lon_deg, r.alt_ft, speed, lower_limit_at(aerodromes, r.lat_deg, r.lon_deg),
                            r.on_ground, r.track_end});
    ++figures_.records;
  }
  figures_.tracks = tracks_.size();
}

void Truth::prepare_track(Track& track) const {
  std::vector<Point>& p = track.points;
  std::stable_sort(p.begin(), p.end(), [](const Point& x, const Point& y) { return x.t < y.t; });
  p.erase(std::unique(p.begin(), p.end(), [](const Point& x, const Point& y) { return x.t == y.t; }), p.end());
  track.info.records = p.size();

  std::vector<double> intervals;
  for (std::size_t i = 1; i < p.size(); ++i)
    if (p[i].t - p[i - 1].t <= kMaxGap_s) intervals.push_back(p[i].t - p[i - 1].t);
  if (intervals.empty()) {
    track.info.median_interval_s = kNaN;
  } else {
    // The lower median: always one of the intervals, whatever their count.
    const auto mid = intervals.begin() + static_cast<std::ptrdiff_t>((intervals.size() - 1) / 2);
    std::nth_element(intervals.begin(), mid, intervals.end());
    track.info.median_interval_s = *mid;
  }

  for (std::size_t begin = 0; begin < p.size();) {
    std::size_t end = begin + 1;
    while (end < p.size() && p[end].t - p[end - 1].t <= kMaxGap_s && !p[end - 1].track_end) ++end;
    // Speeds not reported are derived over a baseline of kSpeedBaseline_s centred on the
    // record where the run allows, and never over less than a second.
    std::size_t a = begin, b = begin;
    for (std::size_t k = begin; k < end; ++k) {
      while (a + 1 <= k && p[a + 1].t <= p[k].t - 0.5 * kSpeedBaseline_s) ++a;
      if (b < k) b = k;
      while (b + 1 < end && p[b].t < p[k].t + 0.5 * kSpeedBaseline_s) ++b;
      if (!std::isnan(p[k].speed_kt)) continue;
      const double dt = p[b].t - p[a].t;
      if (dt >= 1.0) p[k].speed_kt = local_distance_m(p[a].lat, p[a].lon, p[b].lat, p[b].lon) / dt / kMpsPerKnot;
    }
    const auto first_s = static_cast<std::int64_t>(std::ceil(p[begin].t));
    const auto last_s = static_cast<std::int64_t>(std::floor(p[end - 1].t));
    if (first_s <= last_s)
      track.runs.push_back({static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(end), first_s, last_s});
    begin = end;
  }
}

TruthSample Truth::interpolate(const Track& track, const Run& run, std::uint32_t segment, std::int64_t second) const {
  const Point& p = track.points[segment];
  const auto s = static_cast<double>(second);
  TruthSample out;
  if (segment + 1 >= run.end || s <= p.t) {
    out = {p.lat, p.lon, p.alt, p.speed_kt, p.on_ground, false, p.lower_limit_ft};
  } else {
    const Point& q = track.points[segment + 1];
    const double f = (s - p.t) / (q.t - p.t);
    out.lat_deg = p.lat + f * (q.lat - p.lat);
    out.lon_deg = p.lon + f * longitude_difference(p.lon, q.lon);
    if (out.lon_deg > 180.0) out.lon_deg -= 360.0;
    if (out.lon_deg < -180.0) out.lon_deg += 360.0;
    out.alt_ft = p.alt + f * (q.alt - p.alt);
    if (std::isnan(p.speed_kt))
      out.speed_kt = q.speed_kt;
    else if (std::isnan(q.speed_kt))
      out.speed_kt = p.speed_kt;
    else
      out.speed_kt = p.speed_kt + f * (q.speed_kt - p.speed_kt);
    out.on_ground = f <= 0.5 ? p.on_ground : q.on_ground;
    out.lower_limit_ft = f <= 0.5 ? p.lower_limit_ft : q.lower_limit_ft;
  }
  // NaN speed compares false: a target whose speed is unknown is not shown to fly.
  out.airborne = out.speed_kt >= kMinAirborneSpeed_kt && out.alt_ft >= kMinPlausibleAltitude_ft &&
                 out.alt_ft <= kMaxPlausibleAltitude_ft && !out.on_ground && out.alt_ft >= out.lower_limit_ft;
  return out;
}

void Truth::sweep(std::unordered_map<std::uint64_t, PairTrace>& traces) {
  struct Start {
    std::int64_t first_s;
    TruthTrackId track;
    std::uint32_t run;
  };
  std::vector<Start> starts;
  for (TruthTrackId t = 0; t < tracks_.size(); ++t)
    for (std::uint32_t r = 0; r < tracks_[t].runs.size(); ++r) starts.push_back({tracks_[t].runs[r].first_s, t, r});
  std::sort(starts.begin(), starts.end(), [](const Start& x, const Start& y) {
    return x.first_s != y.first_s ? x.first_s < y.first_s : x.track < y.track;
  });

  struct Active {
    TruthTrackId track;
    const Run* run;
    std::uint32_t cursor;  // the record at or before the current second
  };
  struct Airborne {
    double lat, lon, alt;
    TruthTrackId track;
  };
  const double vertical_loss_ft = standard_.vertical_loss_ft();
  const double close_m = standard_.horizontal_m + kCloseCallMargin_m;
  const double zone_m = std::max(close_m, kOneAircraftHorizontal_m);
  const double zone_ft = std::max(vertical_loss_ft, kOneAircraftVertical_ft);
  // No meridional radius of curvature is below 6,335 km (the equator's), so a latitude
  // difference above this is farther apart than the zone.
  const double zone_lat_deg = zone_m / 6.335e6 / kDegree;

  std::vector<Active> active;
  std::vector<Airborne> airborne;
  std::size_t next = 0;
  std::int64_t s = starts.empty() ? 0 : starts.front().first_s;
  while (next < starts.size() || !active.empty()) {
    if (active.empty()) s = std::max(s, starts[next].first_s);
    for (; next < starts.size() && starts[next].first_s <= s; ++next) {
      const Run& run = tracks_[starts[next].track].runs[starts[next].run];
      active.push_back({starts[next].track, &run, run.begin});
    }
    airborne.clear();
    for (Active& a : active) {
      Track& track = tracks_[a.track];
      while (a.cursor + 1 < a.run->end && track.points[a.cursor + 1].t <= static_cast<double>(s)) ++a.cursor;
      const TruthSample sample = interpolate(track, *a.run, a.cursor, s);
      if (!sample.airborne) continue;
      append_second(track.airborne, s);
      airborne.push_back({sample.lat_deg, sample.lon_deg, sample.alt_ft, a.track});
    }
    std::sort(airborne.begin(), airborne.end(), [](const Airborne& x, const Airborne& y) {
      return x.lat != y.lat ? x.lat < y.lat : x.track < y.track;
    });
    for (std::size_t i = 0; i < airborne.size(); ++i) {
      const Airborne& x = airborne[i];
      for (std::size_t j = i + 1; j < airborne.size() && airborne[j].lat - x.lat <= zone_lat_deg; ++j) {
        const Airborne& y = airborne[j];
        const double v_ft = std::abs(x.alt - y.alt);
        if (v_ft >= zone_ft) continue;
        const double h_m = local_distance_m(x.lat, x.lon, y.lat, y.lon);
        if (h_m >= zone_m) continue;
        const std::uint64_t key = pair_key(x.track, y.track);
        if (v_ft < vertical_loss_ft && h_m < close_m) {
          PairTrace& trace = traces[key];
          append_second(trace.close, s);
          if (h_m < standard_.horizontal_m) {
            if (append_second(trace.loss, s)) {
              trace.loss_min_h_m.push_back(h_m);
              trace.loss_v_at_min_ft.push_back(v_ft);
              trace.loss_tracks.push_back(key);
            } else if (h_m < trace.loss_min_h_m.back()) {
              trace.loss_min_h_m.back() = h_m;
              trace.loss_v_at_min_ft.back() = v_ft;
            }
          }
        }
        if (v_ft < kOneAircraftVertical_ft && h_m < kOneAircraftHorizontal_m) append_second(traces[key].near, s);
      }
    }
    std::erase_if(active, [s](const Active& a) { return a.run->last_s <= s; });
    ++s;
  }
}

void Truth::merge_aircraft(const std::vector<std::pair<std::uint64_t, const PairTrace*>>& traces) {
  Components components(tracks_.size());
  std::map<std::uint32_t, TruthTrackId> by_address;
  for (TruthTrackId t = 0; t < tracks_.size(); ++t) {
    if (!tracks_[t].info.address) continue;
    const auto [it, inserted] = by_address.try_emplace(*tracks_[t].info.address, t);
    if (!inserted && components.join(it->second, t)) ++figures_.merged_by_address;
  }
  for (const auto& [key, trace] : traces) {
    const bool a_minute = std::any_of(trace->near.begin(), trace->near.end(),
                                      [](const SecondRange& r) { return r.length() >= kOneAircraft_s; });
    if (!a_minute) continue;
    // Two different addresses are two aircraft, however close (a formation), and so are
    // two tracks without a discrete code in common: closeness is no identity.
    const Track& tx = tracks_[key_first(key)];
    const Track& ty = tracks_[key_second(key)];
    if (tx.info.address && ty.info.address && *tx.info.address != *ty.info.address) continue;
    const bool shared_code = std::any_of(tx.codes.begin(), tx.codes.end(), [&](std::uint16_t c) {
      return std::find(ty.codes.begin(), ty.codes.end(), c) != ty.codes.end();
    });
    if (!shared_code) continue;
    if (components.join(key_first(key), key_second(key))) ++figures_.merged_by_proximity;
  }
  std::vector<AircraftId> of_root(tracks_.size(), std::numeric_limits<AircraftId>::max());
  std::vector<std::vector<SecondRange>> airborne;
  for (TruthTrackId t = 0; t < tracks_.size(); ++t) {
    const std::uint32_t root = components.find(t);
    if (of_root[root] == std::numeric_limits<AircraftId>::max()) {
      of_root[root] = static_cast<AircraftId>(airborne.size());
      airborne.emplace_back();
    }
    tracks_[t].aircraft = of_root[root];
    auto& ranges = airborne[tracks_[t].aircraft];
    ranges.insert(ranges.end(), tracks_[t].airborne.begin(), tracks_[t].airborne.end());
  }
  figures_.aircraft = airborne.size();
  // Seconds two tracks of one aircraft share are flown once.
  for (auto& ranges : airborne)
    for (const SecondRange& r : union_of(std::move(ranges))) figures_.airborne_seconds += r.length();
}

void Truth::build_losses(const std::vector<std::pair<std::uint64_t, const PairTrace*>>& traces) {
  // Track pairs → aircraft pairs: the ranges of every track pair between two aircraft.
  std::map<std::uint64_t, PairTrace> by_aircraft;
  for (const auto& [key, trace] : traces) {
    const AircraftId a = tracks_[key_first(key)].aircraft, b = tracks_[key_second(key)].aircraft;
    if (a == b || trace->close.empty()) continue;
    PairTrace& into = by_aircraft[pair_key(a, b)];
    into.close.insert(into.close.end(), trace->close.begin(), trace->close.end());
    into.loss.insert(into.loss.end(), trace->loss.begin(), trace->loss.end());
    into.loss_min_h_m.insert(into.loss_min_h_m.end(), trace->loss_min_h_m.begin(), trace->loss_min_h_m.end());
    into.loss_v_at_min_ft.insert(into.loss_v_at_min_ft.end(), trace->loss_v_at_min_ft.begin(),
                                 trace->loss_v_at_min_ft.end());
    into.loss_tracks.insert(into.loss_tracks.end(), trace->loss_tracks.begin(), trace->loss_tracks.end());
  }

  aircraft_traces_.reserve(by_aircraft.size());
  for (auto& keyed : by_aircraft) {
    const std::uint64_t key = keyed.first;
    PairTrace& trace = keyed.second;  // plain references: clang 14 cannot capture a structured binding
    PairTrace merged;
    merged.close = union_of(std::move(trace.close));
    // Loss ranges in time order (ties: the lower track pair), joined where they overlap
    // or touch; a joined range keeps the track pair of its first part and the closest
    // approach of all.
    std::vector<std::size_t> order(trace.loss.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      return trace.loss[x].first != trace.loss[y].first ? trace.loss[x].first < trace.loss[y].first
                                                        : trace.loss_tracks[x] < trace.loss_tracks[y];
    });
    for (const std::size_t i : order) {
      const SecondRange& r = trace.loss[i];
      if (!merged.loss.empty() && r.first <= merged.loss.back().last + 1) {
        merged.loss.back().last = std::max(merged.loss.back().last, r.last);
        if (trace.loss_min_h_m[i] < merged.loss_min_h_m.back()) {
          merged.loss_min_h_m.back() = trace.loss_min_h_m[i];
          merged.loss_v_at_min_ft.back() = trace.loss_v_at_min_ft[i];
        }
        continue;
      }
      merged.loss.push_back(r);
      merged.loss_min_h_m.push_back(trace.loss_min_h_m[i]);
      merged.loss_v_at_min_ft.push_back(trace.loss_v_at_min_ft[i]);
      merged.loss_tracks.push_back(trace.loss_tracks[i]);
    }

    const AircraftId a = key_first(key), b = key_second(key);
    for (std::size_t i = 0; i < merged.loss.size(); ++i) {
      if (i > 0 && merged.loss[i].first - merged.loss[i - 1].last < kLossMerge_s) {
        LossEvent& event = losses_.back();
        event.end_s = merged.loss[i].last;
        event.loss_seconds += merged.loss[i].length();
        if (merged.loss_min_h_m[i] < event.min_horizontal_m) {
          event.min_horizontal_m = merged.loss_min_h_m[i];
          event.vertical_at_min_ft = merged.loss_v_at_min_ft[i];
        }
        continue;
      }
      LossEvent event;
      event.a = a;
      event.b = b;
      TruthTrackId ta = key_first(merged.loss_tracks[i]), tb = key_second(merged.loss_tracks[i]);
      if (tracks_[ta].aircraft != a) std::swap(ta, tb);
      event.track_a = ta;
      event.track_b = tb;
      event.start_s = merged.loss[i].first;
      event.end_s = merged.loss[i].last;
      event.loss_seconds = merged.loss[i].length();
      event.min_horizontal_m = merged.loss_min_h_m[i];
      event.vertical_at_min_ft = merged.loss_v_at_min_ft[i];
      losses_.push_back(event);
    }
    merged.loss_min_h_m.clear();
    merged.loss_v_at_min_ft.clear();
    merged.loss_tracks.clear();
    aircraft_traces_.emplace_back(key, std::move(merged));
  }
  std::sort(losses_.begin(), losses_.end(), [](const LossEvent& x, const LossEvent& y) {
    if (x.start_s != y.start_s) return x.start_s < y.start_s;
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
}

std::optional<TruthTrackId> Truth::find_track(std::string_view source, std::string_view id) const {
  std::string key(source);
  key += '\x1f';
  key += id;
  const auto it = index_.find(key);
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

std::optional<TruthSample> Truth::sample(TruthTrackId track, std::int64_t second) const {
  const Track& t = tracks_[track];
  auto run = std::upper_bound(t.runs.begin(), t.runs.end(), second,
                              [](std::int64_t s, const Run& r) { return s < r.first_s; });
  if (run == t.runs.begin()) return std::nullopt;
  --run;
  if (second > run->last_s) return std::nullopt;
  const auto first = t.points.begin() + run->begin, last = t.points.begin() + run->end;
  const auto after = std::upper_bound(first, last, static_cast<double>(second),
                                      [](double s, const Point& p) { return s < p.t; });
  return interpolate(t, *run, static_cast<std::uint32_t>(after - t.points.begin() - 1), second);
}

std::optional<std::pair<std::int64_t, TruthSample>> Truth::nearest_sample(TruthTrackId track, double t,
                                                                          double within_s) const {
  for (const std::int64_t s : seconds_nearest_first(t, within_s))
    if (const auto found = sample(track, s)) return std::pair{s, *found};
  return std::nullopt;
}

std::vector<SecondRange> Truth::sampled(TruthTrackId track) const {
  std::vector<SecondRange> out;
  for (const Run& run : tracks_[track].runs) out.push_back({run.first_s, run.last_s});
  return out;
}

std::optional<std::int64_t> Truth::airborne_since(TruthTrackId track, std::int64_t second) const {
  const SecondRange* r = first_meeting(tracks_[track].airborne, second, second);
  if (!r) return std::nullopt;
  return r->first;
}

const Truth::PairTrace* Truth::aircraft_trace(AircraftId a, AircraftId b) const {
  return find_trace(aircraft_traces_, pair_key(a, b));
}

std::optional<std::int64_t> Truth::first_loss_second(AircraftId a, AircraftId b, std::int64_t from,
                                                     std::int64_t to) const {
  if (a == b) return std::nullopt;
  const PairTrace* trace = aircraft_trace(a, b);
  if (!trace) return std::nullopt;
  return first_second_in(trace->loss, from, to);
}

bool Truth::any_close_second(AircraftId a, AircraftId b, std::int64_t from, std::int64_t to) const {
  if (a == b) return false;
  const PairTrace* trace = aircraft_trace(a, b);
  return trace && first_meeting(trace->close, from, to) != nullptr;
}

}  // namespace kew::replay
