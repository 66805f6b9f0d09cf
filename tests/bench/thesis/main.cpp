// kew_thesis_bench: the three effects the thesis reports for its kinetic Delaunay
// triangulation, measured on a radar-like workload, at the thesis' setting and along
// sweeps of each parameter:
//   (A) §10.4 Fig. 10.4 — the event-time threshold H shrinks the priority queue;
//   (B) §10.4 Fig. 10.3 — a reinsertion tolerance τ > 0 makes updates cheaper;
//   (C) §8.3 Figs. 8.3/8.6 — the redundant event reduction lowers the share of
//       computed events that are discarded before their time.
// Each point replays one pre-generated measurement stream with every configuration,
// each varying one knob from a common baseline (H = P, τ = 50 m, §8.3 on; no lazy
// certificates, no kept models: the thesis' method alone), and beside it kew's kept
// models and the thesis' remove-and-insert reinsertion. Times are the median of
// --repeats runs. docs/performance-kinetic.md explains the figures; plot_thesis.py draws
// them from the JSON.
//
// Usage: kew_thesis_bench [--aircraft N] [--period S] [--duration S] [--noise M]
//          [--tolerance M] [--seed S] [--repeats K] [--sweeps all|LIST] [--counts-only]
//          [--only CONFIGURATION] [--quick] [--json FILE]
// LIST: comma-separated of aircraft, period, noise, tolerance, horizon.
// --counts-only runs once the configurations whose figures are counts, not times (the
// queue and discarded ratios): deterministic, for the check of the documented figures.
// --only runs one configuration of the setting once, for a profiler (profile_thesis.py).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../bench_report.hpp"
#include "runner.hpp"
#include "workload.hpp"

namespace {

using namespace kew::bench::thesis;
using kew::bench::JsonText;

struct Point {
  WorkloadParameters workload;
  double tolerance_m = 50.0;
  double horizon_periods = 1.0;  ///< H in radar periods; ∞: no threshold
  double horizon_s() const { return horizon_periods * workload.period_s; }
};

struct Options {
  Point setting;
  int repeats = 3;
  std::vector<std::string> sweeps;
  bool counts_only = false;
  bool quick = false;  ///< a smoke run: the aircraft sweep stops at 1,000
  std::string only;  ///< run this configuration alone (for a profiler)
  std::string json_path;
  std::string command;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "kew_thesis_bench: " << why
            << "\nusage: kew_thesis_bench [--aircraft N] [--period S] [--duration S] [--noise M] [--tolerance M] "
               "[--seed S] [--repeats K] [--sweeps all|aircraft,period,noise,tolerance,horizon] [--counts-only] "
               "[--only CONFIGURATION] [--quick] [--json FILE]\n";
  std::exit(2);
}

const std::vector<std::string> kSweepNames{"aircraft", "period", "noise", "tolerance", "horizon"};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 0; i < argc; ++i) {
    if (i > 0) o.command += ' ';
    o.command += argv[i];
  }
  WorkloadParameters& w = o.setting.workload;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage("missing value for " + a);
      return argv[++i];
    };
    try {
      if (a == "--quick") {  // smoke run; later flags still override
        w.aircraft = 300;
        w.duration_s = 60.0;
        o.repeats = 1;
        o.quick = true;
      } else if (a == "--aircraft") {
        w.aircraft = std::stoul(value());
      } else if (a == "--period") {
        w.period_s = std::stod(value());
      } else if (a == "--duration") {
        w.duration_s = std::stod(value());
      } else if (a == "--noise") {
        w.noise_sigma_m = std::stod(value());
      } else if (a == "--tolerance") {
        o.setting.tolerance_m = std::stod(value());
      } else if (a == "--seed") {
        w.seed = std::stoull(value());
      } else if (a == "--repeats") {
        o.repeats = std::stoi(value());
      } else if (a == "--sweeps") {
        std::stringstream list(value());
        for (std::string name; std::getline(list, name, ',');) {
          if (name == "all") o.sweeps = kSweepNames;
          else if (std::find(kSweepNames.begin(), kSweepNames.end(), name) != kSweepNames.end()) o.sweeps.push_back(name);
          else usage("unknown sweep " + name);
        }
      } else if (a == "--only") {
        o.only = value();
      } else if (a == "--counts-only") {
        o.counts_only = true;
      } else if (a == "--json") {
        o.json_path = value();
      } else {
        usage("unknown flag " + a);
      }
    } catch (const std::logic_error&) {  // stoul/stod: invalid_argument, out_of_range
      usage("bad value for " + a);
    }
  }
  if (w.aircraft < 3 || !(w.period_s > 0) || !(w.duration_s >= w.period_s) || !(o.setting.tolerance_m > 0) ||
      !(w.noise_sigma_m >= 0) || o.repeats < 1)
    usage("need N >= 3, P > 0, D >= P, tolerance > 0, noise >= 0, repeats >= 1");
  return o;
}

// ---------------------------------------------------------------------------------
// The configurations of one point and the ratios between them

std::vector<Configuration> configurations_of(const Point& point, bool counts_only, bool trace) {
  kew::kinetic::KineticConfig base;
  base.horizon_s = point.horizon_s();
  base.tolerance = point.tolerance_m;
  base.tolerance_mode = kew::kinetic::ToleranceMode::Absolute;
  base.reduce_redundant_events = true;
  auto with = [&](auto change) {
    kew::kinetic::KineticConfig k = base;
    change(k);
    return k;
  };
  std::vector<Configuration> c{
      {"baseline", base, Reinsertion::Engine, trace},
      {"no_threshold", with([](auto& k) { k.horizon_s = kew::kinetic::kNever; }), Reinsertion::Engine, trace},
      {"no_reduction", with([](auto& k) { k.reduce_redundant_events = false; }), Reinsertion::Engine, false},
  };
  if (counts_only) return c;
  const double period = point.workload.period_s;
  c.push_back({"zero_tolerance", with([](auto& k) { k.tolerance = 0.0; }), Reinsertion::Engine, false});
  c.push_back({"kept_models", with([&](auto& k) { k.keep_model_s = period; }), Reinsertion::Engine, false});
  c.push_back({"remove_insert", base, Reinsertion::RemoveInsert, false});
  c.push_back({"remove_insert_zero_tolerance", with([](auto& k) { k.tolerance = 0.0; }), Reinsertion::RemoveInsert,
               false});
  return c;
}

double ratio(double a, double b) { return b != 0 ? a / b : std::nan(""); }

/// name → value; absent figures (counts-only runs) are left out.
std::map<std::string, double> ratios_of(const std::map<std::string, const RunResult*>& by_name) {
  std::map<std::string, double> r;
  auto has = [&](const char* name) { return by_name.count(name) > 0; };
  auto of = [&](const char* name) -> const RunResult& { return *by_name.at(name); };
  const RunResult& base = of("baseline");
  const RunResult& no_h = of("no_threshold");
  r["queue_failures"] = ratio(base.stats.queue_mean(), no_h.stats.queue_mean());
  r["queue_entries"] = ratio(base.entries_queued_mean(), no_h.entries_queued_mean());
  r["events_computed"] = ratio(static_cast<double>(base.stats.events_computed),
                               static_cast<double>(no_h.stats.events_computed));
  r["discarded"] = ratio(base.discarded_share(), of("no_reduction").discarded_share());
  r["velocity_share"] = ratio(static_cast<double>(base.stats.velocity_updates), static_cast<double>(base.updates));
  if (!has("zero_tolerance")) return r;
  const RunResult& zero = of("zero_tolerance");
  r["threshold_loop_cost"] = ratio(base.loop_s, no_h.loop_s);
  r["update_cost"] = ratio(base.update_s, zero.update_s);
  r["loop_cost"] = ratio(base.loop_s, zero.loop_s);
  r["update_cost_kept_models"] = ratio(of("kept_models").update_s, zero.update_s);
  r["loop_cost_kept_models"] = ratio(of("kept_models").loop_s, zero.loop_s);
  r["update_cost_remove_insert"] = ratio(of("remove_insert").update_s, of("remove_insert_zero_tolerance").update_s);
  r["velocity_only_per_reinsertion"] = ratio(base.velocity_only.us_per_call(), base.reinserted.us_per_call());
  r["remove_insert_per_reinsertion"] =
      ratio(of("remove_insert_zero_tolerance").reinserted.us_per_call(), zero.reinserted.us_per_call());
  return r;
}

struct PointResult {
  std::string sweep;
  double value = 0;
  Point point;
  std::vector<RunResult> runs;
  std::map<std::string, double> ratios;
};

PointResult measure(const std::string& sweep, double value, const Point& point, const Options& o, bool trace) {
  char shown[32];
  std::snprintf(shown, sizeof shown, "%g", value);
  std::cerr << "  " << (sweep.empty() ? "setting" : sweep + " = " + shown) << ": " << std::flush;
  const Workload w = make_workload(point.workload);
  PointResult p{sweep, value, point, run_medians(configurations_of(point, o.counts_only, trace), w, o.counts_only ? 1 : o.repeats), {}};
  std::map<std::string, const RunResult*> by_name;
  for (const RunResult& r : p.runs) by_name[r.configuration.name] = &r;
  p.ratios = ratios_of(by_name);
  double spent = 0;
  for (const RunResult& r : p.runs) spent += r.setup_s + r.loop_s;
  std::cerr << static_cast<int>(spent * (o.counts_only ? 1 : o.repeats)) << " s\n";
  return p;
}

/// The points of one sweep: the setting with one parameter varied.
std::vector<std::pair<double, Point>> sweep_points(const std::string& name, const Point& setting, bool quick) {
  std::vector<std::pair<double, Point>> points;
  auto add = [&](double value, auto change) {
    Point p = setting;
    change(p);
    points.emplace_back(value, p);
  };
  if (name == "aircraft") {
    for (const double n : {250, 500, 1000, 2000, 5000, 10000, 20000, 50000, 100000}) {
      if (quick && n > 1000) break;
      add(n, [&](Point& p) {
        p.workload.aircraft = static_cast<std::size_t>(n);
        // Per-update costs need a few periods, not 300 s, once N is large: about
        // 600,000 updates or 300 s, whichever is shorter, and at least 8 periods.
        const double period = p.workload.period_s;
        p.workload.duration_s = std::max(8 * period, std::min(300.0, 6e5 * period / n));
      });
    }
  } else if (name == "period") {
    for (const double s : {1.0, 4.0, 5.0, 12.0}) add(s, [&](Point& p) { p.workload.period_s = s; });
  } else if (name == "noise") {
    for (const double m : {0.0, 10.0, 30.0, 50.0, 100.0}) add(m, [&](Point& p) { p.workload.noise_sigma_m = m; });
  } else if (name == "tolerance") {
    for (const double m : {10.0, 25.0, 50.0, 100.0, 150.0, 200.0, 300.0}) add(m, [&](Point& p) { p.tolerance_m = m; });
  } else if (name == "horizon") {
    for (const double k : {1.0, 2.0, 5.0, 15.0, 75.0, kew::kinetic::kNever}) add(k, [&](Point& p) { p.horizon_periods = k; });
  }
  return points;
}

// ---------------------------------------------------------------------------------
// Output

void put_run(JsonText& j, const RunResult& r) {
  const kew::kinetic::KineticStatistics& s = r.stats;
  j.key(r.configuration.name).begin_object();
  j.key("horizon_s").value(r.configuration.kinetic.horizon_s);
  j.key("tolerance_m").value(r.configuration.kinetic.tolerance);
  j.key("keep_model_s").value(r.configuration.kinetic.keep_model_s);
  j.key("reduce_redundant_events").value(r.configuration.kinetic.reduce_redundant_events);
  j.key("reinsertion").value(r.configuration.reinsertion == Reinsertion::Engine ? "engine" : "remove_insert");
  j.key("valid_at_end").value(r.valid);
  j.key("setup_s").value(r.setup_s);
  j.key("loop_s").value(r.loop_s);
  j.key("update_us_per_call").value(r.update_us());
  j.key("advance_us_per_call").value(r.advance_us());
  j.key("loop_us_per_measurement").value(r.loop_us());
  j.key("velocity_only_us").value(r.velocity_only.us_per_call());
  j.key("reinsertion_us").value(r.reinserted.us_per_call());
  j.key("kept_us").value(r.kept.us_per_call());
  j.key("updates").value(std::uint64_t{r.updates});
  j.key("velocity_updates").value(r.velocity_only.calls);
  j.key("reinsertions").value(r.reinserted.calls);
  j.key("kept_updates").value(r.kept.calls);
  j.key("drift_reinsertions").value(s.drift_reinsertions);
  j.key("certificates_solved").value(s.certificates_solved);
  j.key("certificates_kept").value(s.certificates_kept);
  j.key("events_computed").value(s.events_computed);
  j.key("events_executed").value(s.events_executed);
  j.key("events_discarded").value(s.events_discarded);
  j.key("discarded_share").value(r.discarded_share());
  j.key("renewals").value(s.renewals);
  j.key("queue_mean").value(s.queue_mean());
  j.key("queue_max").value(std::uint64_t{s.queue_max});
  j.key("loop_failures_queued_mean").value(r.failures_queued_mean);
  j.key("loop_renewals_queued_mean").value(r.renewals_queued_mean);
  if (!r.queue_trace.empty()) {
    j.key("queue_trace").begin_object();
    for (const char* column : {"t_s", "failures", "renewals"}) {
      j.key(column).begin_array();
      for (const QueueSample& q : r.queue_trace)
        j.value(column[0] == 't' ? q.t : static_cast<double>(column[0] == 'f' ? q.failures : q.renewals));
      j.end_array();
    }
    j.end_object();
  }
  j.end_object();
}

void put_point(JsonText& j, const PointResult& p) {
  j.begin_object();
  if (!p.sweep.empty()) j.key("value").value(p.value);
  j.key("parameters").begin_object();
  const WorkloadParameters& w = p.point.workload;
  j.key("aircraft").value(std::uint64_t{w.aircraft});
  j.key("side_m").value(w.side_m());
  j.key("period_s").value(w.period_s);
  j.key("duration_s").value(w.duration_s);
  j.key("noise_sigma_m").value(w.noise_sigma_m);
  j.key("tolerance_m").value(p.point.tolerance_m);
  j.key("horizon_s").value(p.point.horizon_s());
  j.key("max_turn_deg_s").value(w.max_turn_deg_s);
  j.key("speed_m_s").begin_array().value(w.speed_min_m_s).value(w.speed_max_m_s).end_array();
  j.key("seed").value(std::uint64_t{w.seed});
  j.end_object();
  j.key("ratios").begin_object();
  for (const auto& [name, value] : p.ratios) j.key(name).value(value);
  j.end_object();
  j.key("configurations").begin_object();
  for (const RunResult& r : p.runs) put_run(j, r);
  j.end_object();
  j.end_object();
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

std::string fixed(double x, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, x);
  return text;
}

void print_point(const PointResult& p) {
  char shown[32];
  std::snprintf(shown, sizeof shown, "%g", p.value);
  std::cout << "\n## " << (p.sweep.empty() ? "setting" : p.sweep + " = " + shown) << "\n\n"
            << "| configuration | update µs | velocity-only µs | reinsertion µs | kept µs | loop µs | queue mean | "
               "discarded share | valid |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const RunResult& r : p.runs)
    std::cout << "| " << r.configuration.name << " | " << fixed(r.update_us(), 2) << " | "
              << fixed(r.velocity_only.us_per_call(), 2) << " | " << fixed(r.reinserted.us_per_call(), 2) << " | "
              << fixed(r.kept.us_per_call(), 2) << " | " << fixed(r.loop_us(), 2) << " | "
              << fixed(r.stats.queue_mean(), 1) << " | " << fixed(r.discarded_share(), 3) << " | "
              << (r.valid ? "yes" : "NO") << " |\n";
  std::cout << "\n";
  for (const auto& [name, value] : p.ratios) std::cout << name << " = " << fixed(value, 3) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  if (!o.only.empty()) {
    for (const Configuration& c : configurations_of(o.setting, false, false))
      if (c.name == o.only) {
        const RunResult r = run_once(c, make_workload(o.setting.workload));
        std::cout << c.name << ": " << r.updates << " updates, " << r.update_us() << " µs per update, "
                  << r.advance_us() << " µs per advance, valid " << r.valid << "\n";
        return r.valid ? 0 : 1;
      }
    usage("unknown configuration " + o.only);
  }
  std::cout << "machine: " << kew::bench::cpu_model_name() << ", " << kew::bench::hardware_threads()
            << " threads, build " << KEW_BUILD_TYPE << "\n";
  std::vector<PointResult> points;
  std::cerr << "kew_thesis_bench:\n";
  points.push_back(measure("", 0, o.setting, o, true));
  for (const std::string& sweep : o.sweeps)
    for (const auto& [value, point] : sweep_points(sweep, o.setting, o.quick)) points.push_back(measure(sweep, value, point, o, false));

  bool all_valid = true;
  for (const PointResult& p : points) {
    print_point(p);
    for (const RunResult& r : p.runs) all_valid = all_valid && r.valid;
  }
  if (!o.json_path.empty()) {
    JsonText j;
    j.begin_object();
    j.key("command").value(o.command);
    j.key("date").value(utc_now());
    kew::bench::put_machine(j, KEW_BUILD_TYPE);
    j.key("repeats").value(std::uint64_t(o.counts_only ? 1 : o.repeats));
    j.key("setting");
    put_point(j, points.front());
    j.key("sweeps").begin_object();
    for (const std::string& sweep : o.sweeps) {
      j.key(sweep).begin_array();
      for (const PointResult& p : points)
        if (p.sweep == sweep) put_point(j, p);
      j.end_array();
    }
    j.end_object();
    j.end_object();
    if (!j.save(o.json_path)) {
      std::cerr << "kew_thesis_bench: cannot write " << o.json_path << "\n";
      return 1;
    }
  }
  if (!all_valid) std::cerr << "kew_thesis_bench: a configuration ended with an invalid triangulation\n";
  return all_valid ? 0 : 1;
}
