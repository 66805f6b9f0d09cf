// kew_apw_bench: what the area proximity warning (design §4.11) costs the pipeline. One
// fleet of random traffic at 1 Hz (kew-gen's random scenario: uniform positions and
// tracks, FL100–FL400, 250–500 kt, over a disk of 2,000 km about 50° N 10° E, i.e.
// Europe) through Pipeline::process() on one thread, with 0, 1,000 and 10,000 watched
// volumes side by side in one run. The volumes are random too, with a fixed seed, over
// the same disk: half circles, half star-shaped polygons of 4–12 vertices, 1–20 NM
// across, bands with a floor of 0–38,000 ft and 1,000–20,000 ft deep, of every kind,
// always active, the default look-ahead (120 s) and warning time (60 s). The smaller
// sets are the first volumes of the largest.
//
// For each volume count (runs repeated round robin, so that a machine's drift falls on
// every count alike):
//  - records/s: the measured records over this thread's CPU time (the machine may be
//    shared), and over wall time;
//  - per-record latency: the wall time of each process() (batch_records = 1: a record's
//    events come out of its own process()), p50/p99/p99.9/max;
//  - per data second: the wall time the pipeline spent on the records of one second of
//    data (25,000 at the default fleet), p50/p99/max: real time needs less than 1 s;
//  - alerts opened, by kind, and APW events;
//  - the volume index's candidates per record (the volumes whose box meets the box of
//    the record's path over the look-ahead: each costs an entry test), how many of them
//    the aircraft's altitude is within the band of (only those reach the horizontal
//    geometry), circles and polygons apart, how many the path enters, and the mean
//    wall time of volume::entry() on those, by shape, on every 50th measured record.
// The first --warmup seconds fill the picture (tracks created) and are not measured.
//
// Usage: kew_apw_bench [--aircraft N] [--seconds S] [--warmup S] [--volumes N,N...]
//                      [--repeat R] [--radius-km R] [--volume-radius-km R] [--json FILE]
// Defaults: 25,000 aircraft, 30 s measured after 5 s, volumes 0,1000,10000, 3 repeats.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "bench_report.hpp"
#include "kew/config/aerodromes.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/replay/traffic_generator.hpp"
#include "kew/volume/entry.hpp"
#include "kew/volume/volume_index.hpp"
#include "kew/volume/watched_volume.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using kew::bench::percentile;

constexpr double kCentreLat_deg = 50.0, kCentreLon_deg = 10.0;
constexpr std::uint64_t kTrafficSeed = 20261211, kVolumeSeed = 4711;
constexpr double kMetresPerNm = 1852.0;
constexpr double kEarthRadius_m = 6371008.8;

struct Params {
  std::size_t aircraft = 25000;
  double seconds = 30.0;
  double warmup_s = 5.0;
  std::vector<std::size_t> volumes{0, 1000, 10000};
  int repeat = 3;
  /// The traffic over a disk of this radius about 50° N 10° E (km, 100–2,000: kew-gen's
  /// limit): 2,000 is Europe.
  double radius_km = 2000.0;
  /// The volumes over a disk of this radius about the same centre (km, 100–20,000; 0:
  /// radius_km): 10,000 spreads them over half the earth, as a world's 10,000 volumes
  /// would be around the traffic of one region.
  double volume_radius_km = 0.0;
  std::string json_path;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "kew_apw_bench: " << why
            << "\nusage: kew_apw_bench [--aircraft N] [--seconds S] [--warmup S] [--volumes N,N...] [--repeat R] "
               "[--radius-km R] [--volume-radius-km R] [--json FILE]\n";
  std::exit(64);
}

Params parse(int argc, char** argv) {
  Params p;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--aircraft" && i + 1 < argc) {
      const long n = std::atol(argv[++i]);
      if (n < 1 || n > 1'000'000) usage("--aircraft takes 1 to 1000000");
      p.aircraft = static_cast<std::size_t>(n);
    } else if (flag == "--seconds" && i + 1 < argc) {
      p.seconds = std::atof(argv[++i]);
      if (!(p.seconds >= 1.0 && p.seconds <= 3600.0)) usage("--seconds must be in [1, 3600]");
    } else if (flag == "--warmup" && i + 1 < argc) {
      p.warmup_s = std::atof(argv[++i]);
      if (!(p.warmup_s >= 0.0 && p.warmup_s <= 600.0)) usage("--warmup must be in [0, 600]");
    } else if (flag == "--volumes" && i + 1 < argc) {
      p.volumes.clear();
      const std::string list = argv[++i];
      for (std::size_t at = 0; at <= list.size();) {
        const std::size_t comma = std::min(list.find(',', at), list.size());
        const long n = std::atol(list.substr(at, comma - at).c_str());
        if (n < 0 || n > 1'000'000) usage("--volumes takes counts from 0 to 1000000");
        p.volumes.push_back(static_cast<std::size_t>(n));
        at = comma + 1;
      }
    } else if (flag == "--repeat" && i + 1 < argc) {
      p.repeat = std::atoi(argv[++i]);
      if (p.repeat < 1 || p.repeat > 100) usage("--repeat takes 1 to 100");
    } else if (flag == "--radius-km" && i + 1 < argc) {
      p.radius_km = std::atof(argv[++i]);
      if (!(p.radius_km >= 100.0 && p.radius_km <= 2000.0)) usage("--radius-km must be in [100, 2000]");
    } else if (flag == "--volume-radius-km" && i + 1 < argc) {
      p.volume_radius_km = std::atof(argv[++i]);
      if (!(p.volume_radius_km >= 100.0 && p.volume_radius_km <= 20000.0))
        usage("--volume-radius-km must be in [100, 20000]");
    } else if (flag == "--json" && i + 1 < argc) {
      p.json_path = argv[++i];
    } else {
      usage("unknown or incomplete flag " + flag);
    }
  }
  return p;
}

std::vector<kew::TrackReport> traffic(const Params& p) {
  kew::replay::GeneratorConfig g;
  g.scenario = kew::replay::Scenario::Random;
  g.aircraft = p.aircraft;
  g.duration_s = p.warmup_s + p.seconds;
  g.period_s = 1.0;
  g.seed = kTrafficSeed;
  g.center_lat_deg = kCentreLat_deg;
  g.center_lon_deg = kCentreLon_deg;
  g.radius_km = p.radius_km;
  kew::replay::TrafficGenerator generator(g);
  std::vector<kew::TrackReport> records;
  records.reserve(static_cast<std::size_t>(static_cast<double>(p.aircraft) * g.duration_s * 1.01));
  for (kew::TrackReport r; generator.next(r);) records.push_back(std::move(r));
  return records;
}

// The point `distance_m` from `from` at `bearing_deg` on a sphere: volumes need no more.
kew::volume::LatLon destination(kew::volume::LatLon from, double bearing_deg, double distance_m) {
  constexpr double kRad = std::numbers::pi / 180.0;
  const double d = distance_m / kEarthRadius_m, b = bearing_deg * kRad;
  const double lat1 = from.lat_deg * kRad, lon1 = from.lon_deg * kRad;
  const double lat2 = std::asin(std::sin(lat1) * std::cos(d) + std::cos(lat1) * std::sin(d) * std::cos(b));
  const double lon2 = lon1 + std::atan2(std::sin(b) * std::sin(d) * std::cos(lat1), std::cos(d) - std::sin(lat1) * std::sin(lat2));
  return {lat2 / kRad, std::remainder(lon2 / kRad, 360.0)};
}

std::vector<kew::volume::WatchedVolume> random_volumes(std::size_t count, double radius_km) {
  std::mt19937_64 rng(kVolumeSeed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  std::vector<kew::volume::WatchedVolume> out;
  out.reserve(count);
  while (out.size() < count) {
    const kew::volume::LatLon centre =
        destination({kCentreLat_deg, kCentreLon_deg}, uniform(0.0, 360.0), 1e3 * radius_km * std::sqrt(unit(rng)));
    const double radius_m = 0.5 * uniform(1.0, 20.0) * kMetresPerNm;  // 1–20 NM across
    kew::volume::VerticalBand band;
    band.floor_ft = std::round(uniform(0.0, 38000.0) / 100.0) * 100.0;
    band.ceiling_ft = band.floor_ft + std::round(uniform(1000.0, 20000.0) / 100.0) * 100.0;
    kew::volume::VolumeResult made;
    if (out.size() % 2 == 0) {
      made = kew::volume::Volume::circle(centre, radius_m, band);
    } else {
      // Star-shaped about the centre: n vertices at increasing bearings, each within
      // ±40 % of its share of the turn, at 50–100 % of the radius.
      const int n = 4 + static_cast<int>(unit(rng) * 9.0);  // 4–12
      kew::volume::Ring ring;
      for (int k = 0; k < n; ++k) {
        const double bearing = (k + uniform(-0.4, 0.4)) * 360.0 / n;
        ring.push_back(destination(centre, bearing, radius_m * uniform(0.5, 1.0)));
      }
      made = kew::volume::Volume::polygon(ring, {}, band);
    }
    if (!made.volume) continue;  // never seen; a refused shape is drawn again
    kew::volume::WatchedVolume v;
    char name[16];
    std::snprintf(name, sizeof name, "V%05zu", out.size());
    v.name = name;
    v.kind = static_cast<kew::volume::VolumeKind>(out.size() / 2 % 4);
    v.area = std::move(made.volume);
    out.push_back(std::move(v));
  }
  return out;
}

struct Latency {
  double p50_us = NAN, p99_us = NAN, p999_us = NAN, max_us = NAN;
};

Latency summarise(std::vector<double>& seconds) {
  Latency l;
  if (seconds.empty()) return l;
  l.p50_us = 1e6 * percentile(seconds, 0.50);
  l.p99_us = 1e6 * percentile(seconds, 0.99);
  l.p999_us = 1e6 * percentile(seconds, 0.999);
  l.max_us = 1e6 * *std::max_element(seconds.begin(), seconds.end());
  return l;
}

struct Run {
  std::size_t volumes = 0;
  int repeat = 0;
  std::uint64_t records = 0;  // measured
  double cpu_s = 0, wall_s = 0;
  Latency record;      // one process()
  Latency per_second;  // the records of one second of data
  std::uint64_t stca_opened = 0, apw_opened = 0, apw_events = 0;
  std::size_t live_tracks = 0;
  double records_per_cpu_s() const { return static_cast<double>(records) / cpu_s; }
  double records_per_wall_s() const { return static_cast<double>(records) / wall_s; }
};

kew::PipelineConfig configured(const std::vector<kew::volume::WatchedVolume>& all, std::size_t n) {
  kew::PipelineConfig c;  // one thread, batch_records 1: each record judged in its process()
  c.eligibility.aerodromes = kew::config::load_default_aerodromes();  // as every tool reads them
  c.volumes.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n));
  return c;
}

Run run(const std::vector<kew::TrackReport>& records, const kew::PipelineConfig& config, double measure_from) {
  Run r;
  r.volumes = config.volumes.size();
  kew::Pipeline pipeline(config);
  pipeline.set_alert_sink([&](const kew::AlertEvent& e) {
    const bool apw = e.kind == kew::AlertKind::Apw;
    r.apw_events += apw;
    if (e.state == kew::AlertState::New) ++(apw ? r.apw_opened : r.stca_opened);
  });
  std::size_t i = 0;
  for (; i < records.size() && records[i].t < measure_from; ++i) pipeline.process(records[i]);
  std::vector<double> record_s, second_s;
  record_s.reserve(records.size() - i);
  double second_start = measure_from, second_sum = 0.0;
  const kew::bench::Stopwatch cpu;
  const auto wall0 = Clock::now();
  for (; i < records.size(); ++i) {
    const kew::TrackReport& rec = records[i];
    if (rec.t >= second_start + 1.0) {
      second_s.push_back(second_sum);
      second_sum = 0.0;
      second_start += std::floor(rec.t - second_start);
    }
    const auto t0 = Clock::now();
    pipeline.process(rec);
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    record_s.push_back(s);
    second_sum += s;
  }
  pipeline.flush();
  r.cpu_s = cpu.seconds();
  r.wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
  second_s.push_back(second_sum);
  r.records = record_s.size();
  r.record = summarise(record_s);
  r.per_second = summarise(second_s);
  r.live_tracks = pipeline.live_tracks();
  return r;
}

// The index's candidates per record, and those within the band at the record's altitude
// (on every 50th measured record), for the first n volumes.
struct Reach {
  double candidates_per_record = 0, in_band_per_record = 0;
  double circles_in_band_per_record = 0, polygons_in_band_per_record = 0;
  double entering_per_record = 0;  // entry() finds an entry within the look-ahead
  // entry() alone on the candidates within the band, wall µs per call (mean).
  double circle_entry_us = NAN, polygon_entry_us = NAN;
};

Reach reach(const std::vector<kew::TrackReport>& records, const std::vector<kew::volume::WatchedVolume>& all,
            std::size_t n, double measure_from) {
  Reach out;
  if (n == 0) return out;
  std::vector<kew::volume::Volume> areas;
  for (std::size_t v = 0; v < n; ++v) areas.push_back(*all[v].area);
  const kew::volume::VolumeIndex index(areas);
  std::uint64_t sampled = 0, candidates = 0, in_band = 0, circles = 0, polygons = 0, entering = 0;
  double circle_s = 0, polygon_s = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const kew::TrackReport& r = records[i];
    if (r.t < measure_from || i % 50 != 0) continue;
    kew::volume::Motion m;
    m.start = {r.lat_deg, r.lon_deg};
    m.alt_ft = r.alt_ft;
    m.track_deg = r.trk_deg.value_or(0.0);
    m.gs_kt = std::min(r.gs_kt.value_or(0.0), kew::volume::kMaxGroundSpeed_kt);
    m.vr_fpm = r.vr_fpm.value_or(0.0);
    ++sampled;
    for (const std::uint32_t v : index.candidates(m, all[0].lookahead_s)) {
      ++candidates;
      if (!kew::volume::vertical_interval(m, areas[v].band(), all[v].lookahead_s)) continue;
      ++in_band;
      const auto t0 = Clock::now();
      const kew::volume::Entry e = kew::volume::entry(areas[v], m, all[v].lookahead_s);
      const double spent = std::chrono::duration<double>(Clock::now() - t0).count();
      entering += e.entry_s.has_value();
      (areas[v].is_circle() ? circle_s : polygon_s) += spent;
      ++(areas[v].is_circle() ? circles : polygons);
    }
  }
  const auto per_record = [&](std::uint64_t count) {
    return static_cast<double>(count) / static_cast<double>(std::max<std::uint64_t>(1, sampled));
  };
  out.candidates_per_record = per_record(candidates);
  out.in_band_per_record = per_record(in_band);
  out.circles_in_band_per_record = per_record(circles);
  out.polygons_in_band_per_record = per_record(polygons);
  out.entering_per_record = per_record(entering);
  if (circles) out.circle_entry_us = 1e6 * circle_s / static_cast<double>(circles);
  if (polygons) out.polygon_entry_us = 1e6 * polygon_s / static_cast<double>(polygons);
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  const Params prm = parse(argc, argv);
  std::cout << "machine: " << kew::bench::cpu_model_name() << ", " << kew::bench::hardware_threads()
            << " hardware threads, build " << KEW_BUILD_TYPE << "\n";
  std::cerr << "generating " << prm.aircraft << " aircraft × " << prm.warmup_s + prm.seconds << " s...\n";
  const std::vector<kew::TrackReport> records = traffic(prm);
  const double measure_from = records.front().t + prm.warmup_s;
  const std::size_t most = *std::max_element(prm.volumes.begin(), prm.volumes.end());
  std::cerr << "generating " << most << " volumes...\n";
  const std::vector<kew::volume::WatchedVolume> volumes = random_volumes(most, prm.volume_radius_km > 0.0 ? prm.volume_radius_km : prm.radius_km);

  std::vector<kew::PipelineConfig> configs;
  std::vector<Reach> reaches;
  for (const std::size_t n : prm.volumes) {
    configs.push_back(configured(volumes, n));
    reaches.push_back(reach(records, volumes, n, measure_from));
  }
  std::vector<Run> runs;
  for (int rep = 0; rep < prm.repeat; ++rep)
    for (const kew::PipelineConfig& c : configs) {
      std::cerr << "repeat " << rep + 1 << "/" << prm.repeat << ", " << c.volumes.size() << " volumes...\n";
      runs.push_back(run(records, c, measure_from));
      runs.back().repeat = rep;
    }

  // Per volume count: the medians over the repeats.
  struct Summary {
    std::size_t volumes = 0;
    double records_per_cpu_s = NAN, records_per_wall_s = NAN, ratio = NAN;
    double p50_us = NAN, p99_us = NAN, p999_us = NAN, max_us = NAN, second_p99_ms = NAN, second_max_ms = NAN;
    std::uint64_t apw_opened = 0, stca_opened = 0, apw_events = 0;
  };
  std::vector<Summary> summary;
  for (const std::size_t n : prm.volumes) {
    Summary s;
    s.volumes = n;
    std::vector<double> cpu, wall, p50, p99, p999, mx, sp99, smax;
    for (const Run& r : runs) {
      if (r.volumes != n) continue;
      cpu.push_back(r.records_per_cpu_s());
      wall.push_back(r.records_per_wall_s());
      p50.push_back(r.record.p50_us);
      p99.push_back(r.record.p99_us);
      p999.push_back(r.record.p999_us);
      mx.push_back(r.record.max_us);
      sp99.push_back(1e-3 * r.per_second.p99_us);
      smax.push_back(1e-3 * r.per_second.max_us);
      s.apw_opened = r.apw_opened;
      s.stca_opened = r.stca_opened;
      s.apw_events = r.apw_events;
    }
    s.records_per_cpu_s = median(cpu);
    s.records_per_wall_s = median(wall);
    s.p50_us = median(p50);
    s.p99_us = median(p99);
    s.p999_us = median(p999);
    s.max_us = median(mx);
    s.second_p99_ms = median(sp99);
    s.second_max_ms = median(smax);
    summary.push_back(s);
  }
  const auto none = std::find_if(summary.begin(), summary.end(), [](const Summary& s) { return s.volumes == 0; });
  for (Summary& s : summary)
    if (none != summary.end()) s.ratio = s.records_per_cpu_s / none->records_per_cpu_s;

  std::printf("\n%zu aircraft at 1 Hz, %.0f s measured after %.0f s, %d repeat(s), medians:\n\n", prm.aircraft,
              prm.seconds, prm.warmup_s, prm.repeat);
  std::printf("| volumes | records/s (CPU) | × none | records/s (wall) | per record p50 / p99 / p99.9 / max (µs) | "
              "per data second p99 / max (ms) | candidates / record | in band | APW opened | APW events | STCA opened |\n"
              "|---:|---:|---:|---:|---|---|---:|---:|---:|---:|---:|\n");
  for (std::size_t k = 0; k < summary.size(); ++k) {
    const Summary& s = summary[k];
    std::printf("| %zu | %.0f | %.3f | %.0f | %.1f / %.1f / %.1f / %.0f | %.1f / %.1f | %.2f | %.2f | %llu | %llu | %llu |\n",
                s.volumes, s.records_per_cpu_s, s.ratio, s.records_per_wall_s, s.p50_us, s.p99_us, s.p999_us, s.max_us,
                s.second_p99_ms, s.second_max_ms, reaches[k].candidates_per_record, reaches[k].in_band_per_record,
                static_cast<unsigned long long>(s.apw_opened), static_cast<unsigned long long>(s.apw_events),
                static_cast<unsigned long long>(s.stca_opened));
  }

  std::printf("\n| volumes | in band: circles / polygons per record | entering per record | entry() µs: circle / polygon |\n"
              "|---:|---|---:|---|\n");
  for (std::size_t k = 0; k < summary.size(); ++k)
    std::printf("| %zu | %.2f / %.2f | %.3f | %.1f / %.1f |\n", summary[k].volumes, reaches[k].circles_in_band_per_record,
                reaches[k].polygons_in_band_per_record, reaches[k].entering_per_record, reaches[k].circle_entry_us,
                reaches[k].polygon_entry_us);

  if (!prm.json_path.empty()) {
    kew::bench::JsonText j;
    j.begin_object();
    kew::bench::put_machine(j, KEW_BUILD_TYPE);
    j.key("workload").begin_object();
    j.key("scenario").value("random");
    j.key("aircraft").value(std::uint64_t{prm.aircraft});
    j.key("radius_km").value(prm.radius_km);
    j.key("volume_radius_km").value(prm.volume_radius_km > 0.0 ? prm.volume_radius_km : prm.radius_km);
    j.key("period_s").value(1.0);
    j.key("centre_lat_deg").value(kCentreLat_deg);
    j.key("centre_lon_deg").value(kCentreLon_deg);
    j.key("warmup_s").value(prm.warmup_s);
    j.key("seconds").value(prm.seconds);
    j.key("repeat").value(std::uint64_t(prm.repeat));
    j.key("threads").value(std::uint64_t{1});
    j.key("batch_records").value(std::uint64_t{1});
    j.end_object();
    j.key("summary").begin_array();
    for (std::size_t k = 0; k < summary.size(); ++k) {
      const Summary& s = summary[k];
      j.begin_object();
      j.key("volumes").value(std::uint64_t{s.volumes});
      j.key("records_per_cpu_s").value(s.records_per_cpu_s);
      j.key("throughput_vs_no_volumes").value(s.ratio);
      j.key("records_per_wall_s").value(s.records_per_wall_s);
      j.key("record_p50_us").value(s.p50_us);
      j.key("record_p99_us").value(s.p99_us);
      j.key("record_p999_us").value(s.p999_us);
      j.key("record_max_us").value(s.max_us);
      j.key("data_second_p99_ms").value(s.second_p99_ms);
      j.key("data_second_max_ms").value(s.second_max_ms);
      j.key("index_candidates_per_record").value(reaches[k].candidates_per_record);
      j.key("candidates_in_band_per_record").value(reaches[k].in_band_per_record);
      j.key("circles_in_band_per_record").value(reaches[k].circles_in_band_per_record);
      j.key("polygons_in_band_per_record").value(reaches[k].polygons_in_band_per_record);
      j.key("entering_per_record").value(reaches[k].entering_per_record);
      j.key("circle_entry_us").value(reaches[k].circle_entry_us);
      j.key("polygon_entry_us").value(reaches[k].polygon_entry_us);
      j.key("apw_opened").value(s.apw_opened);
      j.key("apw_events").value(s.apw_events);
      j.key("stca_opened").value(s.stca_opened);
      j.end_object();
    }
    j.end_array();
    j.key("runs").begin_array();
    for (const Run& r : runs) {
      j.begin_object();
      j.key("volumes").value(std::uint64_t{r.volumes});
      j.key("repeat").value(std::uint64_t(r.repeat));
      j.key("records").value(r.records);
      j.key("cpu_s").value(r.cpu_s);
      j.key("wall_s").value(r.wall_s);
      j.key("records_per_cpu_s").value(r.records_per_cpu_s());
      j.key("records_per_wall_s").value(r.records_per_wall_s());
      j.key("record_p50_us").value(r.record.p50_us);
      j.key("record_p99_us").value(r.record.p99_us);
      j.key("record_p999_us").value(r.record.p999_us);
      j.key("record_max_us").value(r.record.max_us);
      j.key("data_second_p50_ms").value(1e-3 * r.per_second.p50_us);
      j.key("data_second_p99_ms").value(1e-3 * r.per_second.p99_us);
      j.key("data_second_max_ms").value(1e-3 * r.per_second.max_us);
      j.key("live_tracks").value(std::uint64_t{r.live_tracks});
      j.key("apw_opened").value(r.apw_opened);
      j.key("apw_events").value(r.apw_events);
      j.key("stca_opened").value(r.stca_opened);
      j.end_object();
    }
    j.end_array();
    j.end_object();
    if (!j.save(prm.json_path)) {
      std::cerr << "kew_apw_bench: cannot write " << prm.json_path << "\n";
      return 1;
    }
  }
  return 0;
}
