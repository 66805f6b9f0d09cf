// kew_thesis_bench: reproduces, on one radar-like workload and in one run, the three
// effects the thesis reports for its kinetic Delaunay triangulation:
//   (A) §10.4 Fig 10.4 — the event-time threshold H shrinks the priority queue;
//   (B) §10.4 Fig 10.3 — a reinsertion tolerance τ > 0 makes updates cheaper;
//   (C) §8.3 Figs 8.3/8.6 — the redundant event reduction lowers the share of
//       computed events that are discarded before their time.
// Every configuration replays the same pre-generated measurement stream, and each
// comparison varies one knob from a common baseline (H = P, τ = 50 m, §8.3 on).
//
// Usage: kew_thesis_bench [--quick] [--aircraft N] [--period P] [--duration D]
//                         [--tolerance M] [--seed S] [--json FILE]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "kew/kinetic/kinetic_delaunay.hpp"

#ifndef KEW_BUILD_TYPE
#define KEW_BUILD_TYPE "unknown"
#endif

namespace {

using kew::geometry::Point2;
using kew::geometry::Vector2;
using kew::kinetic::KineticConfig;
using kew::kinetic::KineticDelaunay;
using kew::kinetic::KineticStatistics;
using kew::kinetic::PointId;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------
// Parameters

struct Params {
  std::size_t aircraft = 2000;
  double period_s = 4.0;      // radar rotation period P
  double duration_s = 300.0;  // simulated time D
  double tolerance_m = 50.0;  // τ of the baseline (absolute mode)
  double noise_sigma_m = 30.0;
  double max_turn_deg_s = 1.5;
  double speed_min = 120.0, speed_max = 260.0;
  std::uint64_t seed = 20240611;
  std::string json_path;
  // Side of the square (m). 800 km for 2000 aircraft (≈ one aircraft per 320 km², a
  // busy en-route sector); scaled with √N so other N keep the same density.
  double side_m() const { return 800e3 * std::sqrt(static_cast<double>(aircraft) / 2000.0); }
};

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr,
               "kew_thesis_bench: %s\nusage: kew_thesis_bench [--quick] [--aircraft N] [--period S] "
               "[--duration S] [--tolerance M] [--seed S] [--json FILE]\n",
               why);
  std::exit(2);
}

Params parse(int argc, char** argv) {
  Params p;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    // Every flag but --quick takes a value.
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(("missing value for " + a).c_str());
      return argv[++i];
    };
    try {
      if (a == "--quick") {  // smoke run; later flags still override
        p.aircraft = 300;
        p.duration_s = 60.0;
      } else if (a == "--aircraft") {
        p.aircraft = std::stoul(value());
      } else if (a == "--period") {
        p.period_s = std::stod(value());
      } else if (a == "--duration") {
        p.duration_s = std::stod(value());
      } else if (a == "--tolerance") {
        p.tolerance_m = std::stod(value());
      } else if (a == "--seed") {
        p.seed = std::stoull(value());
      } else if (a == "--json") {
        p.json_path = value();
      } else {
        usage(("unknown flag " + a).c_str());
      }
    } catch (const std::logic_error&) {  // stoul/stod: invalid_argument, out_of_range
      usage(("bad value for " + a).c_str());
    }
  }
  if (p.aircraft < 3 || !(p.period_s > 0) || !(p.duration_s >= p.period_s) || !(p.tolerance_m > 0))
    usage("need N >= 3, P > 0, D >= P, tolerance > 0");
  return p;
}

// ---------------------------------------------------------------------------------
// Workload: one measurement stream shared by every configuration

struct Measurement {
  double t;
  std::uint32_t aircraft;
  Point2 p;
  Vector2 v;
};

struct Workload {
  std::vector<Measurement> initial;  // t = 0, one per aircraft, inserted during setup
  std::vector<Measurement> updates;  // time-ordered
  std::size_t periods = 0;
};

// True motion of one aircraft: constant speed, piecewise-constant turn rate. Segments
// last 20–120 s and half of them are straight, so most aircraft fly straight most of
// the time while some turn at up to max_turn — the case where a linear prediction
// drifts and τ decides between a velocity update and a reinsertion.
struct Flight {
  Point2 p;
  double heading = 0.0;  // rad, from the x axis
  double speed = 0.0;
  double turn = 0.0;     // rad/s
  double segment_end = 0.0;

  Vector2 velocity() const { return {speed * std::cos(heading), speed * std::sin(heading)}; }

  void new_segment(double now, double max_turn, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> length(20.0, 120.0), rate(-max_turn, max_turn);
    std::bernoulli_distribution straight(0.5);
    turn = straight(rng) ? 0.0 : rate(rng);
    segment_end = now + length(rng);
  }

  // Moves from `now` to `now + dt` exactly (circular arcs), crossing segment ends.
  void fly(double now, double dt, double max_turn, std::mt19937_64& rng) {
    while (dt > 0) {
      const double h = std::min(dt, segment_end - now);
      if (turn == 0.0) {
        p = p + h * velocity();
      } else {
        const double r = speed / turn, h1 = heading + turn * h;
        p = p + Vector2{r * (std::sin(h1) - std::sin(heading)), r * (std::cos(heading) - std::cos(h1))};
        heading = h1;
      }
      now += h;
      dt -= h;
      if (now >= segment_end) new_segment(now, max_turn, rng);
    }
  }
};

Workload make_workload(const Params& prm) {
  std::mt19937_64 rng(prm.seed);
  std::uniform_real_distribution<double> pos(0.0, prm.side_m()), speed(prm.speed_min, prm.speed_max),
      angle(0.0, 2 * std::numbers::pi);
  std::normal_distribution<double> noise(0.0, prm.noise_sigma_m);
  const double max_turn = prm.max_turn_deg_s * std::numbers::pi / 180.0;
  const std::size_t n = prm.aircraft;

  // The antenna sweeps the aircraft in a fixed order: aircraft slot[k] is seen at
  // offset (k + ½)·P/N in every period, so times are spread over the period.
  std::vector<std::uint32_t> slot(n);
  for (std::uint32_t i = 0; i < n; ++i) slot[i] = i;
  std::shuffle(slot.begin(), slot.end(), rng);
  std::vector<double> offset(n);
  for (std::size_t k = 0; k < n; ++k)
    offset[slot[k]] = (static_cast<double>(k) + 0.5) * prm.period_s / static_cast<double>(n);

  Workload w;
  w.periods = static_cast<std::size_t>(std::floor(prm.duration_s / prm.period_s));
  w.initial.reserve(n);
  w.updates.reserve(n * w.periods);
  auto measure = [&](double t, std::uint32_t i, const Flight& f) {
    return Measurement{t, i, f.p + Vector2{noise(rng), noise(rng)}, f.velocity()};
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    Flight f{{pos(rng), pos(rng)}, angle(rng), speed(rng)};
    f.new_segment(0.0, max_turn, rng);
    w.initial.push_back(measure(0.0, i, f));
    double t = 0.0;
    for (std::size_t k = 0; k < w.periods; ++k) {
      const double next = static_cast<double>(k) * prm.period_s + offset[i];
      f.fly(t, next - t, max_turn, rng);
      t = next;
      w.updates.push_back(measure(t, i, f));
    }
  }
  // The engine's clock only moves forward: replay measurements in time order.
  std::stable_sort(w.updates.begin(), w.updates.end(),
                   [](const Measurement& a, const Measurement& b) { return a.t < b.t; });
  return w;
}

// ---------------------------------------------------------------------------------
// Running one configuration

struct Run {
  std::string name;
  KineticConfig config;
  KineticStatistics stats;
  double setup_s = 0;    // initial insertion of all aircraft (not part of the comparison)
  double advance_s = 0;  // processing events up to each measurement time
  double update_s = 0;   // update() itself, its clock already at the measurement time
  double loop_s = 0;     // the whole update loop: advance + update + clock reads
  std::size_t updates = 0;
  // Sampled after each advance() of the loop. The engine keeps only the current
  // renewals_queued, and its queue_mean() also samples the queue while it fills during
  // setup, so both are sampled here at the same instants to add them up.
  double failures_queued_mean = 0;
  double renewals_queued_mean = 0;
  // What the priority queue really holds besides stale entries: with H, edges without
  // a failure before now + H hold a renewal entry instead of nothing.
  double entries_queued_mean() const { return failures_queued_mean + renewals_queued_mean; }
  bool valid = false;

  double update_us() const { return 1e6 * update_s / static_cast<double>(updates); }
  double advance_us() const { return 1e6 * advance_s / static_cast<double>(updates); }
  double per_measurement_us() const { return 1e6 * loop_s / static_cast<double>(updates); }
  double discarded_share() const {
    return stats.events_computed ? static_cast<double>(stats.events_discarded) / static_cast<double>(stats.events_computed)
                                 : 0.0;
  }
};

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

Run run(const std::string& name, const KineticConfig& config, const Workload& w) {
  Run r;
  r.name = name;
  r.config = config;
  KineticDelaunay kdt(config, 0.0);
  std::vector<PointId> id(w.initial.size());

  const auto s0 = Clock::now();
  for (const Measurement& m : w.initial) id[m.aircraft] = kdt.insert(m.t, m.p, m.v);
  r.setup_s = seconds(Clock::now() - s0);

  // advance() is called before update() so that event processing up to the
  // measurement time is timed apart from the update itself: update() would
  // otherwise advance internally and the τ comparison would mostly measure the
  // (shared) event processing.
  const auto l0 = Clock::now();
  for (const Measurement& m : w.updates) {
    const auto a0 = Clock::now();
    kdt.advance(m.t);
    const auto a1 = Clock::now();
    r.failures_queued_mean += static_cast<double>(kdt.statistics().queue_now);
    r.renewals_queued_mean += static_cast<double>(kdt.statistics().renewals_queued);
    kdt.update(id[m.aircraft], m.t, m.p, m.v);
    const auto a2 = Clock::now();
    r.advance_s += seconds(a1 - a0);
    r.update_s += seconds(a2 - a1);
  }
  r.loop_s = seconds(Clock::now() - l0);

  r.updates = w.updates.size();
  r.failures_queued_mean /= static_cast<double>(r.updates);
  r.renewals_queued_mean /= static_cast<double>(r.updates);
  r.stats = kdt.statistics();
  r.valid = kdt.is_valid();  // a fast run that broke the triangulation proves nothing
  return r;
}

// ---------------------------------------------------------------------------------
// Output

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

// A minimal JSON writer (nlohmann-json is not installed): objects, strings, numbers.
class Json {
 public:
  explicit Json(std::ostream& out) : out_(out) {}
  void open(const char* key = nullptr) { prefix(key); out_ << '{'; first_ = true; ++depth_; }
  void close() { --depth_; out_ << '\n' << std::string(2 * depth_, ' ') << '}'; first_ = false; }
  void put(const char* key, const std::string& s) { prefix(key); quote(s); }
  void put(const char* key, const char* s) { put(key, std::string(s)); }
  void put(const char* key, bool b) { prefix(key); out_ << (b ? "true" : "false"); }
  void put(const char* key, std::uint64_t n) { prefix(key); out_ << n; }
  void put(const char* key, double x) {
    prefix(key);
    if (std::isfinite(x)) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.9g", x);
      out_ << buf;
    } else {
      out_ << "null";  // JSON has no infinity; used for H = ∞
    }
  }

 private:
  void prefix(const char* key) {
    if (depth_ > 0) out_ << (first_ ? "\n" : ",\n") << std::string(2 * depth_, ' ');
    if (key) { quote(key); out_ << ": "; }
    first_ = false;
  }
  void quote(const std::string& s) {
    out_ << '"';
    for (const char c : s) {
      if (c == '"' || c == '\\') out_ << '\\' << c;
      else if (static_cast<unsigned char>(c) < 0x20) out_ << ' ';
      else out_ << c;
    }
    out_ << '"';
  }
  std::ostream& out_;
  bool first_ = true;
  int depth_ = 0;
};

void write_json(const std::string& path, const Params& prm, const Workload& w, const std::vector<Run>& runs) {
  std::ofstream file(path);
  if (!file) {
    std::fprintf(stderr, "kew_thesis_bench: cannot write %s\n", path.c_str());
    std::exit(1);
  }
  Json j(file);
  j.open();
  j.open("machine");
  j.put("cpu", cpu_model());
  j.put("nproc", static_cast<std::uint64_t>(std::thread::hardware_concurrency()));
  j.put("compiler", __VERSION__);
  j.put("build_type", KEW_BUILD_TYPE);
  j.close();
  j.open("parameters");
  j.put("aircraft", static_cast<std::uint64_t>(prm.aircraft));
  j.put("side_m", prm.side_m());
  j.put("period_s", prm.period_s);
  j.put("duration_s", prm.duration_s);
  j.put("periods", static_cast<std::uint64_t>(w.periods));
  j.put("measurements", static_cast<std::uint64_t>(w.updates.size()));
  j.put("speed_min_m_s", prm.speed_min);
  j.put("speed_max_m_s", prm.speed_max);
  j.put("max_turn_deg_s", prm.max_turn_deg_s);
  j.put("noise_sigma_m", prm.noise_sigma_m);
  j.put("seed", prm.seed);
  j.close();
  j.open("configurations");
  for (const Run& r : runs) {
    const KineticStatistics& s = r.stats;
    j.open(r.name.c_str());
    j.put("horizon_s", r.config.horizon_s);
    j.put("tolerance_m", r.config.tolerance);
    j.put("reduce_redundant_events", r.config.reduce_redundant_events);
    j.put("valid_at_end", r.valid);
    j.open("timing");
    j.put("setup_s", r.setup_s);
    j.put("loop_s", r.loop_s);
    j.put("advance_s", r.advance_s);
    j.put("update_s", r.update_s);
    j.put("update_us_per_call", r.update_us());
    j.put("advance_us_per_call", r.advance_us());
    j.put("loop_us_per_measurement", r.per_measurement_us());
    j.close();
    j.open("statistics");
    j.put("certificates_solved", s.certificates_solved);
    j.put("events_computed", s.events_computed);
    j.put("events_executed", s.events_executed);
    j.put("events_discarded", s.events_discarded);
    j.put("discarded_share", r.discarded_share());
    j.put("events_early", s.events_early);
    j.put("tangencies_ignored", s.tangencies_ignored);
    j.put("renewals", s.renewals);
    j.put("insertions", s.insertions);
    j.put("removals", s.removals);
    j.put("updates", s.updates);
    j.put("velocity_updates", s.velocity_updates);
    j.put("reinsertions", s.reinsertions);
    j.put("repairs", s.repairs);
    j.put("repair_flips", s.repair_flips);
    j.put("repair_reinsertions", s.repair_reinsertions);
    j.put("rebuilds", s.rebuilds);
    j.put("twins_created", s.twins_created);
    j.put("twins_released", s.twins_released);
    j.put("queue_now", static_cast<std::uint64_t>(s.queue_now));
    j.put("queue_max", static_cast<std::uint64_t>(s.queue_max));
    j.put("queue_mean", s.queue_mean());
    j.put("queue_samples", s.queue_samples);
    j.put("renewals_queued_now", static_cast<std::uint64_t>(s.renewals_queued));
    j.put("loop_failures_queued_mean", r.failures_queued_mean);
    j.put("loop_renewals_queued_mean", r.renewals_queued_mean);
    j.put("loop_entries_queued_mean", r.entries_queued_mean());
    j.close();
    j.close();
  }
  j.close();
  j.close();
  file << '\n';
}

double ratio(double a, double b) { return b != 0 ? a / b : std::nan(""); }

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}
std::string count(std::uint64_t n) { return std::to_string(n); }

void print_tables(const Run& base, const Run& no_h, const Run& no_tau, const Run& no_red) {
  auto h = [](const Run& r) { return std::isfinite(r.config.horizon_s) ? fmt("%g s", r.config.horizon_s) : "∞"; };
  auto row = [](const Run& r, std::initializer_list<std::string> cells) {
    std::cout << "| " << r.name << (r.valid ? "" : " (INVALID)");
    for (const auto& c : cells) std::cout << " | " << c;
    std::cout << " |\n";
  };

  std::cout << "\n### (A) Priority queue length: threshold H (thesis §10.4, Fig 10.4)\n\n"
               "| config | H | queue mean | queue max | renewals queued (mean) | failures + renewals (mean) | "
               "renewals run | events computed | loop time (s) |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const Run* r : {&base, &no_h})
    row(*r, {h(*r), fmt("%.1f", r->stats.queue_mean()), count(r->stats.queue_max), fmt("%.1f", r->renewals_queued_mean),
             fmt("%.1f", r->entries_queued_mean()), count(r->stats.renewals), count(r->stats.events_computed),
             fmt("%.2f", r->loop_s)});
  std::cout << "\nqueue mean with H / without H = " << fmt("%.4f", ratio(base.stats.queue_mean(), no_h.stats.queue_mean()))
            << "; queue max ratio = "
            << fmt("%.4f", ratio(static_cast<double>(base.stats.queue_max), static_cast<double>(no_h.stats.queue_max)))
            << "; failures + renewals ratio = "
            << fmt("%.4f", ratio(base.entries_queued_mean(), no_h.entries_queued_mean())) << "  (thesis: ≈ 0.01)\n"
            << "(queue = scheduled failures, the thesis' events; renewals are the entries that re-examine an edge "
               "at now + H instead)\n";

  std::cout << "\n### (B) Update cost: tolerance τ (thesis §10.4, Fig 10.3)\n\n"
               "| config | τ | update() µs/call | advance µs/call | loop µs/measurement | velocity updates | "
               "reinsertions |\n|---|---|---|---|---|---|---|\n";
  for (const Run* r : {&base, &no_tau})
    row(*r, {fmt("%g m", r->config.tolerance), fmt("%.2f", r->update_us()), fmt("%.2f", r->advance_us()),
             fmt("%.2f", r->per_measurement_us()), count(r->stats.velocity_updates), count(r->stats.reinsertions)});
  std::cout << "\nupdate cost τ>0 / τ=0 = " << fmt("%.3f", ratio(base.update_s, no_tau.update_s))
            << "; whole loop (incl. events) = " << fmt("%.3f", ratio(base.loop_s, no_tau.loop_s))
            << "  (thesis: ≈ 0.15)\n";

  std::cout << "\n### (C) Discarded events: redundant event reduction (thesis §8.3, Figs 8.3/8.6)\n\n"
               "| config | §8.3 | certificates solved | events computed | executed | discarded | discarded share | "
               "loop time (s) |\n|---|---|---|---|---|---|---|---|\n";
  for (const Run* r : {&base, &no_red})
    row(*r, {r->config.reduce_redundant_events ? "on" : "off", count(r->stats.certificates_solved),
             count(r->stats.events_computed), count(r->stats.events_executed), count(r->stats.events_discarded),
             fmt("%.3f", r->discarded_share()), fmt("%.2f", r->loop_s)});
  std::cout << "\ndiscarded share with §8.3 / without = " << fmt("%.3f", ratio(base.discarded_share(), no_red.discarded_share()))
            << "  (thesis: ≈ 0.5 → ≈ 0.33, ratio ≈ 0.67)\n";
}

}  // namespace

int main(int argc, char** argv) {
  const Params prm = parse(argc, argv);
  std::cout << "machine: " << cpu_model() << ", nproc " << std::thread::hardware_concurrency() << ", build "
            << KEW_BUILD_TYPE << "\n"
            << "workload: " << prm.aircraft << " aircraft in " << fmt("%.0f", prm.side_m() / 1e3) << " km square, P = "
            << prm.period_s << " s, D = " << prm.duration_s << " s, noise σ = " << prm.noise_sigma_m << " m, seed "
            << prm.seed << "\n";
  const Workload w = make_workload(prm);

  KineticConfig base;
  base.horizon_s = prm.period_s;  // one radar period: new data will have arrived by then
  base.tolerance = prm.tolerance_m;
  base.tolerance_mode = kew::kinetic::ToleranceMode::Absolute;
  base.reduce_redundant_events = true;
  KineticConfig no_h = base, no_tau = base, no_red = base;
  no_h.horizon_s = kew::kinetic::kNever;
  no_tau.tolerance = 0.0;
  no_red.reduce_redundant_events = false;

  const std::pair<const char*, KineticConfig> configs[] = {
      {"baseline", base}, {"no_threshold", no_h}, {"zero_tolerance", no_tau}, {"no_reduction", no_red}};
  std::vector<Run> runs;
  for (const auto& [name, cfg] : configs) {
    std::cerr << "running " << name << "...\n";
    runs.push_back(run(name, cfg, w));
    std::cerr << "  " << fmt("%.2f", runs.back().setup_s + runs.back().loop_s) << " s\n";
  }
  print_tables(runs[0], runs[1], runs[2], runs[3]);
  if (!prm.json_path.empty()) write_json(prm.json_path, prm, w, runs);

  bool all_valid = true;
  for (const Run& r : runs) all_valid = all_valid && r.valid;
  if (!all_valid) std::cerr << "kew_thesis_bench: a configuration ended with an invalid triangulation\n";
  return all_valid ? 0 : 1;
}
