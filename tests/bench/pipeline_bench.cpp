// kew_pipeline_bench: end-to-end throughput of kew on one core (design §6.7):
// bytes → decoder → Pipeline → ALERT JSON lines, for canonical NDJSON (generated traffic)
// and ASTERIX CAT062 (the bundled JADE final-format excerpt, and the 30-minute JADE
// recording of ../shared/data/recordings when present); the in-process record-to-alert
// latency (from the decoder handing the record over to the alert sink receiving the
// event); and the memory each live track costs.
//
// Throughput is records per CPU second of this thread (the machine may be shared).
// Latency is wall time (steady clock), so it includes what a loaded machine adds.
// Memory is counted by this program's operator new (bytes in use, as malloc sizes them)
// before and after loading a fleet, divided by the live tracks; RSS is printed too.
//
// Usage: kew_pipeline_bench [--quick] [--memory-only] [--json FILE] [--seconds S]
//                           [--fleets N,N...] [--scenario NAME]
// --fleets and --scenario choose the generated NDJSON runs (default 2,000 and 10,000
// aircraft, mixed); the same flags on an older tree give a before/after pair.

#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <new>
#include <span>
#include <string>
#include <vector>

#include "bench_report.hpp"
#include "kew/config/aerodromes.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/protocol/formats.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/replay/traffic_generator.hpp"

// ---------------------------------------------------------------------------------
// Heap accounting: every allocation of the process goes through these.

namespace {
std::atomic<std::int64_t> g_heap_bytes{0};

void* counted_allocate(std::size_t size) {
  void* p = std::malloc(size == 0 ? 1 : size);
  if (!p) throw std::bad_alloc();
  g_heap_bytes.fetch_add(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
  return p;
}
void counted_free(void* p) noexcept {
  if (!p) return;
  g_heap_bytes.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
  std::free(p);
}
}  // namespace

void* operator new(std::size_t size) { return counted_allocate(size); }
void* operator new[](std::size_t size) { return counted_allocate(size); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }

namespace {

using kew::bench::JsonText;
using kew::bench::Stopwatch;

struct Params {
  bool quick = false;
  bool memory_only = false;  // skip the throughput runs
  double ndjson_seconds = 300.0;  // duration of the generated NDJSON traffic
  std::vector<std::size_t> fleets;  // empty: 2,000 and 10,000 (2,000 with --quick)
  kew::replay::Scenario scenario = kew::replay::Scenario::Mixed;
  std::string json_path;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "kew_pipeline_bench: " << why << "\nusage: kew_pipeline_bench [--quick] [--memory-only] [--seconds S] [--fleets N,N...] [--scenario NAME] [--json FILE]\n";
  std::exit(2);
}

Params parse(int argc, char** argv) {
  Params p;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--quick") {
      p.quick = true;
      p.ndjson_seconds = 60.0;
    } else if (flag == "--memory-only") {
      p.memory_only = true;
    } else if (flag == "--json" && i + 1 < argc) {
      p.json_path = argv[++i];
    } else if (flag == "--fleets" && i + 1 < argc) {
      std::string list = argv[++i];
      for (std::size_t start = 0; start <= list.size();) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        const long n = std::atol(list.substr(start, comma - start).c_str());
        if (n < 1 || n > 1'000'000) usage("--fleets takes aircraft counts from 1 to 1000000");
        p.fleets.push_back(static_cast<std::size_t>(n));
        start = comma + 1;
      }
    } else if (flag == "--scenario" && i + 1 < argc) {
      const auto scenario = kew::replay::kScenarioNames.parse(argv[++i]);
      if (!scenario) usage(std::string("--scenario takes one of ") + std::string(kew::replay::kScenarioNames.list()));
      p.scenario = *scenario;
    } else if (flag == "--seconds" && i + 1 < argc) {
      p.ndjson_seconds = std::atof(argv[++i]);
      if (!(p.ndjson_seconds >= 4.0 && p.ndjson_seconds <= 3600.0)) usage("--seconds must be in [4, 3600]");
    } else {
      usage("unknown or incomplete flag " + flag);
    }
  }
  return p;
}

// kew-replay's usual density: 2,000 aircraft in a 400 km radius; other fleets get a
// region scaled by √N (one aircraft per 251 km²).
// The pipeline's defaults with kew's aerodromes, as every tool reads them.
kew::PipelineConfig with_aerodromes() {
  kew::PipelineConfig config;
  config.eligibility.aerodromes = kew::config::load_default_aerodromes();
  return config;
}

kew::replay::GeneratorConfig generated(std::size_t aircraft, double seconds,
                                       kew::replay::Scenario scenario = kew::replay::Scenario::Mixed) {
  kew::replay::GeneratorConfig g;
  g.scenario = scenario;
  g.aircraft = aircraft;
  g.duration_s = seconds;
  g.seed = 1;
  g.radius_km = std::min(2000.0, 400.0 * std::sqrt(static_cast<double>(aircraft) / 2000.0));
  g.aerodromes = kew::config::load_default_aerodromes();
  return g;
}

std::string generated_ndjson(std::size_t aircraft, double seconds, kew::replay::Scenario scenario) {
  kew::replay::TrafficGenerator generator(generated(aircraft, seconds, scenario));
  std::string text;
  for (kew::TrackReport r; generator.next(r);) {
    kew::protocol::append_ndjson(text, r);
    text += '\n';
  }
  return text;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

using kew::bench::percentile;

struct Latency {
  double p50_us = 0, p99_us = 0, max_us = 0;
  std::size_t samples = 0;
};

Latency summarise(std::vector<double>& seconds) {
  Latency l;
  l.samples = seconds.size();
  l.p50_us = 1e6 * percentile(seconds, 0.50);
  l.p99_us = 1e6 * percentile(seconds, 0.99);
  l.max_us = seconds.empty() ? std::nan("") : 1e6 * *std::max_element(seconds.begin(), seconds.end());
  return l;
}

struct EndToEnd {
  std::string input;
  kew::protocol::Format format = kew::protocol::Format::Ndjson;
  std::size_t bytes = 0;
  std::uint64_t records = 0;
  std::uint64_t alert_events = 0;
  std::size_t tracks_max = 0;
  double decode_only_s = 0;  // CPU s of decoding alone
  double end_to_end_s = 0;   // CPU s of decode → pipeline → encode
  Latency alert_latency;      // record handed over → its alert events encoded (wall)
  Latency record_latency;     // record handed over → pipeline done with it (wall, every record)
  Latency alert_latency_cpu;  // the same in CPU time of this thread: without preemption
  Latency record_latency_cpu;
  std::size_t alerts_active_max = 0;
  double records_per_s() const { return static_cast<double>(records) / end_to_end_s; }
};

constexpr std::size_t kChunk = 64 * 1024;  // what kew-replay reads at a time

void feed_all(kew::protocol::Decoder& decoder, const std::string& bytes, const kew::protocol::ReportSink& sink) {
  const auto all = std::as_bytes(std::span<const char>(bytes.data(), bytes.size()));
  for (std::size_t at = 0; at < all.size(); at += kChunk) decoder.feed(all.subspan(at, std::min(kChunk, all.size() - at)), sink);
  decoder.finish(sink);
}

EndToEnd run_end_to_end(const std::string& name, kew::protocol::Format format, const std::string& bytes) {
  EndToEnd r;
  r.input = name;
  r.format = format;
  r.bytes = bytes.size();
  {  // decoding alone, to tell its share
    auto decoder = kew::protocol::make_decoder(format);
    std::uint64_t n = 0;
    const Stopwatch clock;
    feed_all(*decoder, bytes, [&](const kew::TrackReport&) { ++n; });
    r.decode_only_s = clock.seconds();
  }
  // Throughput pass: nothing but the work itself is timed.
  {
    auto decoder = kew::protocol::make_decoder(format);
    kew::Pipeline pipeline(with_aerodromes());
    std::string out;
    pipeline.set_alert_sink([&](const kew::AlertEvent& e) {
      kew::protocol::append_alert_json(out, e, e.seq);
      ++r.alert_events;
    });
    const Stopwatch clock;
    feed_all(*decoder, bytes, [&](const kew::TrackReport& report) {
      pipeline.process(report);
      if (out.size() > (1u << 20)) out.clear();  // a sink would write it out here
    });
    pipeline.drop_all();
    r.end_to_end_s = clock.seconds();
    r.records = pipeline.statistics().records;
    r.tracks_max = pipeline.tracks().max_size();
  }
  // Latency pass: the same run with clock reads around every record. Wall time is what
  // a client sees; CPU time leaves out the slices another process took on a busy machine.
  {
    auto decoder = kew::protocol::make_decoder(format);
    kew::Pipeline pipeline(with_aerodromes());
    std::string out;
    std::vector<double> alert_s, record_s, alert_cpu_s, record_cpu_s;
    record_s.reserve(r.records);
    record_cpu_s.reserve(r.records);
    std::chrono::steady_clock::time_point handed_over;
    Stopwatch cpu;
    pipeline.set_alert_sink([&](const kew::AlertEvent& e) {
      kew::protocol::append_alert_json(out, e, e.seq);
      alert_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - handed_over).count());
      alert_cpu_s.push_back(cpu.seconds());
    });
    feed_all(*decoder, bytes, [&](const kew::TrackReport& report) {
      handed_over = std::chrono::steady_clock::now();
      cpu.restart();
      pipeline.process(report);
      record_cpu_s.push_back(cpu.seconds());
      record_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - handed_over).count());
      r.alerts_active_max = std::max(r.alerts_active_max, pipeline.alerts().active_count());
      if (out.size() > (1u << 20)) out.clear();
    });
    r.alert_latency = summarise(alert_s);
    r.record_latency = summarise(record_s);
    r.alert_latency_cpu = summarise(alert_cpu_s);
    r.record_latency_cpu = summarise(record_cpu_s);
  }
  return r;
}

// ---------------------------------------------------------------------------------
// Memory per live track

struct MemoryPerTrack {
  std::string scenario;
  std::size_t aircraft = 0;
  std::size_t live_tracks = 0;
  std::size_t alerts_active = 0;  // alert state is part of what is counted
  double heap_bytes_per_track = 0;
  double rss_bytes_per_track = 0;
};

double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return pages_resident * 4096.0;
}

MemoryPerTrack measure_memory(std::size_t aircraft, kew::replay::Scenario scenario) {
  // Records first (they are input, not kew's state), then the pipeline from empty.
  std::vector<kew::TrackReport> records;
  {
    kew::replay::TrafficGenerator generator(generated(aircraft, 12.0, scenario));
    for (kew::TrackReport r; generator.next(r);) records.push_back(r);
  }
  malloc_trim(0);
  const std::int64_t heap_before = g_heap_bytes.load();
  const double rss_before = resident_bytes();
  MemoryPerTrack m;
  m.scenario = kew::replay::to_string(scenario);
  m.aircraft = aircraft;
  {
    kew::PipelineConfig config = with_aerodromes();
    // Centred on the region, whose radius (2,000 km at 100k aircraft) is beyond the
    // default coverage.
    const kew::replay::GeneratorConfig region = generated(aircraft, 12.0, scenario);
    config.zone_mode = kew::ZoneMode::Single;
    config.reference = kew::geo::GeodeticPosition{region.center_lat_deg, region.center_lon_deg};
    config.coverage_radius_m = 1.25e3 * region.radius_km + 50e3;
    kew::Pipeline pipeline(config);
    for (const kew::TrackReport& r : records) pipeline.process(r);
    m.live_tracks = pipeline.live_tracks();
    m.alerts_active = pipeline.alerts().active_count();
    const double tracks = static_cast<double>(m.live_tracks);
    m.heap_bytes_per_track = static_cast<double>(g_heap_bytes.load() - heap_before) / tracks;
    m.rss_bytes_per_track = (resident_bytes() - rss_before) / tracks;
  }
  return m;
}

// ---------------------------------------------------------------------------------

void print(const std::vector<EndToEnd>& runs, const std::vector<MemoryPerTrack>& memory) {
  if (!runs.empty())
    std::printf("\n| input | records | records/s end to end | decode share | alert events | alert latency p50 / p99 / max "
                "(µs, wall) | same, CPU | per-record p50 / p99 / max (µs, wall) | same, CPU |\n"
                "|---|---|---|---|---|---|---|---|---|\n");
  const auto triple = [](const Latency& l) {
    char text[64];
    std::snprintf(text, sizeof text, "%.1f / %.1f / %.1f", l.p50_us, l.p99_us, l.max_us);
    return std::string(text);
  };
  for (const EndToEnd& r : runs)
    std::printf("| %s | %llu | %.0f | %.1f %% | %llu | %s | %s | %s | %s |\n", r.input.c_str(),
                static_cast<unsigned long long>(r.records), r.records_per_s(), 100.0 * r.decode_only_s / r.end_to_end_s,
                static_cast<unsigned long long>(r.alert_events), triple(r.alert_latency).c_str(),
                triple(r.alert_latency_cpu).c_str(), triple(r.record_latency).c_str(), triple(r.record_latency_cpu).c_str());
  std::printf("\n| scenario | aircraft | live tracks | active alerts | heap bytes / track | RSS bytes / track |\n"
              "|---|---|---|---|---|---|\n");
  for (const MemoryPerTrack& m : memory)
    std::printf("| %s | %zu | %zu | %zu | %.0f | %.0f |\n", m.scenario.c_str(), m.aircraft, m.live_tracks, m.alerts_active,
                m.heap_bytes_per_track, m.rss_bytes_per_track);
}

void put_latency(JsonText& j, const char* key, const Latency& l) {
  j.key(key).begin_object();
  j.key("samples").value(std::uint64_t{l.samples});
  j.key("p50_us").value(l.p50_us);
  j.key("p99_us").value(l.p99_us);
  j.key("max_us").value(l.max_us);
  j.end_object();
}

void write_json(const std::string& path, const std::vector<EndToEnd>& runs, const std::vector<MemoryPerTrack>& memory) {
  JsonText j;
  j.begin_object();
  kew::bench::put_machine(j, KEW_BUILD_TYPE);
  j.key("end_to_end").begin_array();
  for (const EndToEnd& r : runs) {
    j.begin_object();
    j.key("input").value(r.input);
    j.key("format").value(kew::protocol::to_string(r.format));
    j.key("bytes").value(std::uint64_t{r.bytes});
    j.key("records").value(r.records);
    j.key("tracks_max").value(std::uint64_t{r.tracks_max});
    j.key("alert_events").value(r.alert_events);
    j.key("decode_only_cpu_s").value(r.decode_only_s);
    j.key("end_to_end_cpu_s").value(r.end_to_end_s);
    j.key("records_per_s").value(r.records_per_s());
    j.key("alerts_active_max").value(std::uint64_t{r.alerts_active_max});
    put_latency(j, "alert_latency_wall", r.alert_latency);
    put_latency(j, "record_latency_wall", r.record_latency);
    put_latency(j, "alert_latency_cpu", r.alert_latency_cpu);
    put_latency(j, "record_latency_cpu", r.record_latency_cpu);
    j.end_object();
  }
  j.end_array();
  j.key("memory").begin_array();
  for (const MemoryPerTrack& m : memory) {
    j.begin_object();
    j.key("scenario").value(m.scenario);
    j.key("aircraft").value(std::uint64_t{m.aircraft});
    j.key("live_tracks").value(std::uint64_t{m.live_tracks});
    j.key("alerts_active").value(std::uint64_t{m.alerts_active});
    j.key("heap_bytes_per_track").value(m.heap_bytes_per_track);
    j.key("rss_bytes_per_track").value(m.rss_bytes_per_track);
    j.end_object();
  }
  j.end_array();
  j.end_object();
  if (!j.save(path)) {
    std::cerr << "kew_pipeline_bench: cannot write " << path << "\n";
    std::exit(1);
  }
}

std::vector<EndToEnd> run_throughput(const Params& prm) {
  std::vector<EndToEnd> runs;
  std::vector<std::size_t> fleets = prm.fleets;
  if (fleets.empty()) fleets = prm.quick ? std::vector<std::size_t>{2000} : std::vector<std::size_t>{2000, 10000};
  for (const std::size_t n : fleets) {
    const std::string name = "ndjson " + std::string(kew::replay::to_string(prm.scenario)) + " " + std::to_string(n) + " × " +
                             std::to_string(static_cast<int>(prm.ndjson_seconds)) + " s";
    std::cerr << name << "...\n";
    runs.push_back(run_end_to_end(name, kew::protocol::Format::Ndjson, generated_ndjson(n, prm.ndjson_seconds, prm.scenario)));
  }
  const std::string bundled = std::string(KEW_TEST_DATA_DIR) + "/asterix/jade/final_frame_062_first3min.ff";
  const std::string shared = std::string(KEW_SHARED_RECORDINGS_DIR) + "/jade-cat062-ff/final_frame_062_30min.ff";
  std::cerr << "cat062 (bundled)...\n";
  runs.push_back(run_end_to_end("CAT062 JADE first 3 min (.ff)", kew::protocol::Format::AsterixFinalFormat, read_file(bundled)));
  if (!prm.quick && std::filesystem::exists(shared)) {
    std::cerr << "cat062 (shared, 30 min)...\n";
    runs.push_back(run_end_to_end("CAT062 JADE 30 min (.ff)", kew::protocol::Format::AsterixFinalFormat, read_file(shared)));
  } else if (!prm.quick) {
    std::cerr << "(" << shared << " absent: the 30-minute CAT062 run is skipped)\n";
  }
  return runs;
}

}  // namespace

int main(int argc, char** argv) {
  const Params prm = parse(argc, argv);
  std::cout << "machine: " << kew::bench::cpu_model_name() << ", " << kew::bench::hardware_threads()
            << " hardware threads, build " << KEW_BUILD_TYPE << "\n";
  const std::vector<EndToEnd> runs = prm.memory_only ? std::vector<EndToEnd>{} : run_throughput(prm);
  std::vector<MemoryPerTrack> memory;
  // Mixed traffic at this density keeps about one alert per aircraft open (holding
  // stacks, converging arrivals), and alert state costs memory too; random traffic has
  // few: both are measured.
  for (const std::size_t n : prm.quick ? std::vector<std::size_t>{10000} : std::vector<std::size_t>{10000, 100000})
    for (const auto scenario : {kew::replay::Scenario::Mixed, kew::replay::Scenario::Random}) {
      std::cerr << "memory, " << n << " aircraft, " << kew::replay::to_string(scenario) << "...\n";
      memory.push_back(measure_memory(n, scenario));
    }
  print(runs, memory);
  if (!prm.json_path.empty()) write_json(prm.json_path, runs, memory);
  return 0;
}
