// kew_peers_bench's workload: generated records, and what the Pipeline's track table
// makes of them.

#include "workload.hpp"

#include <CGAL/hilbert_sort.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <utility>

#include "cgal_types.hpp"
#include "kew/config/aerodromes.hpp"
#include "kew/replay/recording_reader.hpp"
#include "kew/replay/traffic_generator.hpp"

namespace kew::bench::peers {

namespace {

// Density: 100,000 aircraft fill the generator's largest region (radius 2,000 km), and
// smaller fleets get a region scaled by √N, so every fleet size has the same density:
// one aircraft per 126 km² (twice kew-replay's usual 2,000 aircraft in 400 km).
double region_radius_km(std::size_t aircraft) {
  return std::clamp(2000.0 * std::sqrt(static_cast<double>(aircraft) / 100000.0), 20.0, 2000.0);
}

// The records of --recording, in data-time order (some files are not), and the number
// of tracks in them; the first record's position becomes the projection's reference.
void read_recording(const Params& prm, Workload& w) {
  kew::replay::RecordingReader reader(prm.recording, kew::protocol::Format::Auto, {});
  for (kew::TrackReport r; reader.next(r);) w.records.push_back(std::move(r));
  if (w.records.empty()) usage("no records in " + prm.recording);
  std::stable_sort(w.records.begin(), w.records.end(),
                   [](const kew::TrackReport& a, const kew::TrackReport& b) { return a.t < b.t; });
  std::set<std::pair<std::string, std::string>> tracks;
  for (const kew::TrackReport& r : w.records) tracks.emplace(r.source, r.id);
  w.aircraft = tracks.size();
  // The other methods work in one plane: so does the pipeline they are measured against.
  w.config.zone_mode = kew::ZoneMode::Single;
  w.config.reference = kew::geo::GeodeticPosition{w.records.front().lat_deg, w.records.front().lon_deg};
}

// --first-order: the first period's records in a random or a Hilbert-curve order of
// their positions (arrival order untouched).
void reorder_first_period(const Params& prm, double start_time, std::vector<kew::TrackReport>& records) {
  if (prm.first_order == Params::FirstOrder::Arrival) return;
  const auto end = std::find_if(records.begin(), records.end(),
                                [&](const kew::TrackReport& r) { return r.t >= start_time + prm.period_s; });
  if (prm.first_order == Params::FirstOrder::Shuffled) {
    std::mt19937_64 random(prm.seed);
    std::shuffle(records.begin(), end, random);
    return;
  }
  std::vector<cgal::CgalPoint> where;
  for (auto r = records.begin(); r != end; ++r) where.emplace_back(r->lon_deg, r->lat_deg);
  std::vector<std::size_t> order(where.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  CGAL::hilbert_sort(order.begin(), order.end(), cgal::SortTraits(CGAL::make_property_map(where)));
  std::vector<kew::TrackReport> sorted;
  sorted.reserve(order.size());
  for (const std::size_t i : order) sorted.push_back(std::move(records[i]));
  std::move(sorted.begin(), sorted.end(), records.begin());
}

}  // namespace

Workload make_workload(const Params& prm, std::size_t aircraft) {
  Workload w;
  // kew's aerodromes, as every tool reads them (the lower limit above them).
  w.config.eligibility.aerodromes = kew::config::load_default_aerodromes();
  double start_time = 0.0;
  if (!prm.recording.empty()) {
    read_recording(prm, w);
    start_time = std::floor(w.records.front().t);
  } else {
    w.aircraft = aircraft;
    w.radius_km = region_radius_km(aircraft);
    kew::replay::GeneratorConfig g;
    g.scenario = prm.scenario;
    g.aircraft = aircraft;
    g.period_s = prm.period_s;
    g.duration_s = prm.period_s * static_cast<double>(prm.warmup + prm.periods);
    g.seed = prm.seed;
    g.radius_km = w.radius_km;
    g.aerodromes = w.config.eligibility.aerodromes;
    kew::replay::TrafficGenerator generator(g);
    w.records.reserve(aircraft * (prm.warmup + prm.periods));
    for (kew::TrackReport r; generator.next(r);) w.records.push_back(r);
    start_time = g.start_time;
    w.config.zone_mode = kew::ZoneMode::Single;
    w.config.reference = kew::geo::GeodeticPosition{g.center_lat_deg, g.center_lon_deg};
    w.config.coverage_radius_m = std::min(3.0e6, std::max(1.5e6, 1.25e3 * w.radius_km + 50e3));
  }
  const kew::geo::Projection projection(*w.config.reference,
                                        w.config.coverage_radius_m.value_or(kew::PipelineConfig::kSingleCoverage_m));
  w.k_max = projection.max_scale();
  reorder_first_period(prm, start_time, w.records);

  // The Pipeline's own sequence of track table calls (Pipeline::process), so the slots
  // and kinematics here are the ones its probe sees.
  kew::track::TrackTable table(w.config.tracks);
  std::vector<bool> in_engine;
  double clock = 0.0;
  bool started = false;
  std::size_t period = 0;
  for (std::uint32_t index = 0; index < w.records.size(); ++index) {
    const kew::TrackReport& r = w.records[index];
    while (r.t >= start_time + prm.period_s * static_cast<double>(period)) {
      w.period_first_record.push_back(index);
      w.period_first_step.push_back(w.steps.size());
      ++period;
    }
    if (table.plausibility_problem(r) != kew::track::Refusal::None) {
      ++w.rejected;
      continue;
    }
    if (!started) {
      started = true;
      clock = std::floor(r.t);
    }
    if (r.t >= clock - table.config().max_lateness_s) {
      const double to = std::max(clock, r.t);
      table.expire(to, [&](Slot slot, const kew::track::Track& track) {
        clock = std::max(clock, track.t + table.config().track_timeout_s);
        if (in_engine[slot]) w.steps.push_back({true, slot, index, clock, {}});
        in_engine[slot] = false;
      });
      clock = to;
    }
    const kew::track::AdmitResult admitted = table.admit(r, clock, projection);
    if (admitted.admission == kew::track::Admission::Rejected) {
      ++w.rejected;
      continue;
    }
    if (admitted.slot >= in_engine.size()) in_engine.resize(admitted.slot + 1, false);
    if (admitted.admission == kew::track::Admission::AwaitingVelocity) {
      if (in_engine[admitted.slot]) w.steps.push_back({true, admitted.slot, index, clock, {}});
      in_engine[admitted.slot] = false;
      continue;
    }
    const kew::track::Track& track = table[admitted.slot];
    in_engine[admitted.slot] = true;
    w.steps.push_back({false, admitted.slot, index, clock, {track.kinematics, track.t, track.plane_scale}});
    w.v_max = std::max(w.v_max, kew::geometry::norm(track.kinematics.velocity));
  }
  w.periods_with_records = period;
  while (w.period_first_record.size() <= prm.warmup + prm.periods) {
    w.period_first_record.push_back(w.records.size());
    w.period_first_step.push_back(w.steps.size());
  }
  return w;
}

}  // namespace kew::bench::peers
