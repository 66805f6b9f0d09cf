#include "kew/replay/area_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

#include <GeographicLib/Geodesic.hpp>

#include "kew/util/wildcard.hpp"
#include "kew/volume/volume_index.hpp"
#include "evaluation/scoring.hpp"
#include "evaluation/truth_support.hpp"

namespace kew::replay {

namespace {

using namespace area_rules;

// A fixed volume's candidates are looked up once per this many seconds of a track.
constexpr std::int64_t kChunk_s = 64;

std::uint64_t key_of(std::uint32_t volume, std::uint32_t second) {
  return (static_cast<std::uint64_t>(volume) << 32) | second;
}

// Distance (m) from `p` to the segment [a, b] of a plane.
double segment_distance(geometry::Point2 p, geometry::Point2 a, geometry::Point2 b) {
  const geometry::Vector2 ab = b - a, ap = p - a;
  const double length2 = geometry::dot(ab, ab);
  const double u = length2 > 0.0 ? std::clamp(geometry::dot(ap, ab) / length2, 0.0, 1.0) : 0.0;
  return geometry::norm(ap - u * ab);
}

bool in_band(volume::VerticalBand band, double alt_ft) { return alt_ft >= band.floor_ft && alt_ft <= band.ceiling_ft; }

}  // namespace

bool flies_for_areas(const TruthSample& s) {
  return s.speed_kt >= truth_rules::kMinAirborneSpeed_kt && s.alt_ft >= truth_rules::kMinPlausibleAltitude_ft &&
         s.alt_ft <= truth_rules::kMaxPlausibleAltitude_ft && !s.on_ground;
}

double distance_to_area_m(const volume::Volume& volume, volume::LatLon p) {
  if (volume.contains_horizontally(p)) return 0.0;
  if (volume.is_circle()) {
    double distance = 0.0;
    GeographicLib::Geodesic::WGS84().Inverse(volume.centre().lat_deg, volume.centre().lon_deg, p.lat_deg, p.lon_deg,
                                             distance);
    return std::max(0.0, distance - volume.extent_m());
  }
  const geometry::Point2 q = volume.project(p);
  if (!std::isfinite(q.x) || !std::isfinite(q.y)) return std::numeric_limits<double>::infinity();
  double best = std::numeric_limits<double>::infinity();
  for (const std::vector<geometry::Point2>& ring : volume.plane_rings())
    for (std::size_t i = 0; i < ring.size(); ++i)
      best = std::min(best, segment_distance(q, ring[i], ring[(i + 1) % ring.size()]));
  return best;
}

AreaTruth::AreaTruth(const Truth& truth, std::span<const TrackReport> records,
                     std::vector<volume::WatchedVolume> volumes)
    : truth_(truth), volumes_(std::move(volumes)), centres_(volumes_.size()) {
  read_idents(records);
  for (std::uint32_t v = 0; v < volumes_.size(); ++v) {
    if (volumes_[v].area) continue;
    for (TruthTrackId k = 0; k < truth_.track_count(); ++k) {
      const std::string& pattern = volumes_[v].follow;
      bool named = util::matches_wildcard(pattern, truth_.track(k).id);
      for (const Ident& i : idents_[k])
        named = named || (i.callsign != 0 && util::matches_wildcard(pattern, callsigns_[i.callsign]));
      if (named) centres_[v].push_back(k);
    }
  }
  sweep_fixed();
  for (std::uint32_t v = 0; v < volumes_.size(); ++v)
    if (!volumes_[v].area) sweep_followed(v);
  build_entries();
}

void AreaTruth::read_idents(std::span<const TrackReport> records) {
  idents_.resize(truth_.track_count());
  callsigns_.assign(1, std::string());
  const bool needed = std::any_of(volumes_.begin(), volumes_.end(), [](const volume::WatchedVolume& v) {
    return !v.area || !v.traffic.everyone();
  });
  if (!needed) return;
  std::unordered_map<std::string, std::uint32_t> interned;
  for (const TrackReport& r : records) {
    if (!std::isfinite(r.t) || (r.callsign.empty() && !r.mode3a)) continue;
    const std::optional<TruthTrackId> k = truth_.find_track(r.source, r.id);
    if (!k) continue;
    std::uint32_t callsign = 0;
    if (!r.callsign.empty()) {
      const auto [it, inserted] = interned.try_emplace(r.callsign, static_cast<std::uint32_t>(callsigns_.size()));
      if (inserted) callsigns_.push_back(r.callsign);
      callsign = it->second;
    }
    idents_[*k].push_back({r.t, callsign, r.mode3a});
  }
  // Each record's own fields, in time order, become the track's state from then on: the
  // last callsign and the last code reported, as the pipeline's track keeps them.
  for (std::vector<Ident>& list : idents_) {
    std::stable_sort(list.begin(), list.end(), [](const Ident& x, const Ident& y) { return x.t < y.t; });
    std::vector<Ident> states;
    for (const Ident& i : list) {
      Ident state = states.empty() ? Ident{i.t, 0, std::nullopt} : states.back();
      state.t = i.t;
      if (i.callsign != 0) state.callsign = i.callsign;
      if (i.squawk) state.squawk = i.squawk;
      if (!states.empty() && states.back().callsign == state.callsign && states.back().squawk == state.squawk) continue;
      states.push_back(state);
    }
    list = std::move(states);
  }
}

const AreaTruth::Ident* AreaTruth::ident_at(TruthTrackId track, std::int64_t second) const {
  const std::vector<Ident>& list = idents_[track];
  const auto after = std::upper_bound(list.begin(), list.end(), static_cast<double>(second),
                                      [](double s, const Ident& i) { return s < i.t; });
  return after == list.begin() ? nullptr : &*(after - 1);
}

bool AreaTruth::concerns(const volume::WatchedVolume& v, TruthTrackId track, std::int64_t second) const {
  if (v.traffic.everyone()) return true;
  const Ident* i = ident_at(track, second);
  return v.traffic.concerns(truth_.track(track).id, i ? std::string_view(callsigns_[i->callsign]) : std::string_view(),
                            i ? i->squawk : std::nullopt);
}

bool AreaTruth::names(const volume::WatchedVolume& v, TruthTrackId track, std::int64_t second) const {
  if (util::matches_wildcard(v.follow, truth_.track(track).id)) return true;
  const Ident* i = ident_at(track, second);
  return i && i->callsign != 0 && util::matches_wildcard(v.follow, callsigns_[i->callsign]);
}

std::optional<std::pair<TruthTrackId, TruthSample>> AreaTruth::centre_at(std::uint32_t v, std::int64_t second) const {
  for (const TruthTrackId k : centres_[v]) {
    const std::optional<TruthSample> s = truth_.sample(k, second);
    if (s && !s->on_ground && names(volumes_[v], k, second)) return std::pair{k, *s};
  }
  return std::nullopt;
}

bool AreaTruth::eligible(std::uint32_t v, TruthTrackId track, std::int64_t second) const {
  const volume::WatchedVolume& w = volumes_[v];
  const std::optional<TruthSample> s = truth_.sample(track, second);
  if (!s || !flies_for_areas(*s) || !w.schedule.active_at(static_cast<double>(second)) || !concerns(w, track, second))
    return false;
  if (w.area) return true;
  const auto centre = centre_at(v, second);
  return centre && truth_.aircraft_of(centre->first) != truth_.aircraft_of(track);
}

void AreaTruth::note(std::uint32_t v, TruthTrackId track, std::int64_t second, bool inside, bool close) {
  if (!inside && !close) return;
  const std::uint64_t key = key_of(v, track);
  // Each (volume, track) is noted in one go, its seconds in order.
  if (track_traces_.empty() || track_traces_.back().first != key) track_traces_.emplace_back(key, Trace{});
  Trace& trace = track_traces_.back().second;
  if (inside && append_second(trace.inside, second)) trace.inside_tracks.push_back(track);
  append_second(trace.close, second);
}

void AreaTruth::sweep_fixed() {
  std::vector<volume::Volume> areas;
  std::vector<std::uint32_t> fixed;  // the index's positions → volume numbers
  for (std::uint32_t v = 0; v < volumes_.size(); ++v)
    if (volumes_[v].area) {
      areas.push_back(*volumes_[v].area);
      fixed.push_back(v);
    }
  if (areas.empty()) return;
  const volume::VolumeIndex index(areas);
  std::vector<std::pair<std::int64_t, TruthSample>> chunk;
  for (TruthTrackId k = 0; k < truth_.track_count(); ++k) {
    // Per volume, this track's close seconds in order (inside, close), noted per volume.
    std::map<std::uint32_t, std::vector<std::pair<std::int64_t, std::pair<bool, bool>>>> found;
    for (const SecondRange& run : truth_.sampled(k)) {
      for (std::int64_t from = run.first; from <= run.last; from += kChunk_s) {
        chunk.clear();
        const std::int64_t to = std::min(run.last, from + kChunk_s - 1);
        for (std::int64_t s = from; s <= to; ++s)
          if (const std::optional<TruthSample> sample = truth_.sample(k, s); sample && flies_for_areas(*sample))
            chunk.emplace_back(s, *sample);
        if (chunk.empty()) continue;
        const volume::LatLon first{chunk.front().second.lat_deg, chunk.front().second.lon_deg};
        double reach = 0.0;
        for (const auto& [s, sample] : chunk)
          reach = std::max(reach, local_distance_m(first.lat_deg, first.lon_deg, sample.lat_deg, sample.lon_deg));
        // local_distance_m is within 0.02 % of the geodesic over a chunk's few miles.
        for (const std::uint32_t i : index.near(first, 1.001 * reach + kCloseCallMargin_m + 1.0)) {
          const volume::WatchedVolume& w = volumes_[fixed[i]];
          for (const auto& [s, sample] : chunk) {
            if (!in_band(w.area->band(), sample.alt_ft)) continue;
            if (!w.schedule.active_at(static_cast<double>(s)) || !concerns(w, k, s)) continue;
            const volume::LatLon p{sample.lat_deg, sample.lon_deg};
            const bool inside = w.area->contains_horizontally(p);
            if (inside || distance_to_area_m(*w.area, p) <= kCloseCallMargin_m)
              found[fixed[i]].push_back({s, {inside, true}});
          }
        }
      }
    }
    for (const auto& [v, seconds] : found)
      for (const auto& [s, flags] : seconds) note(v, k, s, flags.first, flags.second);
  }
}

void AreaTruth::sweep_followed(std::uint32_t v) {
  if (centres_[v].empty()) return;
  const volume::WatchedVolume& w = volumes_[v];
  // The centre at every second of the span its candidates were seen in.
  std::int64_t first = std::numeric_limits<std::int64_t>::max(), last = std::numeric_limits<std::int64_t>::min();
  for (const TruthTrackId k : centres_[v])
    for (const SecondRange& r : truth_.sampled(k)) {
      first = std::min(first, r.first);
      last = std::max(last, r.last);
    }
  if (first > last) return;
  std::vector<std::optional<std::pair<TruthTrackId, TruthSample>>> centre(static_cast<std::size_t>(last - first + 1));
  for (std::int64_t s = first; s <= last; ++s) centre[static_cast<std::size_t>(s - first)] = centre_at(v, s);

  for (TruthTrackId k = 0; k < truth_.track_count(); ++k) {
    for (const SecondRange& run : truth_.sampled(k)) {
      for (std::int64_t s = std::max(run.first, first); s <= std::min(run.last, last); ++s) {
        const auto& c = centre[static_cast<std::size_t>(s - first)];
        if (!c || truth_.aircraft_of(c->first) == truth_.aircraft_of(k)) continue;
        const std::optional<TruthSample> sample = truth_.sample(k, s);
        if (!sample || !flies_for_areas(*sample)) continue;
        const double dv = sample->alt_ft - c->second.alt_ft;
        if (!in_band(w.follow_band, dv)) continue;
        const double distance =
            local_distance_m(c->second.lat_deg, c->second.lon_deg, sample->lat_deg, sample->lon_deg);
        if (distance > w.follow_radius_m + kCloseCallMargin_m) continue;
        if (!w.schedule.active_at(static_cast<double>(s)) || !concerns(w, k, s)) continue;
        note(v, k, s, distance <= w.follow_radius_m, true);
      }
    }
  }
}

void AreaTruth::build_entries() {
  // (volume, track) traces, then (volume, aircraft) ones: inside ranges in time order
  // (ties: the lower track), joined where they overlap or touch, each keeping the track of
  // its first part.
  std::map<std::uint64_t, std::vector<std::pair<SecondRange, TruthTrackId>>> inside;
  std::map<std::uint64_t, std::vector<SecondRange>> close;
  for (auto& [key, trace] : track_traces_) {
    const auto v = static_cast<std::uint32_t>(key >> 32);
    const auto track = static_cast<TruthTrackId>(key & 0xffffffffu);
    const std::uint64_t a = key_of(v, truth_.aircraft_of(track));
    for (std::size_t i = 0; i < trace.inside.size(); ++i) inside[a].emplace_back(trace.inside[i], track);
    std::vector<SecondRange>& c = close[a];
    c.insert(c.end(), trace.close.begin(), trace.close.end());
  }
  for (auto& [key, ranges] : close) {
    Trace merged;
    merged.close = union_of(std::move(ranges));
    std::vector<std::pair<SecondRange, TruthTrackId>>& in = inside[key];
    std::sort(in.begin(), in.end(), [](const auto& x, const auto& y) {
      return x.first.first != y.first.first ? x.first.first < y.first.first : x.second < y.second;
    });
    for (const auto& [r, track] : in) {
      if (!merged.inside.empty() && r.first <= merged.inside.back().last + 1) {
        merged.inside.back().last = std::max(merged.inside.back().last, r.last);
        continue;
      }
      merged.inside.push_back(r);
      merged.inside_tracks.push_back(track);
    }
    const auto v = static_cast<std::uint32_t>(key >> 32);
    for (std::size_t i = 0; i < merged.inside.size(); ++i) {
      if (i > 0 && merged.inside[i].first - merged.inside[i - 1].last < kEntryMerge_s) {
        entries_.back().end_s = merged.inside[i].last;
        entries_.back().inside_seconds += merged.inside[i].length();
        continue;
      }
      AreaEntry e;
      e.volume = v;
      e.aircraft = static_cast<AircraftId>(key & 0xffffffffu);
      e.track = merged.inside_tracks[i];
      e.start_s = merged.inside[i].first;
      e.end_s = merged.inside[i].last;
      e.inside_seconds = merged.inside[i].length();
      if (!volumes_[v].area)
        if (const auto c = centre_at(v, e.start_s)) e.centre = c->first;
      e.eligible_since_s = e.start_s;
      while (eligible(v, e.track, e.eligible_since_s - 1)) --e.eligible_since_s;
      entries_.push_back(e);
    }
    aircraft_traces_.emplace_back(key, std::move(merged));
  }
  track_traces_.clear();
  std::sort(entries_.begin(), entries_.end(), [](const AreaEntry& x, const AreaEntry& y) {
    if (x.start_s != y.start_s) return x.start_s < y.start_s;
    return x.volume != y.volume ? x.volume < y.volume : x.aircraft < y.aircraft;
  });
}

std::optional<std::uint32_t> AreaTruth::find_volume(std::string_view name) const {
  for (std::uint32_t v = 0; v < volumes_.size(); ++v)
    if (volumes_[v].name == name) return v;
  return std::nullopt;
}

const AreaTruth::Trace* AreaTruth::aircraft_trace(std::uint32_t v, AircraftId a) const {
  return find_trace(aircraft_traces_, key_of(v, a));
}

std::optional<std::int64_t> AreaTruth::first_inside_second(std::uint32_t v, AircraftId a, std::int64_t from,
                                                           std::int64_t to) const {
  const Trace* trace = aircraft_trace(v, a);
  if (!trace) return std::nullopt;
  return first_second_in(trace->inside, from, to);
}

bool AreaTruth::any_close_second(std::uint32_t v, AircraftId a, std::int64_t from, std::int64_t to) const {
  const Trace* trace = aircraft_trace(v, a);
  return trace && first_meeting(trace->close, from, to) != nullptr;
}

std::optional<TruthTrackId> AreaTruth::nearest_centre(std::uint32_t v, double t, double within_s) const {
  if (volumes_[v].area) return std::nullopt;
  for (const std::int64_t s : seconds_nearest_first(t, within_s))
    if (const auto c = centre_at(v, s)) return c->first;
  return std::nullopt;
}

double AreaTruth::update_period_s(const AreaEntry& entry) const {
  return scoring::update_period_s(truth_.track(entry.track), entry.centre ? &truth_.track(*entry.centre) : nullptr);
}

}  // namespace kew::replay
