// kew_peers_bench: kew's per-radar-period cost against what an engineer would otherwise
// build (design §6.7), on the same generated traffic and in one run:
//   (a) kew         the Pipeline (track table, projection, kinetic Delaunay updates and
//                   events, exact BFS probe, alert manager) — no alert output;
//   (a') kew-index  kew's kinetic triangulation and exact search alone, driven with the
//                   same updates and conflict test as (b)-(e): the method measured as
//                   the baselines are (also split into maintenance, search and tests,
//                   and H counted: what kinetic detection would keep, design §2.7);
//   (a'') kew-lookahead  the prototype of kinetic detection (design §2.7,
//                   tests/support/lookahead_pairs.hpp): H kept by events on a kinetic
//                   triangulation of the look-ahead points, each update testing H(i);
//   (b) cgal        a static Delaunay triangulation rebuilt by CGAL every period
//                   (spatial sort, then insertion with a hint; Epick) + the same BFS probe;
//   (c) flip        one triangulation kept across periods: every position updated in place
//                   at the period's start, every edge checked (exact incircle) and
//                   repaired by Lawson flips (a full rebuild when a face folded over);
//   (d) grid        a uniform grid of R_max cells rebuilt every period;
//   (e) brute       every live track for every update: BlueSky's state-based detection
//                   (all pairs, the same CPA) — sampled when it would take too long.
//
// All five evaluate the same thing: on every applied update of track i at time t, each
// candidate j with the conflict test of the Pipeline (kinematics extrapolated to t, lower
// slot first, minima scaled by the pair's projection scale). Each must find exactly the
// pairs in conflict that (a) finds for the same updates; a difference is printed and
// makes the exit status 1.
//
// The baselines index positions at the period's start t0, so an index position lags
// the track's current one by at most D(t) = v_max·(t − t0) + J, J the largest sum of
// measurement jumps of one track since t0 (both known online): their searches use
// R_i + D(t), with R_i = S_h·k_max + T·(|v_i| + v_max) (kew's R_i without its 2τ).
// Tracks that appeared since t0, or whose jumps add up to more than 500 m, are left out
// of the index (and of J) and tried by every query instead.
//
// Usage: kew_peers_bench [--quick] [--aircraft 1000,10000,100000] [--periods N]
//                        [--warmup N] [--seed S] [--scenario mixed|random|airways|stacks|tma]
//                        [--recording FILE] [--methods kew-index,grid,...]
//                        [--lookahead-tolerance M] [--lookahead-keep S] [--brute-budget PAIRS]
//                        [--first-order arrival|shuffled|hilbert] [--renumber-every S]
//                        [--json FILE]
// --methods picks which methods run beside kew (kew-centred, kew-eager, kew-tau50, kew-renumbered,
// kew-index, kew-lookahead, cgal, flip, grid, brute; all by default). --recording runs
// one fleet on a real recording (any format kew-replay detects, time-sorted here) instead
// of generated traffic: its periods from the first record on. --lookahead-tolerance is
// kew-lookahead's ε (m, default 1000), --lookahead-keep its K (s, default 10; ADS-B feeds
// that report every 5-15 s want more, or most kept reports end as Drifts).
// --first-order permutes the first period's records (which create every track, point and
// face) into a random or a Hilbert-curve order of their positions: the worst and the best
// memory order a renumbering could leave; arrival order by default.
// --renumber-every is kew-renumbered's PipelineConfig::renumber_every_s (default 60).
//
// Density: the region grows with √N (one aircraft per 126 km² at every N), but the
// mixed scenario puts its TMA arrivals (20 %) on one centre and its airways (40 %) on at
// most 40 routes, so its local density grows with N: at 100,000 aircraft an update has
// ~4× the candidates of 1,000. --scenario random keeps the density uniform.

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <set>
#include <random>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "bench_report.hpp"
#include "lookahead_pairs.hpp"
#include "kew/config/aerodromes.hpp"
#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/pipeline/instrumentation.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/probe/proximity_search.hpp"
#include "kew/replay/recording_reader.hpp"
#include "kew/replay/traffic_generator.hpp"
#include "kew/triangulation/delaunay.hpp"
#include "kew/util/name_table.hpp"

namespace {

using kew::bench::JsonText;
using kew::bench::Stopwatch;
using kew::geometry::Point2;
using kew::geometry::Vector2;
using kew::probe::Kinematics;
using Slot = kew::track::TrackSlot;
constexpr Slot kNone = kew::track::kNoTrack;

// ---------------------------------------------------------------------------------
// Parameters

struct Params {
  std::vector<std::size_t> aircraft{1000, 10000, 100000};
  std::size_t periods = 3;  // measured radar periods per fleet size
  std::size_t warmup = 2;   // periods replayed first, untimed (the first inserts everyone)
  double period_s = 4.0;
  std::uint64_t seed = 8;
  kew::replay::Scenario scenario = kew::replay::Scenario::Mixed;
  // Largest number of pair tests brute force runs per period; beyond it every k-th
  // update is timed and the period's time extrapolated (and labelled so).
  double brute_budget = 1.5e8;
  std::string json_path;
  std::vector<std::string> methods;  // empty: all of them; kew itself always runs
  double lookahead_tolerance_m = 1000.0;  // kew-lookahead's ε
  double lookahead_keep_s = 10.0;         // kew-lookahead's K
  std::string recording;  // a real recording instead of generated traffic
  enum class FirstOrder { Arrival, Shuffled, Hilbert } first_order = FirstOrder::Arrival;
  double renumber_every_s = 60.0;  // kew-renumbered's period
};

constexpr const char* kMethodNames[] = {"kew-centred", "kew-eager", "kew-tau50", "kew-renumbered", "kew-index", "kew-lookahead", "cgal", "flip", "grid", "brute"};

bool wanted(const Params& p, const std::string& method) {
  return p.methods.empty() || std::find(p.methods.begin(), p.methods.end(), method) != p.methods.end();
}

// Density: 100,000 aircraft fill the generator's largest region (radius 2,000 km), and
// smaller fleets get a region scaled by √N, so every fleet size has the same density:
// one aircraft per 126 km² (twice kew-replay's usual 2,000 aircraft in 400 km).
double region_radius_km(std::size_t aircraft) {
  return std::clamp(2000.0 * std::sqrt(static_cast<double>(aircraft) / 100000.0), 20.0, 2000.0);
}

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "kew_peers_bench: " << why
            << "\nusage: kew_peers_bench [--quick] [--aircraft N,N,...] [--periods N] [--warmup N] [--seed S]"
               " [--scenario NAME] [--recording FILE] [--methods NAME,...] [--lookahead-tolerance M] [--lookahead-keep S]"
               " [--first-order arrival|shuffled|hilbert] [--renumber-every S]"
               " [--brute-budget PAIRS] [--json FILE]\n";
  std::exit(2);
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    out.push_back(text.substr(begin, comma - begin));
    begin = comma + 1;
  }
  return out;
}

std::vector<std::size_t> parse_list(const std::string& text) {
  std::vector<std::size_t> out;
  for (const std::string& item : split_list(text)) out.push_back(std::stoul(item));
  return out;
}

Params parse(int argc, char** argv) {
  Params p;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage("missing value for " + flag);
      return argv[++i];
    };
    try {
      if (flag == "--quick") {  // CI smoke run (< 1 min); later flags still override
        p.aircraft = {1000, 10000};
        p.periods = 2;
        p.warmup = 1;
        p.brute_budget = 3e7;
      } else if (flag == "--aircraft") {
        p.aircraft = parse_list(value());
      } else if (flag == "--periods") {
        p.periods = std::stoul(value());
      } else if (flag == "--warmup") {
        p.warmup = std::stoul(value());
      } else if (flag == "--scenario") {
        const auto scenario = kew::replay::kScenarioNames.parse(value());
        if (!scenario) usage("unknown scenario");
        p.scenario = *scenario;
      } else if (flag == "--seed") {
        p.seed = std::stoull(value());
      } else if (flag == "--brute-budget") {
        p.brute_budget = std::stod(value());
      } else if (flag == "--recording") {
        p.recording = value();
        p.aircraft = {0};  // one fleet: the recording's
      } else if (flag == "--lookahead-keep") {
        p.lookahead_keep_s = std::stod(value());
      } else if (flag == "--lookahead-tolerance") {
        p.lookahead_tolerance_m = std::stod(value());
      } else if (flag == "--renumber-every") {
        p.renumber_every_s = std::stod(value());
        if (!(p.renumber_every_s > 0.0)) usage("--renumber-every wants seconds > 0");
      } else if (flag == "--first-order") {
        const std::string order = value();
        if (order == "arrival") p.first_order = Params::FirstOrder::Arrival;
        else if (order == "shuffled") p.first_order = Params::FirstOrder::Shuffled;
        else if (order == "hilbert") p.first_order = Params::FirstOrder::Hilbert;
        else usage("unknown --first-order " + order);
      } else if (flag == "--json") {
        p.json_path = value();
      } else if (flag == "--methods") {
        for (const std::string& name : split_list(value())) {
          if (name == "kew") continue;  // always run: every other method is checked against it
          if (std::find_if(std::begin(kMethodNames), std::end(kMethodNames), [&](const char* m) { return name == m; }) ==
              std::end(kMethodNames))
            usage("unknown method " + name);
          p.methods.push_back(name);
        }
        if (p.methods.empty()) p.methods.push_back("kew");  // kew alone
      } else {
        usage("unknown flag " + flag);
      }
    } catch (const std::logic_error&) {
      usage("bad value for " + flag);
    }
  }
  for (const std::size_t n : p.aircraft)
    if (p.recording.empty() && (n < 10 || n > 1000000)) usage("aircraft must be in [10, 1000000]");
  if (p.periods < 1 || p.warmup < 1 || !(p.brute_budget > 0)) usage("need periods >= 1, warmup >= 1, budget > 0");
  return p;
}

// ---------------------------------------------------------------------------------
// Workload: generated records, and what the Pipeline's track table makes of them

// A track's state as the probe reads it (the Pipeline's ProbeState).
struct TrackState {
  Kinematics kinematics;  // at t
  double t = 0.0;
  double scale = 1.0;
  Kinematics at(double at_t) const {  // the Pipeline's extrapolation, operation for operation
    Kinematics k = kinematics;
    const double dt = at_t - t;
    k.position = k.position + dt * k.velocity;
    k.altitude_m += dt * k.vertical_rate_mps;
    return k;
  }
};

// One applied update (the Pipeline probes) or one track leaving the engine.
struct Step {
  bool drop = false;
  Slot slot = 0;
  std::uint32_t record = 0;  // index in Workload::records
  double clock = 0.0;        // pipeline clock when it happens (UTC s)
  TrackState state;          // after the update
};

struct Workload {
  std::size_t aircraft = 0;
  double radius_km = 0.0;
  kew::PipelineConfig config;
  std::vector<kew::TrackReport> records;
  std::vector<Step> steps;
  std::vector<std::size_t> period_first_record;  // period k: [first[k], first[k+1])
  std::vector<std::size_t> period_first_step;
  double v_max = 0.0;  // fastest plane speed of any state (m/s)
  double k_max = 1.0;  // projection scale bound
  std::uint64_t rejected = 0;
  std::size_t periods_with_records = 0;
};

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

void reorder_first_period(const Params& prm, double start_time, std::vector<kew::TrackReport>& records);

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

// ---------------------------------------------------------------------------------
// Conflicts found, to compare methods

struct Conflict {
  std::uint32_t record;
  Slot p, q;  // p < q
  auto operator<=>(const Conflict&) const = default;
};

struct PeriodResult {
  double seconds = 0.0;            // measured (or, for sampled brute force, extrapolated)
  double measured_seconds = 0.0;   // what the clock said
  std::uint64_t pairs_tested = 0;  // CPA tests (sampled updates only, when sampled)
  std::uint64_t queries = 0;
  std::vector<Conflict> conflicts;
  std::uint64_t fallbacks = 0;     // (c): periods needing a full rebuild
  std::uint64_t flips = 0;         // (c)
  std::uint64_t audit_violations = 0;
  kew::PhaseTimes phases;          // kew only: where the period's time went
};

struct MethodResult {
  std::string name;
  std::string label;
  std::size_t sample_stride = 1;  // every k-th record's update is evaluated (brute force)
  std::vector<PeriodResult> periods;
  std::uint64_t missing = 0, extra = 0;  // against kew, over all periods
  double mean_seconds() const {
    double sum = 0.0;
    for (const PeriodResult& p : periods) sum += p.seconds;
    return periods.empty() ? 0.0 : sum / static_cast<double>(periods.size());
  }
  std::uint64_t total(std::uint64_t PeriodResult::*field) const {
    std::uint64_t sum = 0;
    for (const PeriodResult& p : periods) sum += p.*field;
    return sum;
  }
};

// ---------------------------------------------------------------------------------
// (a) kew

// kew as configured, and each of its speed levers turned back off, beside it in one run.
std::string fixed(double x, int decimals);

enum class KewVariant { Default, Centred, Eager, Reinserting, Renumbered };
inline constexpr kew::util::NameTable<KewVariant, 5> kKewVariantNames({{
    {KewVariant::Default, "kew"},
    {KewVariant::Centred, "kew-centred"},
    {KewVariant::Eager, "kew-eager"},
    {KewVariant::Reinserting, "kew-tau50"},
    {KewVariant::Renumbered, "kew-renumbered"},
}});
std::string variant_name(KewVariant variant) { return std::string(kKewVariantNames.name(variant)); }

// kew's time per period, then (time_phases) a second run for the split of print_split:
// timing the parts costs a few clock reads per update (about 1 µs with a TSC clock
// source, several on a virtual machine without one), kept out of the first.
MethodResult run_kew(const Params& prm, const Workload& w, KewVariant variant = KewVariant::Default,
                     bool time_phases = false) {
  kew::PipelineConfig config = w.config;
  kew::PipelineInstrumentation instruments;
  instruments.time_phases = time_phases;
  MethodResult result{variant_name(variant), "", 1, {}, 0, 0};
  switch (variant) {
    case KewVariant::Default:
      result.label = "kew: KDT updates (lazy certificates) + exact BFS probe around p + v·T (Pipeline)";
      break;
    case KewVariant::Centred:
      result.label = "kew with the earlier query: BFS around p, radius S_h + T(|v| + v_max)";
      instruments.search_ahead = false;
      break;
    case KewVariant::Eager:
      result.label = "kew with every certificate solved over the whole horizon";
      config.kinetic.lazy_window_s = 0.0;
      break;
    case KewVariant::Reinserting:
      result.label = "kew with the earlier tolerance: τ = 50 m, every update within τ changes the velocity";
      config.kinetic.tolerance = 50.0;
      config.kinetic.keep_model_s = 0.0;
      break;
    case KewVariant::Renumbered:
      result.label = "kew renumbering its points and probe states along a Hilbert curve every " +
                     fixed(prm.renumber_every_s, 0) + " s";
      config.renumber_every_s = prm.renumber_every_s;
      break;
  }
  kew::Pipeline pipeline(config);
  std::uint32_t current = 0;
  std::vector<Conflict>* sink = nullptr;
  instruments.conflict_tap = [&](Slot p, Slot q) {
    if (sink) sink->push_back({current, p, q});
  };
  pipeline.instrument(instruments);
  for (std::size_t period = 0; period < prm.warmup + prm.periods; ++period) {
    const bool measured = period >= prm.warmup;
    PeriodResult out;
    sink = measured ? &out.conflicts : nullptr;
    const std::uint64_t probes0 = pipeline.statistics().probes, pairs0 = pipeline.statistics().candidates;
    const kew::PhaseTimes phases0 = pipeline.phase_times();
    const Stopwatch clock;
    for (std::size_t i = w.period_first_record[period]; i < w.period_first_record[period + 1]; ++i) {
      current = static_cast<std::uint32_t>(i);
      pipeline.process(w.records[i]);
    }
    out.seconds = out.measured_seconds = clock.seconds();
    out.queries = pipeline.statistics().probes - probes0;
    out.pairs_tested = pipeline.statistics().candidates - pairs0;
    const kew::PhaseTimes& phases = pipeline.phase_times();
    out.phases = {phases.maintenance_s - phases0.maintenance_s, phases.search_s - phases0.search_s,
                  phases.tests_s - phases0.tests_s};
    if (measured) result.periods.push_back(std::move(out));
  }
  return result;
}

// ---------------------------------------------------------------------------------
// The baselines' common driver

// What every baseline knows of the tracks: the probe states, and how stale the index
// built at the period's start t0 may be.
struct World {
  static constexpr double kMaxIndexedJump_m = 500.0;
  std::vector<TrackState> state;
  std::vector<std::uint8_t> live;     // in the engine
  std::vector<std::uint8_t> indexed;  // in this period's index, at its t0 position
  std::vector<double> jumps;          // Σ |new − predicted| since t0, per indexed track (m)
  std::vector<Slot> extras;           // live tracks not in the index (appeared since t0)
  std::vector<std::uint8_t> in_extras;
  double jump_max = 0.0;
  double t0 = 0.0;

  void grow(Slot slot) {
    if (slot < state.size()) return;
    state.resize(slot + 1);
    live.resize(slot + 1, 0);
    indexed.resize(slot + 1, 0);
    jumps.resize(slot + 1, 0.0);
    in_extras.resize(slot + 1, 0);
  }
  void begin_period(double t) {
    t0 = t;
    jump_max = 0.0;
    for (const Slot s : extras) in_extras[s] = 0;
    extras.clear();
    for (std::size_t s = 0; s < live.size(); ++s) {
      indexed[s] = live[s];
      jumps[s] = 0.0;
    }
  }
  void apply(const Step& step) {
    grow(step.slot);
    const Slot s = step.slot;
    if (step.drop) {
      live[s] = 0;
      indexed[s] = 0;  // the slot may be reused by a new track: its index entry is stale
      return;
    }
    if (indexed[s]) {
      const Vector2 jump = step.state.at(step.clock).position - state[s].at(step.clock).position;
      jumps[s] += kew::geometry::norm(jump);
      // One track that jumped far (a manoeuvre, a bad plot) would widen every search;
      // it leaves the index instead and is tried by every query until the next rebuild.
      if (jumps[s] > kMaxIndexedJump_m) indexed[s] = 0;
      else jump_max = std::max(jump_max, jumps[s]);
    }
    if (!indexed[s] && !in_extras[s]) {
      in_extras[s] = 1;
      extras.push_back(s);
    }
    state[s] = step.state;
    live[s] = 1;
  }
  /// Bound on |current position − index position| of any indexed track at t (m).
  double staleness(double t, double v_max) const { return v_max * (t - t0) + jump_max; }
};

// The Pipeline's conflict test of the pair (slot, other) at `clock` (Pipeline::probe).
bool in_conflict(const World& world, Slot slot, const Kinematics& k_self, Slot other, double clock,
                 const kew::probe::SeparationMinima& base) {
  const TrackState& self = world.state[slot];
  const TrackState& them = world.state[other];
  kew::probe::SeparationMinima minima = base;
  minima.horizontal_m *= kew::geo::Projection::pair_scale(self.scale, them.scale);
  const Kinematics k_other = them.at(clock);
  return slot < other ? kew::probe::in_conflict(k_self, k_other, minima)
                      : kew::probe::in_conflict(k_other, k_self, minima);
}

// ---------------------------------------------------------------------------------
// (a') kew's method alone, measured as the baselines are

// How much of kew-index's work one run does. Three runs (maintenance alone, with the
// search, everything) split its time by their differences, without reading a clock
// around each part of each update: a clock read costs microseconds on virtual machines
// whose clock source is not the TSC, which is what distorts PipelineInstrumentation::time_phases.
enum class IndexWork { Maintenance, Search, All };

// What kinetic detection (design §2.7) would have to keep, counted on
// kew-index's updates: H, the pairs whose horizontal separation is below S_h somewhere in
// the look-ahead window [t, t + T] (every pair that can be in conflict is in H).
struct HorizontalCensus {
  std::uint64_t updates = 0;
  std::uint64_t candidates = 0;        // pairs the exact search returned
  std::uint64_t horizontal = 0;        // of those, pairs in H at the update: Σ |H_i|
  std::uint64_t conflicts = 0;
  std::uint64_t distinct = 0;          // pairs in H at some update of the period
  std::uint64_t entering = 0;          // of those, pairs in H at no update of the period before
  std::uint64_t entering_two_hop = 0;  // of those, pairs with a common H partner the period before
};

// Whether two tracks come within `s_h` of each other horizontally during [0, T] (m, s).
bool horizontally_close(const Kinematics& a, const Kinematics& b, double s_h, double lookahead_s) {
  const Vector2 d = b.position - a.position, v = b.velocity - a.velocity;
  const double vv = kew::geometry::dot(v, v);
  const double at = vv > 0.0 ? std::clamp(-kew::geometry::dot(d, v) / vv, 0.0, lookahead_s) : 0.0;
  const Vector2 closest = d + at * v;
  return kew::geometry::dot(closest, closest) < s_h * s_h;
}

// The Pipeline's kinetic triangulation and exact search (the disk of radius
// S_h·k_max + T·v_max + 2τ around p_i + v_i·T, design §2.1), fed the same updates as the
// baselines (the track table's output, World) and testing candidates with the same
// conflict test: the method's maintenance, search and CPA tests, without the track
// table, projection, eligibility rules and alert bookkeeping the Pipeline adds around
// them. v_max is the largest speed of the whole run, as the baselines' (the Pipeline's
// is that of the tracks live at the time).
// With `census`, counts H per measured period as well (an untimed run: hash sets).
MethodResult run_kinetic_index(const Params& prm, const Workload& w, IndexWork work = IndexWork::All,
                               std::vector<HorizontalCensus>* census = nullptr) {
  using kew::kinetic::kNoPoint;
  using kew::kinetic::PointId;
  MethodResult result{"kew-index", "kew's kinetic Delaunay triangulation and exact search alone, fed as the baselines are",
                      1, {}, 0, 0};
  const kew::probe::SeparationMinima& minima = w.config.minima;
  kew::kinetic::KineticDelaunay kdt(w.config.kinetic, 0.0);
  kew::probe::ProximitySearch search;
  World world;
  std::vector<PointId> point_of;  // by slot
  std::vector<Slot> slot_of;      // by point
  std::vector<PointId> found;
  const double epoch = w.steps.empty() ? 0.0 : std::floor(w.steps.front().clock);
  const double radius =
      minima.horizontal_m * w.k_max + minima.lookahead_s * w.v_max + 2.0 * w.config.kinetic.tolerance + 1.0;
  // The Pipeline's calls for one step (Pipeline::apply, leave_engine); the point updated.
  const auto apply = [&](const Step& s) -> PointId {
    world.grow(s.slot);
    if (point_of.size() <= s.slot) point_of.resize(s.slot + 1, kNoPoint);
    const double t = s.clock - epoch;
    kdt.advance(t);
    PointId& point = point_of[s.slot];
    if (s.drop) {
      if (point != kNoPoint) {
        kdt.remove(point, t);
        slot_of[point] = kNone;
        point = kNoPoint;
      }
      world.live[s.slot] = 0;
      return kNoPoint;
    }
    world.state[s.slot] = s.state;
    world.live[s.slot] = 1;
    const Kinematics now = s.state.at(s.clock);
    if (point == kNoPoint) {
      point = kdt.insert(t, now.position, now.velocity);
      if (slot_of.size() <= point) slot_of.resize(point + 1, kNone);
      slot_of[point] = s.slot;
    } else {
      kdt.update(point, t, now.position, now.velocity);
    }
    return point;
  };
  const auto pair_key = [](Slot a, Slot b) {
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
  };
  std::unordered_set<std::uint64_t> h_now, h_before;                      // pairs in H, this period and the one before
  std::unordered_map<Slot, std::vector<Slot>> partners_now, partners_before;  // H as adjacency lists
  std::size_t step = 0;
  for (; step < w.period_first_step[prm.warmup]; ++step) apply(w.steps[step]);
  for (std::size_t period = prm.warmup; period < prm.warmup + prm.periods; ++period) {
    PeriodResult out;
    HorizontalCensus counted;
    const Stopwatch clock;
    for (; step < w.period_first_step[period + 1]; ++step) {
      const Step& s = w.steps[step];
      const PointId point = apply(s);
      if (point == kNoPoint || work == IndexWork::Maintenance) continue;
      const Kinematics k_self = world.state[s.slot].at(s.clock);
      found.clear();
      search.within_around(kdt, point, kdt.position_now(point) + minima.lookahead_s * k_self.velocity, radius, found);
      ++out.queries;
      if (work == IndexWork::Search) continue;
      for (const PointId p : found) {
        const Slot other = slot_of[p];
        ++out.pairs_tested;
        if (in_conflict(world, s.slot, k_self, other, s.clock, minima))
          out.conflicts.push_back({s.record, std::min(s.slot, other), std::max(s.slot, other)});
        if (census) {
          const double s_h = minima.horizontal_m * kew::geo::Projection::pair_scale(world.state[s.slot].scale,
                                                                                   world.state[other].scale);
          if (horizontally_close(k_self, world.state[other].at(s.clock), s_h, minima.lookahead_s)) {
            ++counted.horizontal;
            if (h_now.insert(pair_key(s.slot, other)).second) {
              partners_now[s.slot].push_back(other);
              partners_now[other].push_back(s.slot);
            }
          }
        }
      }
    }
    out.seconds = out.measured_seconds = clock.seconds();
    if (census) {
      counted.updates = out.queries;
      counted.candidates = out.pairs_tested;
      counted.conflicts = out.conflicts.size();
      counted.distinct = h_now.size();
      std::vector<Slot> mine;
      for (const std::uint64_t key : h_now) {
        if (h_before.count(key)) continue;
        ++counted.entering;
        const auto a = partners_before.find(static_cast<Slot>(key >> 32));
        const auto b = partners_before.find(static_cast<Slot>(key & 0xFFFFFFFFu));
        if (a == partners_before.end() || b == partners_before.end()) continue;
        mine = a->second;
        std::sort(mine.begin(), mine.end());
        for (const Slot k : b->second)
          if (std::binary_search(mine.begin(), mine.end(), k)) {
            ++counted.entering_two_hop;
            break;
          }
      }
      // The period before the first measured one is not counted: nothing enters then.
      if (period > prm.warmup) census->push_back(counted);
      h_before.swap(h_now);
      partners_before.swap(partners_now);
      h_now.clear();
      partners_now.clear();
    }
    out.audit_violations += kdt.is_valid() ? 0 : 1;
    result.periods.push_back(std::move(out));
  }
  return result;
}

// (a'') Kinetic detection: the prototype fed the same steps, testing
// the candidates LookaheadPairs gives with the same conflict test. Its own counters
// (reports kept and replaced, disk searches, entries) are printed to stderr.
MethodResult run_lookahead(const Params& prm, const Workload& w) {
  MethodResult result{"kew-lookahead", "prototype: H kept by events on a kinetic triangulation of p + v·T (design §2.7)",
                      1, {}, 0, 0};
  const kew::probe::SeparationMinima& minima = w.config.minima;
  kew::testing::LookaheadPairsConfig config;
  config.separation_m = minima.horizontal_m * w.k_max;
  config.lookahead_s = minima.lookahead_s;
  config.tolerance_m = prm.lookahead_tolerance_m;
  config.keep_s = prm.lookahead_keep_s;
  config.max_speed_mps = w.v_max;
  config.kinetic = w.config.kinetic;
  const double epoch = w.steps.empty() ? 0.0 : std::floor(w.steps.front().clock);
  kew::testing::LookaheadPairs pairs(config, 0.0);
  World world;
  const auto apply = [&](const Step& s) {
    world.grow(s.slot);
    const double t = s.clock - epoch;
    if (s.drop) {
      pairs.remove(s.slot, t);
      world.live[s.slot] = 0;
      return;
    }
    world.state[s.slot] = s.state;
    world.live[s.slot] = 1;
    const Kinematics now = s.state.at(s.clock);
    pairs.report(s.slot, t, now.position, now.velocity);
  };
  std::size_t step = 0;
  for (; step < w.period_first_step[prm.warmup]; ++step) apply(w.steps[step]);
  const kew::testing::LookaheadPairsStatistics before = pairs.statistics();
  // Reports whose track replaced its model within the last 10, 30 and 60 s (this one
  // included): the tracks a hybrid would search for instead of keeping in H.
  constexpr double kRecent_s[] = {10.0, 30.0, 60.0};
  std::uint64_t recent[3] = {0, 0, 0};
  std::uint64_t measured_reports = 0;
  for (std::size_t period = prm.warmup; period < prm.warmup + prm.periods; ++period) {
    PeriodResult out;
    const Stopwatch clock;
    for (; step < w.period_first_step[period + 1]; ++step) {
      const Step& s = w.steps[step];
      apply(s);
      if (s.drop) continue;
      ++measured_reports;
      const double age = s.clock - epoch - pairs.last_replaced(s.slot);
      for (int k = 0; k < 3; ++k) recent[k] += age < kRecent_s[k] ? 1 : 0;
      const Kinematics k_self = world.state[s.slot].at(s.clock);
      pairs.for_each_candidate(s.slot, [&](Slot other) {
        ++out.pairs_tested;
        if (in_conflict(world, s.slot, k_self, other, s.clock, minima))
          out.conflicts.push_back({s.record, std::min(s.slot, other), std::max(s.slot, other)});
      });
      ++out.queries;
    }
    out.seconds = out.measured_seconds = clock.seconds();
    result.periods.push_back(std::move(out));
  }
  const kew::testing::LookaheadPairsStatistics& after = pairs.statistics();
  const auto per_period = [&](std::uint64_t a, std::uint64_t b) {
    return fixed(static_cast<double>(a - b) / static_cast<double>(prm.periods), 0);
  };
  std::cerr << "  kew-lookahead per period (epsilon " << fixed(config.tolerance_m, 0) << " m): reports "
            << per_period(after.reports, before.reports) << ", replaced " << per_period(after.replaced, before.replaced)
            << " ("
            << fixed(100.0 * static_cast<double>(after.replaced + after.drifts - before.replaced - before.drifts) /
                         std::max(1.0, static_cast<double>(after.reports - before.reports)),
                     1)
            << " % of reports with drifts)"
            << ", drifts " << per_period(after.drifts, before.drifts) << ", disk searches "
            << per_period(after.disk_searches, before.disk_searches) << ", edges told "
            << per_period(after.edges_told, before.edges_told) << ", entries "
            << per_period(after.entries, before.entries) << ", exits " << per_period(after.exits, before.exits)
            << ", candidate pairs computed " << per_period(after.two_hop_considered, before.two_hop_considered)
            << " (two-hop entries pruned " << per_period(after.two_hop_pruned, before.two_hop_pruned) << ")"
            << ", entries queued " << per_period(after.entries_queued, before.entries_queued) << ", stale "
            << per_period(after.events_stale, before.events_stale) << ", queue max " << after.queue_max << ", |H| per track "
            << fixed(static_cast<double>(pairs.pair_ends()) / static_cast<double>(w.aircraft), 1) << ", twins made "
            << pairs.triangulation_statistics().twins_created << ", reports of tracks replaced within 10/30/60 s "
            << fixed(100.0 * static_cast<double>(recent[0]) / std::max(1.0, static_cast<double>(measured_reports)), 1) << " / "
            << fixed(100.0 * static_cast<double>(recent[1]) / std::max(1.0, static_cast<double>(measured_reports)), 1) << " / "
            << fixed(100.0 * static_cast<double>(recent[2]) / std::max(1.0, static_cast<double>(measured_reports)), 1) << " %\n";
  return result;
}

// An index answers for_each_candidate(world, slot, centre, radius, f): f(j) at least for
// every indexed track j whose t0 position is within radius of centre (others allowed).
// rebuild(world, t0) makes it from the live tracks at the period's start.
template <class Index>
void run_index(const Params& prm, const Workload& w, Index& index, MethodResult& result) {
  World world;
  const kew::probe::SeparationMinima& minima = w.config.minima;
  const double lookahead = minima.lookahead_s;
  const std::size_t stride = result.sample_stride;
  std::size_t step = 0;
  for (; step < w.period_first_step[prm.warmup]; ++step) world.apply(w.steps[step]);
  {  // untimed: (c) starts each period from the previous one's triangulation
    PeriodResult unused;
    const double t_start = w.records[w.period_first_record[prm.warmup]].t;
    world.begin_period(t_start);
    index.rebuild(world, t_start, unused);
  }
  for (std::size_t period = prm.warmup; period < prm.warmup + prm.periods; ++period) {
    PeriodResult out;
    const double t0 = w.records[w.period_first_record[period]].t;
    double query_seconds = 0.0;
    std::uint64_t records_in_period = 0, sampled = 0;
    const Stopwatch clock;
    world.begin_period(t0);
    index.rebuild(world, t0, out);
    for (; step < w.period_first_step[period + 1]; ++step) {
      const Step& s = w.steps[step];
      world.apply(s);
      if (s.drop) continue;
      ++records_in_period;
      if (s.record % stride != 0) continue;
      ++sampled;
      std::optional<Stopwatch> query_clock;
      if (stride > 1) query_clock.emplace();
      const Kinematics k_self = world.state[s.slot].at(s.clock);
      const double radius = minima.horizontal_m * w.k_max +
                            lookahead * (kew::geometry::norm(k_self.velocity) + w.v_max) + 1.0 +
                            world.staleness(s.clock, w.v_max);
      const auto test = [&](Slot other) {
        if (other == s.slot || !world.live[other]) return;
        ++out.pairs_tested;
        if (in_conflict(world, s.slot, k_self, other, s.clock, minima))
          out.conflicts.push_back({s.record, std::min(s.slot, other), std::max(s.slot, other)});
      };
      // An index entry of a slot dropped since t0 is stale (the slot may hold a new track,
      // which is among the extras).
      index.for_each_candidate(world, s.slot, k_self.position, radius, [&](Slot other) {
        if (world.indexed[other]) test(other);
      });
      for (const Slot other : world.extras) test(other);
      ++out.queries;
      if (query_clock) query_seconds += query_clock->seconds();
    }
    out.measured_seconds = clock.seconds();
    out.seconds = out.measured_seconds;
    if (stride > 1 && sampled > 0)
      out.seconds += query_seconds * (static_cast<double>(records_in_period) / static_cast<double>(sampled) - 1.0);
    out.audit_violations += index.audit();
    result.periods.push_back(std::move(out));
  }
}

double squared_distance(Point2 a, Point2 b) {
  const Vector2 d = a - b;
  return kew::geometry::dot(d, d);
}

// ---------------------------------------------------------------------------------
// (b) CGAL static Delaunay triangulation, rebuilt every period

namespace cgal {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct VertexInfo {
  Slot first = kNone;      // a track at this point; others at exactly the same point chain on
  std::uint32_t seen = 0;  // BFS round that visited the vertex
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Kernel>;
using Structure = CGAL::Triangulation_data_structure_2<VertexBase>;
using Triangulation = CGAL::Delaunay_triangulation_2<Kernel, Structure>;
using CgalPoint = Kernel::Point_2;
using SortTraits = CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::Pointer_property_map<CgalPoint>::type>;
}  // namespace cgal

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

class CgalRebuild {
 public:
  void rebuild(const World& world, double t0, PeriodResult&) {
    dt_.clear();
    points_.clear();
    slots_.clear();
    for (Slot s = 0; s < world.live.size(); ++s) {
      if (!world.live[s]) continue;
      const Point2 p = world.state[s].at(t0).position;
      points_.emplace_back(p.x, p.y);
      slots_.push_back(s);
    }
    order_.resize(points_.size());
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    CGAL::spatial_sort(order_.begin(), order_.end(), cgal::SortTraits(CGAL::make_property_map(points_)));
    vertex_of_.assign(world.live.size(), {});
    same_point_next_.assign(world.live.size(), kNone);
    cgal::Triangulation::Face_handle hint;
    for (const std::size_t i : order_) {
      const auto v = dt_.insert(points_[i], hint);
      hint = v->face();
      const Slot s = slots_[i];
      same_point_next_[s] = v->info().first;  // kNone unless a duplicate
      v->info().first = s;
      vertex_of_[s] = v;
    }
  }

  template <class F>
  void for_each_candidate(const World& world, Slot slot, Point2 centre, double radius, F&& f) {
    if (dt_.number_of_vertices() == 0) return;
    const cgal::CgalPoint c(centre.x, centre.y);
    // Any vertex in the disk will do as a start (see ProximitySearch): the track's own,
    // or the nearest to the centre for a track that is not in the index.
    const auto start = slot < vertex_of_.size() && world.indexed[slot] ? vertex_of_[slot] : dt_.nearest_vertex(c);
    const double r2 = radius * radius;
    if (CGAL::squared_distance(start->point(), c) > r2) return;
    if (++round_ == 0) round_ = 1;  // a wrapped mark could only add candidates
    frontier_.assign(1, start);
    start->info().seen = round_;
    for (std::size_t next = 0; next < frontier_.size(); ++next) {
      const auto v = frontier_[next];
      for (Slot s = v->info().first; s != kNone; s = same_point_next_[s]) f(s);
      if (dt_.dimension() < 2) {  // all collinear: CGAL gives no faces, try every vertex
        for (auto it = dt_.finite_vertices_begin(); it != dt_.finite_vertices_end(); ++it)
          if (it->info().seen != round_) {
            it->info().seen = round_;
            frontier_.push_back(it);
          }
        continue;
      }
      auto around = dt_.incident_vertices(v);
      const auto done = around;
      do {
        if (dt_.is_infinite(around) || around->info().seen == round_) continue;
        around->info().seen = round_;
        if (CGAL::squared_distance(around->point(), c) <= r2) frontier_.push_back(around);
      } while (++around != done);
    }
  }

  std::uint64_t audit() const { return dt_.is_valid() ? 0 : 1; }

 private:
  cgal::Triangulation dt_;
  std::vector<cgal::CgalPoint> points_;
  std::vector<Slot> slots_;
  std::vector<std::size_t> order_;
  std::vector<cgal::Triangulation::Vertex_handle> vertex_of_;
  std::vector<Slot> same_point_next_;
  std::vector<cgal::Triangulation::Vertex_handle> frontier_;
  std::uint32_t round_ = 0;
};

// ---------------------------------------------------------------------------------
// (c) One triangulation moved in place, checked edge by edge and repaired by flips

class FlipRepair {
 public:
  void rebuild(const World& world, double t0, PeriodResult& out) {
    using kew::triangulation::kNoVertex;
    using kew::triangulation::Trajectory;
    if (vertex_of_.size() < world.live.size()) vertex_of_.resize(world.live.size(), kNoVertex);
    for (std::vector<Slot>& extra : same_point_) extra.clear();
    // Tracks gone since the last period leave first, at the positions the structure holds.
    bool broken = false;
    for (Slot s = 0; s < vertex_of_.size(); ++s) {
      const auto v = vertex_of_[s];
      if (v == kNoVertex || world.live[s]) continue;
      if (dt_.is_attached(v)) {
        const kew::triangulation::DetachResult detached = dt_.detach(v);
        broken = broken || !detached.hole_triangulated;
        // Left out by the rebuild that took: they go back in below, with the new tracks.
        for (const kew::triangulation::Eviction& e : detached.evicted) {
          vertex_of_[slot_of_vertex_[e.vertex]] = kNoVertex;
          dt_.destroy_vertex(e.vertex);
        }
      }
      dt_.destroy_vertex(v);
      vertex_of_[s] = kNoVertex;
    }
    // Every remaining vertex jumps to its track's position at t0 (velocity zero keeps it
    // there exactly while the period is probed).
    for (Slot s = 0; s < vertex_of_.size(); ++s)
      if (vertex_of_[s] != kNoVertex) dt_.set_trajectory(vertex_of_[s], Trajectory{world.state[s].at(t0).position, {}, t0});
    dt_.set_time(t0);
    // Check: a folded face (a point moved across an edge) cannot be repaired by flips.
    const kew::triangulation::Tds& tds = dt_.tds();
    seeds_.clear();
    for (kew::triangulation::FaceIndex f = 0; f < tds.face_capacity() && !broken; ++f) {
      if (!tds.face(f).alive) continue;
      if (!dt_.is_positive(f)) broken = true;
      for (int i = 0; i < 3; ++i) seeds_.emplace_back(f, i);
    }
    if (!broken) {
      stuck_.clear();
      out.flips += dt_.make_locally_delaunay(seeds_, &stuck_);
      broken = !stuck_.empty();
    }
    if (broken) {
      ++out.fallbacks;
      for (const auto& [vertex, same] : dt_.rebuild()) forget_duplicate(vertex, same);
    }
    // New tracks are inserted into the repaired triangulation.
    for (Slot s = 0; s < world.live.size(); ++s) {
      if (!world.live[s] || vertex_of_[s] != kNoVertex) continue;
      const auto v = dt_.create_vertex(Trajectory{world.state[s].at(t0).position, {}, t0});
      vertex_of_[s] = v;
      grow_slot_map(v);
      slot_of_vertex_[v] = s;
      kew::triangulation::VertexIndex same = kNoVertex;
      if (dt_.attach(v, &same, valid_hint()) == kew::triangulation::AttachResult::Duplicate) forget_duplicate(v, same);
      else hint_ = tds.vertex_face(v);
    }
  }

  template <class F>
  void for_each_candidate(const World& world, Slot slot, Point2 centre, double radius, F&& f) {
    using kew::triangulation::kInfiniteVertex;
    if (dt_.size() == 0) return;
    const kew::triangulation::Tds& tds = dt_.tds();
    const bool own = slot < vertex_of_.size() && world.indexed[slot] && vertex_of_[slot] != kew::triangulation::kNoVertex;
    const auto start = own ? vertex_of_[slot] : nearest_vertex(centre);
    const double r2 = radius * radius;
    if (squared_distance(dt_.position(start), centre) > r2) return;
    if (seen_.size() < tds.vertex_capacity()) seen_.resize(tds.vertex_capacity(), 0);
    if (++round_ == 0) round_ = 1;
    frontier_.assign(1, start);
    seen_[start] = round_;
    for (std::size_t next = 0; next < frontier_.size(); ++next) {
      const auto v = frontier_[next];
      f(slot_of_vertex_[v]);
      for (const Slot s : same_point_[v]) f(s);
      if (!tds.is_attached(v)) continue;  // fewer than two points: no faces
      tds.for_each_adjacent_vertex(v, [&](kew::triangulation::VertexIndex w) {
        if (w == kInfiniteVertex || seen_[w] == round_) return;
        seen_[w] = round_;
        if (squared_distance(dt_.position(w), centre) <= r2) frontier_.push_back(w);
      });
    }
  }

  std::uint64_t audit() const { return dt_.audit().violations(); }

 private:
  // Greedy walk to the vertex nearest `p`: from any vertex some neighbour is closer to p
  // unless the vertex is the nearest (Delaunay).
  kew::triangulation::VertexIndex nearest_vertex(Point2 p) const {
    const kew::triangulation::Tds& tds = dt_.tds();
    const kew::triangulation::Face& face = tds.face(dt_.locate(p, valid_hint()));
    auto best = face.vertex[0] != kew::triangulation::kInfiniteVertex ? face.vertex[0] : face.vertex[1];
    double best_d2 = squared_distance(dt_.position(best), p);
    for (auto current = kew::triangulation::kNoVertex; current != best;) {
      current = best;
      tds.for_each_adjacent_vertex(current, [&](kew::triangulation::VertexIndex w) {
        if (w == kew::triangulation::kInfiniteVertex) return;
        const double d2 = squared_distance(dt_.position(w), p);
        if (d2 < best_d2) {
          best_d2 = d2;
          best = w;
        }
      });
    }
    return best;
  }
  kew::triangulation::FaceIndex valid_hint() const {
    const kew::triangulation::Tds& tds = dt_.tds();
    return hint_ < tds.face_capacity() && tds.face(hint_).alive ? hint_ : kew::triangulation::kNoFace;
  }
  void grow_slot_map(kew::triangulation::VertexIndex v) {
    if (v >= slot_of_vertex_.size()) {
      slot_of_vertex_.resize(v + 1, kNone);
      same_point_.resize(v + 1);
    }
  }
  // A track at exactly another's position rides along with that vertex this period.
  void forget_duplicate(kew::triangulation::VertexIndex vertex, kew::triangulation::VertexIndex same) {
    const Slot s = slot_of_vertex_[vertex];
    grow_slot_map(same);
    same_point_[same].push_back(s);
    dt_.destroy_vertex(vertex);
    vertex_of_[s] = kew::triangulation::kNoVertex;
  }

  kew::triangulation::DelaunayTriangulation dt_;
  std::vector<kew::triangulation::VertexIndex> vertex_of_;  // by slot
  std::vector<Slot> slot_of_vertex_;
  std::vector<std::vector<Slot>> same_point_;  // by vertex: tracks at exactly its point
  std::vector<std::pair<kew::triangulation::FaceIndex, int>> seeds_, stuck_;
  std::vector<kew::triangulation::VertexIndex> frontier_;
  std::vector<std::uint32_t> seen_;
  std::uint32_t round_ = 0;
  kew::triangulation::FaceIndex hint_ = kew::triangulation::kNoFace;
};

// ---------------------------------------------------------------------------------
// (d) Uniform grid rebuilt every period

class UniformGrid {
 public:
  explicit UniformGrid(double cell_m) : cell_(cell_m) {}

  void rebuild(const World& world, double t0, PeriodResult&) {
    entries_.clear();
    double min_x = INFINITY, min_y = INFINITY, max_x = -INFINITY, max_y = -INFINITY;
    for (Slot s = 0; s < world.live.size(); ++s) {
      if (!world.live[s]) continue;
      const Point2 p = world.state[s].at(t0).position;
      entries_.push_back({p, s});
      min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
    }
    if (entries_.empty()) return;
    origin_ = {min_x, min_y};
    columns_ = static_cast<std::size_t>((max_x - min_x) / cell_) + 1;
    rows_ = static_cast<std::size_t>((max_y - min_y) / cell_) + 1;
    // Counting sort of the entries by cell: each cell's entries are contiguous.
    cell_start_.assign(columns_ * rows_ + 1, 0);
    for (const Entry& e : entries_) ++cell_start_[cell_of(e.p) + 1];
    std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
    sorted_.resize(entries_.size());
    fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (const Entry& e : entries_) sorted_[fill_[cell_of(e.p)]++] = e;
  }

  template <class F>
  void for_each_candidate(const World&, Slot, Point2 centre, double radius, F&& f) const {
    if (sorted_.empty()) return;
    const double r2 = radius * radius;
    const std::size_t x0 = clamp_cell(centre.x - radius - origin_.x, columns_);
    const std::size_t x1 = clamp_cell(centre.x + radius - origin_.x, columns_);
    const std::size_t y0 = clamp_cell(centre.y - radius - origin_.y, rows_);
    const std::size_t y1 = clamp_cell(centre.y + radius - origin_.y, rows_);
    for (std::size_t y = y0; y <= y1; ++y)
      for (std::size_t i = cell_start_[y * columns_ + x0]; i < cell_start_[y * columns_ + x1 + 1]; ++i)
        if (squared_distance(sorted_[i].p, centre) <= r2) f(sorted_[i].slot);
  }

  std::uint64_t audit() const { return 0; }

 private:
  struct Entry {
    Point2 p;
    Slot slot;
  };
  std::size_t clamp_cell(double offset, std::size_t count) const {
    const double cell = std::floor(offset / cell_);
    return cell <= 0.0 ? 0 : std::min(count - 1, static_cast<std::size_t>(cell));
  }
  std::size_t cell_of(Point2 p) const {
    return clamp_cell(p.y - origin_.y, rows_) * columns_ + clamp_cell(p.x - origin_.x, columns_);
  }

  double cell_;
  Point2 origin_;
  std::size_t columns_ = 0, rows_ = 0;
  std::vector<Entry> entries_, sorted_;
  std::vector<std::size_t> cell_start_, fill_;
};

// ---------------------------------------------------------------------------------
// (e) Brute force: every live track (BlueSky's state-based detection tests all pairs)

class BruteForce {
 public:
  void rebuild(const World&, double, PeriodResult&) {}
  template <class F>
  void for_each_candidate(const World& world, Slot, Point2, double, F&& f) const {
    for (Slot s = 0; s < world.live.size(); ++s)  // the live ones not indexed are the driver's extras
      if (world.indexed[s]) f(s);
  }
  std::uint64_t audit() const { return 0; }
};

// ---------------------------------------------------------------------------------
// Comparison and output

void compare(const MethodResult& kew_result, MethodResult& m) {
  for (std::size_t k = 0; k < m.periods.size(); ++k) {
    std::vector<Conflict> expected;
    for (const Conflict& c : kew_result.periods[k].conflicts)
      if (c.record % m.sample_stride == 0) expected.push_back(c);
    std::vector<Conflict>& found = m.periods[k].conflicts;
    std::sort(expected.begin(), expected.end());
    std::sort(found.begin(), found.end());
    std::vector<Conflict> missing, extra;
    std::set_difference(expected.begin(), expected.end(), found.begin(), found.end(), std::back_inserter(missing));
    std::set_difference(found.begin(), found.end(), expected.begin(), expected.end(), std::back_inserter(extra));
    m.missing += missing.size();
    m.extra += extra.size();
    const auto show = [&](const char* what, const std::vector<Conflict>& list) {
      for (std::size_t i = 0; i < std::min<std::size_t>(list.size(), 5); ++i)
        std::cerr << "  MISMATCH " << m.name << " period " << k << ": " << what << " record " << list[i].record
                  << " slots " << list[i].p << "-" << list[i].q << "\n";
    };
    show("kew found, baseline did not:", missing);
    show("baseline found, kew did not:", extra);
  }
}

std::string fixed(double x, int decimals) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, x);
  return text;
}

struct FleetResult {
  std::size_t aircraft = 0;
  double radius_km = 0.0;
  std::size_t records = 0;
  std::uint64_t rejected = 0;
  std::vector<MethodResult> methods;  // kew first
  std::vector<MethodResult> split;    // kew and its variants with their parts timed
  struct IndexParts {                  // kew-index's three runs (IndexWork), s per period
    double maintenance = 0.0, with_search = 0.0, all = 0.0;
  };
  std::optional<IndexParts> index_parts;
  std::vector<HorizontalCensus> census;  // by measured period after the first
};

void print_table(const Params& prm, const std::vector<FleetResult>& fleets) {
  std::cout << "\n| aircraft | method | ms / period (mean of " << prm.periods
            << ") | × kew | µs / update | pairs tested / update | conflicts | mismatches |\n"
               "|---|---|---|---|---|---|---|---|\n";
  for (const FleetResult& fleet : fleets) {
    const double kew_s = fleet.methods.front().mean_seconds();
    for (const MethodResult& m : fleet.methods) {
      const double queries = static_cast<double>(m.total(&PeriodResult::queries));
      const double updates = static_cast<double>(fleet.methods.front().total(&PeriodResult::queries)) /
                             static_cast<double>(prm.periods);
      std::string name = m.name;
      if (m.sample_stride > 1) name += " (1/" + std::to_string(m.sample_stride) + " sampled, extrapolated)";
      if (m.total(&PeriodResult::fallbacks) > 0)
        name += " (" + std::to_string(m.total(&PeriodResult::fallbacks)) + " rebuilds)";
      std::uint64_t conflicts = 0;
      for (const PeriodResult& p : m.periods) conflicts += p.conflicts.size();
      std::cout << "| " << fleet.aircraft << " | " << name << " | " << fixed(1e3 * m.mean_seconds(), 1) << " | "
                << fixed(m.mean_seconds() / kew_s, 2) << " | " << fixed(1e6 * m.mean_seconds() / updates, 2) << " | "
                << fixed(static_cast<double>(m.total(&PeriodResult::pairs_tested)) / queries, 1) << " | " << conflicts
                << " | " << (m.missing + m.extra) << " |\n";
    }
  }
}

// kew's time per period split by part (PipelineInstrumentation::time_phases; "other" is the track
// table, projection and what the parts do not cover).
void print_split(const Params& prm, const std::vector<FleetResult>& fleets) {
  std::cout << "\n| aircraft | method | maintenance ms (%) | search ms (%) | CPA tests ms (%) | other ms (%) |\n"
               "|---|---|---|---|---|---|\n";
  for (const FleetResult& fleet : fleets)
    for (const MethodResult& m : fleet.split) {
      kew::PhaseTimes sum;
      for (const PeriodResult& p : m.periods) {
        sum.maintenance_s += p.phases.maintenance_s;
        sum.search_s += p.phases.search_s;
        sum.tests_s += p.phases.tests_s;
      }
      const double n = static_cast<double>(prm.periods), total = m.mean_seconds();
      const auto cell = [&](double seconds) {
        return fixed(1e3 * seconds / n, 1) + " (" + fixed(100.0 * seconds / n / total, 0) + ")";
      };
      std::cout << "| " << fleet.aircraft << " | " << m.name << " | " << cell(sum.maintenance_s) << " | "
                << cell(sum.search_s) << " | " << cell(sum.tests_s) << " | "
                << cell(total * n - sum.maintenance_s - sum.search_s - sum.tests_s) << " |\n";
    }
}

// kew-index's parts from its three runs, beside the grid's whole period.
void print_index_parts(const std::vector<FleetResult>& fleets) {
  bool any = false;
  for (const FleetResult& fleet : fleets) any = any || fleet.index_parts.has_value();
  if (!any) return;
  std::cout << "\n| aircraft | kew-index ms / period | maintenance ms | search ms | CPA tests ms | grid ms / period | "
               "kew-index × grid |\n|---|---|---|---|---|---|---|\n";
  for (const FleetResult& fleet : fleets) {
    if (!fleet.index_parts) continue;
    const FleetResult::IndexParts& parts = *fleet.index_parts;
    const auto grid = std::find_if(fleet.methods.begin(), fleet.methods.end(),
                                   [](const MethodResult& m) { return m.name == "grid"; });
    const double grid_s = grid == fleet.methods.end() ? 0.0 : grid->mean_seconds();
    std::cout << "| " << fleet.aircraft << " | " << fixed(1e3 * parts.all, 1) << " | " << fixed(1e3 * parts.maintenance, 1)
              << " | " << fixed(1e3 * (parts.with_search - parts.maintenance), 1) << " | "
              << fixed(1e3 * (parts.all - parts.with_search), 1) << " | "
              << (grid_s > 0.0 ? fixed(1e3 * grid_s, 1) + " | " + fixed(parts.all / grid_s, 2) : std::string("- | -"))
              << " |\n";
  }
}

// The census of H (HorizontalCensus), per update and per period.
void print_census(const std::vector<FleetResult>& fleets) {
  bool any = false;
  for (const FleetResult& fleet : fleets) any = any || !fleet.census.empty();
  if (!any) return;
  std::cout << "\n| aircraft | candidates / update | in H / update | conflicts / update | pairs in H / period | "
               "entering H / period | entering with a common partner |\n|---|---|---|---|---|---|---|\n";
  for (const FleetResult& fleet : fleets) {
    if (fleet.census.empty()) continue;
    HorizontalCensus sum;
    for (const HorizontalCensus& c : fleet.census) {
      sum.updates += c.updates, sum.candidates += c.candidates, sum.horizontal += c.horizontal;
      sum.conflicts += c.conflicts, sum.distinct += c.distinct, sum.entering += c.entering;
      sum.entering_two_hop += c.entering_two_hop;
    }
    const auto per_update = [&](std::uint64_t x) {
      return fixed(static_cast<double>(x) / static_cast<double>(sum.updates), 1);
    };
    const auto per_period = [&](std::uint64_t x) {
      return fixed(static_cast<double>(x) / static_cast<double>(fleet.census.size()), 0);
    };
    std::cout << "| " << fleet.aircraft << " | " << per_update(sum.candidates) << " | " << per_update(sum.horizontal)
              << " | " << per_update(sum.conflicts) << " | " << per_period(sum.distinct) << " | "
              << per_period(sum.entering) << " | "
              << fixed(100.0 * static_cast<double>(sum.entering_two_hop) / static_cast<double>(std::max<std::uint64_t>(1, sum.entering)), 0)
              << " % |\n";
  }
}

void write_json(const Params& prm, const std::vector<FleetResult>& fleets) {
  JsonText j;
  j.begin_object();
  kew::bench::put_machine(j, KEW_BUILD_TYPE);
  j.key("parameters").begin_object();
  if (prm.recording.empty()) j.key("scenario").value(kew::replay::to_string(prm.scenario));
  else j.key("recording").value(prm.recording);
  j.key("period_s").value(prm.period_s);
  j.key("periods").value(std::uint64_t{prm.periods});
  j.key("warmup_periods").value(std::uint64_t{prm.warmup});
  j.key("seed").value(prm.seed);
  j.key("density_km2_per_aircraft").value(3.14159265358979 * 2000.0 * 2000.0 / 100000.0);
  j.end_object();
  j.key("fleets").begin_array();
  for (const FleetResult& fleet : fleets) {
    const double kew_s = fleet.methods.front().mean_seconds();
    j.begin_object();
    j.key("aircraft").value(std::uint64_t{fleet.aircraft});
    j.key("region_radius_km").value(fleet.radius_km);
    j.key("records").value(std::uint64_t{fleet.records});
    j.key("records_rejected").value(fleet.rejected);
    j.key("methods").begin_object();
    for (const MethodResult& m : fleet.methods) {
      j.key(m.name).begin_object();
      j.key("label").value(m.label);
      j.key("sample_stride").value(std::uint64_t{m.sample_stride});
      j.key("mean_s_per_period").value(m.mean_seconds());
      j.key("ratio_to_kew").value(m.mean_seconds() / kew_s);
      j.key("missing_vs_kew").value(m.missing);
      j.key("extra_vs_kew").value(m.extra);
      j.key("periods").begin_array();
      for (const PeriodResult& p : m.periods) {
        j.begin_object();
        j.key("s").value(p.seconds);
        j.key("measured_s").value(p.measured_seconds);
        j.key("updates").value(p.queries);
        j.key("pairs_tested").value(p.pairs_tested);
        j.key("conflicts").value(std::uint64_t{p.conflicts.size()});
        j.key("full_rebuilds").value(p.fallbacks);
        j.key("flips").value(p.flips);
        j.key("audit_violations").value(p.audit_violations);
        j.end_object();
      }
      j.end_array();
      j.end_object();
    }
    j.end_object();
    if (fleet.index_parts) {  // kew-index's three runs (seconds per period)
      j.key("kew_index_parts").begin_object();
      j.key("maintenance_s").value(fleet.index_parts->maintenance);
      j.key("maintenance_and_search_s").value(fleet.index_parts->with_search);
      j.key("all_s").value(fleet.index_parts->all);
      j.end_object();
    }
    if (!fleet.census.empty()) {
      j.key("kew_index_census").begin_array();
      for (const HorizontalCensus& c : fleet.census) {
        j.begin_object();
        j.key("updates").value(c.updates);
        j.key("candidates").value(c.candidates);
        j.key("in_h").value(c.horizontal);
        j.key("conflicts").value(c.conflicts);
        j.key("distinct_in_h").value(c.distinct);
        j.key("entering_h").value(c.entering);
        j.key("entering_h_with_common_partner").value(c.entering_two_hop);
        j.end_object();
      }
      j.end_array();
    }
    // The runs with their parts timed (CPU seconds per period).
    j.key("split").begin_object();
    for (const MethodResult& m : fleet.split) {
      j.key(m.name).begin_array();
      for (const PeriodResult& p : m.periods) {
        j.begin_object();
        j.key("measured_s").value(p.measured_seconds);
        j.key("maintenance_s").value(p.phases.maintenance_s);
        j.key("search_s").value(p.phases.search_s);
        j.key("tests_s").value(p.phases.tests_s);
        j.end_object();
      }
      j.end_array();
    }
    j.end_object();
    j.end_object();
  }
  j.end_array();
  j.end_object();
  if (!j.save(prm.json_path)) {
    std::cerr << "kew_peers_bench: cannot write " << prm.json_path << "\n";
    std::exit(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Params prm = parse(argc, argv);
  std::cout << "machine: " << kew::bench::cpu_model_name() << ", " << kew::bench::hardware_threads()
            << " hardware threads, build " << KEW_BUILD_TYPE << "\n"
            << "traffic: "
            << (prm.recording.empty() ? "kew-gen scenario " + std::string(kew::replay::to_string(prm.scenario))
                                      : "recording " + prm.recording)
            << ", P = " << prm.period_s << " s, " << prm.warmup << " warm-up + " << prm.periods
            << " measured periods"
            << (prm.recording.empty() ? ", seed " + std::to_string(prm.seed) +
                                            ", one aircraft per 126 km² (region radius 2,000 km·√(N/100,000))"
                                      : "")
            << "\n";
  std::vector<FleetResult> fleets;
  bool all_agree = true;
  for (const std::size_t n : prm.aircraft) {
    std::cerr << (prm.recording.empty() ? std::to_string(n) + " aircraft: generating..." : "reading...") << "\n";
    const Workload w = make_workload(prm, n);
    if (!prm.recording.empty()) {  // measure the recording's periods, not more
      prm.periods = std::max<std::size_t>(1, std::min(prm.periods, w.periods_with_records - std::min(w.periods_with_records, prm.warmup)));
      std::cerr << "  " << prm.periods << " periods measured\n";
    }
    FleetResult fleet{w.aircraft, w.radius_km, w.records.size(), w.rejected, {}, {}, {}, {}};
    std::cerr << "  " << w.records.size() << " records (" << w.rejected << " rejected), region radius "
              << fixed(w.radius_km, 0) << " km; (a) kew...\n";
    fleet.methods.push_back(run_kew(prm, w));
    // On a recording the Pipeline's own rules (the time guard, young runs, sources) give
    // its tracks other slots than the bench's track table does: the methods are checked
    // against the first one run after kew instead, which is fed what they are fed.
    const auto reference = [&]() -> const MethodResult& {
      return prm.recording.empty() ? fleet.methods.front() : fleet.methods[1];
    };
    const auto checked = [&](MethodResult m) {
      std::cerr << "  " << m.name << " done\n";
      if (prm.recording.empty() || fleet.methods.size() > 1) compare(reference(), m);
      all_agree = all_agree && m.missing == 0 && m.extra == 0;
      fleet.methods.push_back(std::move(m));
    };
    constexpr KewVariant kVariants[] = {KewVariant::Centred, KewVariant::Eager, KewVariant::Reinserting,
                                        KewVariant::Renumbered};
    for (const KewVariant variant : kVariants)
      if (wanted(prm, variant_name(variant))) checked(run_kew(prm, w, variant));
    if (wanted(prm, "kew-index")) {
      checked(run_kinetic_index(prm, w));
      fleet.index_parts = {run_kinetic_index(prm, w, IndexWork::Maintenance).mean_seconds(),
                           run_kinetic_index(prm, w, IndexWork::Search).mean_seconds(),
                           run_kinetic_index(prm, w, IndexWork::All).mean_seconds()};
      run_kinetic_index(prm, w, IndexWork::All, &fleet.census);
    }
    if (wanted(prm, "kew-lookahead")) checked(run_lookahead(prm, w));
    std::cerr << "  kew's variants again, timing their parts...\n";
    fleet.split.push_back(run_kew(prm, w, KewVariant::Default, true));
    for (const KewVariant variant : kVariants)
      if (wanted(prm, variant_name(variant))) fleet.split.push_back(run_kew(prm, w, variant, true));

    const double r_max = w.config.minima.horizontal_m * w.k_max + 2.0 * w.config.minima.lookahead_s * w.v_max;
    const auto run = [&](const char* name, const char* label, auto& index, std::size_t stride) {
      std::cerr << "  " << name << "...\n";
      MethodResult m{name, label, stride, {}, 0, 0};
      run_index(prm, w, index, m);
      if (prm.recording.empty() || fleet.methods.size() > 1) compare(reference(), m);
      all_agree = all_agree && m.missing == 0 && m.extra == 0;
      fleet.methods.push_back(std::move(m));
    };
    if (wanted(prm, "cgal")) {
      CgalRebuild cgal;
      run("cgal", "CGAL Delaunay_triangulation_2 (Epick) rebuilt per period, spatial sort + BFS", cgal, 1);
    }
    if (wanted(prm, "flip")) {
      FlipRepair flip;
      run("flip", "positions updated in place, every edge checked (exact incircle), Lawson flips", flip, 1);
    }
    if (wanted(prm, "grid")) {
      UniformGrid grid(r_max);
      run("grid", "uniform grid (cell = R_max) rebuilt per period", grid, 1);
    }
    const double pairs = static_cast<double>(n) * static_cast<double>(n);
    const auto stride = static_cast<std::size_t>(std::max(1.0, std::ceil(pairs / prm.brute_budget)));
    BruteForce brute;
    if (wanted(prm, "brute")) run("brute", "brute force, all pairs per update (BlueSky state-based)", brute, stride);
    for (const MethodResult& m : fleet.methods)
      for (const PeriodResult& p : m.periods)
        if (p.audit_violations) {
          std::cerr << "  " << m.name << ": triangulation audit found " << p.audit_violations << " violations\n";
          all_agree = false;
        }
    fleets.push_back(std::move(fleet));
  }
  print_table(prm, fleets);
  print_split(prm, fleets);
  print_index_parts(fleets);
  print_census(fleets);
  if (!prm.json_path.empty()) write_json(prm, fleets);
  if (!all_agree) std::cerr << "kew_peers_bench: a baseline disagrees with kew (see MISMATCH lines)\n";
  return all_agree ? 0 : 1;
}
