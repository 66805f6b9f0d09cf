// kew_zones_bench: worldwide traffic on every core (design §3.3, §4.9). For each fleet of
// `kew-gen --scenario global` at 1 s ADS-B updates, with 1 and with 2 threads side by
// side in one run:
//  - throughput: every record as fast as the pipeline takes them (batches of 512), wall
//    records/s and CPU s of the process;
//  - live latency: the records paced at their own data times (real time, 1×), each poll
//    taking what has arrived as kewd takes a read (the first 16 judged one by one, the
//    rest as a batch by the flush that follows): the wall time from a record's due time
//    to the moment its events were out, p50/p99/max. A pipeline that cannot keep up shows
//    as a latency that grows without bound; each poll's wall time, and the CPU time all
//    threads spent in it, tell the work from the waits for a CPU;
//  - the machine's floor: the same records at the same times, each judged by a fixed
//    spin of the pipeline's mean CPU time per record: the latency the machine alone gives
//    to work of that cost (the waits for a CPU of a virtual machine);
//  - memory per live track: heap in use (mallinfo2) with the fleet loaded, minus before,
//    over the live tracks;
//  - decoding alone: the same records as NDJSON, records/s of the decoder (the serial
//    part that comes before the pipeline in kew-replay).
// Threads' ratio is the scaling. Usage:
//   kew_zones_bench [--fleets N,N...] [--seconds S] [--live-seconds S] [--json FILE]
// Defaults: 25,000 and 100,000 aircraft, 40 s of throughput, 30 s paced.

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "bench_report.hpp"
#include "kew/config/aerodromes.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/formats.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/replay/traffic_generator.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Params {
  std::vector<std::size_t> fleets{25000, 100000};
  double seconds = 40.0;
  double live_seconds = 30.0;
  std::string json_path;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "kew_zones_bench: " << why
            << "\nusage: kew_zones_bench [--fleets N,N...] [--seconds S] [--live-seconds S] [--json FILE]\n";
  std::exit(64);
}

Params parse(int argc, char** argv) {
  Params p;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--fleets" && i + 1 < argc) {
      p.fleets.clear();
      std::string list = argv[++i];
      for (std::size_t at = 0; at <= list.size();) {
        const std::size_t comma = std::min(list.find(',', at), list.size());
        const long n = std::atol(list.substr(at, comma - at).c_str());
        if (n < 1 || n > 1'000'000) usage("--fleets takes aircraft counts from 1 to 1000000");
        p.fleets.push_back(static_cast<std::size_t>(n));
        at = comma + 1;
      }
    } else if (flag == "--seconds" && i + 1 < argc) {
      p.seconds = std::atof(argv[++i]);
      if (!(p.seconds >= 2.0 && p.seconds <= 3600.0)) usage("--seconds must be in [2, 3600]");
    } else if (flag == "--live-seconds" && i + 1 < argc) {
      p.live_seconds = std::atof(argv[++i]);
      if (!(p.live_seconds >= 0.0 && p.live_seconds <= 3600.0)) usage("--live-seconds must be in [0, 3600]");
    } else if (flag == "--json" && i + 1 < argc) {
      p.json_path = argv[++i];
    } else {
      usage("unknown flag " + flag);
    }
  }
  return p;
}

std::vector<kew::TrackReport> global_traffic(std::size_t aircraft, double seconds) {
  kew::replay::GeneratorConfig g;
  g.scenario = kew::replay::Scenario::Global;
  g.aircraft = aircraft;
  g.duration_s = seconds;
  g.period_s = 1.0;
  g.seed = 20261203;
  g.aerodromes = kew::config::load_default_aerodromes();
  kew::replay::TrafficGenerator generator(g);
  std::vector<kew::TrackReport> records;
  records.reserve(static_cast<std::size_t>(static_cast<double>(aircraft) * seconds));
  for (kew::TrackReport r; generator.next(r);) records.push_back(r);
  return records;
}

double cpu_clock_s(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
double process_cpu_s() { return cpu_clock_s(CLOCK_PROCESS_CPUTIME_ID); }
double thread_cpu_s() { return cpu_clock_s(CLOCK_THREAD_CPUTIME_ID); }

kew::PipelineConfig configured(std::size_t threads) {
  kew::PipelineConfig c;  // worldwide zones, the defaults
  c.eligibility.aerodromes = kew::config::load_default_aerodromes();  // as every tool reads them
  c.threads = threads;
  c.batch_records = 512;
  c.prompt_records = 16;  // as kewd (config::kDefaultPromptRecords)
  return c;
}

struct Result {
  std::size_t aircraft = 0, threads = 0;
  std::uint64_t records = 0, alerts_new = 0;
  std::size_t zones_max = 0, live_tracks = 0;
  double wall_s = 0, cpu_s = 0;
  double heap_bytes_per_track = 0;
  // Paced run.
  std::uint64_t live_records = 0;
  double p50_us = NAN, p99_us = NAN, max_us = NAN;
  std::uint64_t reads = 0;  // polls that took records in the paced run
  double read_p50_us = NAN, read_p99_us = NAN;  // wall time to judge one poll's records
  double read_cpu_p99_us = NAN;  // CPU time of the process during one, every thread
  double cpu_per_record_us = NAN;  // mean, every thread
  double floor_p50_us = NAN, floor_p99_us = NAN;  // a fixed spin of that mean per record
  double records_per_s() const { return static_cast<double>(records) / wall_s; }
};

using kew::bench::percentile;

void throughput(const std::vector<kew::TrackReport>& records, Result& r) {
  const std::size_t heap_before = mallinfo2().uordblks;
  kew::Pipeline pipeline(configured(r.threads));
  std::uint64_t opened = 0;
  pipeline.set_alert_sink([&](const kew::AlertEvent& e) { opened += e.state == kew::AlertState::New; });
  const double cpu0 = process_cpu_s();
  const auto wall0 = Clock::now();
  for (const kew::TrackReport& rec : records) {
    pipeline.process(rec);
    r.zones_max = std::max(r.zones_max, pipeline.zone_count());
  }
  pipeline.flush();
  r.wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
  r.cpu_s = process_cpu_s() - cpu0;
  r.records = records.size();
  r.alerts_new = opened;
  r.live_tracks = pipeline.live_tracks();
  r.heap_bytes_per_track =
      static_cast<double>(mallinfo2().uordblks - heap_before) / static_cast<double>(std::max<std::size_t>(1, r.live_tracks));
}

// Busy for `cpu_s` seconds of this thread's CPU time: work of a fixed cost that a wait for
// the CPU does not shorten.
void spin_cpu(double cpu_s) {
  const double until = thread_cpu_s() + cpu_s;
  while (thread_cpu_s() < until) {
  }
}

// Records paced at their own data times from `from` (real time, 1×): each poll takes the
// records that have fallen due, as kewd takes a read, and hands them to `take`, which
// returns, for each, the wall time (s since `wall0`) its events were out.
template <class Take>
std::vector<double> paced(const std::vector<kew::TrackReport>& records, std::size_t from, double seconds, Take&& take) {
  std::vector<double> latency_s, done_s;
  const double paced_from = records[from].t;
  const auto wall0 = Clock::now();
  for (std::size_t next = from; next < records.size() && records[next].t < paced_from + seconds;) {
    const double now = std::chrono::duration<double>(Clock::now() - wall0).count();
    const std::size_t first = next;
    while (next < records.size() && records[next].t - paced_from <= now) ++next;
    if (next == first) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));
      continue;
    }
    done_s.clear();
    take(first, next, wall0, done_s);
    for (std::size_t i = first; i < next; ++i) latency_s.push_back(done_s[i - first] - (records[i].t - paced_from));
  }
  return latency_s;
}

void live(const std::vector<kew::TrackReport>& records, double seconds, Result& r) {
  if (seconds <= 0.0 || records.empty()) return;
  kew::Pipeline pipeline(configured(r.threads));
  const double t0 = records.front().t;
  // The records of the first 10 s fill the picture unpaced; the paced part follows.
  std::size_t from = 0;
  while (from < records.size() && records[from].t < t0 + 10.0) pipeline.process(records[from++]);
  pipeline.flush();
  if (from == records.size()) return;
  std::vector<double> read_s, read_cpu_s;
  double cpu_total_s = 0.0;
  std::vector<bool> waiting;
  std::vector<double> latency_s =
      paced(records, from, seconds, [&](std::size_t first, std::size_t end, Clock::time_point wall0, std::vector<double>& done) {
        const auto started = Clock::now();
        const double cpu_start = process_cpu_s();
        waiting.clear();
        for (std::size_t i = first; i < end; ++i) {
          pipeline.process(records[i]);
          // Judged at once (prompt_records) unless the record waits for the flush.
          waiting.push_back(pipeline.batch_waiting());
          done.push_back(std::chrono::duration<double>(Clock::now() - wall0).count());
        }
        pipeline.flush();
        const double flushed = std::chrono::duration<double>(Clock::now() - wall0).count();
        for (std::size_t i = 0; i < done.size(); ++i)
          if (waiting[i]) done[i] = flushed;
        const double cpu = process_cpu_s() - cpu_start;
        cpu_total_s += cpu;
        read_cpu_s.push_back(cpu);
        read_s.push_back(std::chrono::duration<double>(Clock::now() - started).count());
      });
  r.live_records = latency_s.size();
  r.reads = read_s.size();
  r.read_p50_us = 1e6 * percentile(read_s, 0.50);
  r.read_p99_us = 1e6 * percentile(read_s, 0.99);
  r.read_cpu_p99_us = 1e6 * percentile(read_cpu_s, 0.99);
  r.p50_us = 1e6 * percentile(latency_s, 0.50);
  r.p99_us = 1e6 * percentile(latency_s, 0.99);
  r.max_us = latency_s.empty() ? NAN : 1e6 * *std::max_element(latency_s.begin(), latency_s.end());
  // The machine's own share: the same records at the same times, each one judged by a
  // fixed spin of the pipeline's mean CPU time per record, delivered at once.
  r.cpu_per_record_us = 1e6 * cpu_total_s / static_cast<double>(std::max<std::size_t>(1, latency_s.size()));
  const double spin_s = 1e-6 * r.cpu_per_record_us;
  std::vector<double> floor_s =
      paced(records, from, seconds, [&](std::size_t first, std::size_t end, Clock::time_point wall0, std::vector<double>& done) {
        for (std::size_t i = first; i < end; ++i) {
          spin_cpu(spin_s);
          done.push_back(std::chrono::duration<double>(Clock::now() - wall0).count());
        }
      });
  r.floor_p50_us = 1e6 * percentile(floor_s, 0.50);
  r.floor_p99_us = 1e6 * percentile(floor_s, 0.99);
}

double decode_records_per_s(const std::vector<kew::TrackReport>& records) {
  std::string text;
  for (const kew::TrackReport& r : records) {
    kew::protocol::append_ndjson(text, r);
    text += '\n';
  }
  auto decoder = kew::protocol::make_decoder(kew::protocol::Format::Ndjson);
  std::uint64_t n = 0;
  const auto wall0 = Clock::now();
  decoder->feed(std::as_bytes(std::span<const char>(text.data(), text.size())), [&](const kew::TrackReport&) { ++n; });
  decoder->finish([&](const kew::TrackReport&) { ++n; });
  return static_cast<double>(n) / std::chrono::duration<double>(Clock::now() - wall0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const Params prm = parse(argc, argv);
  std::cout << "machine: " << kew::bench::cpu_model_name() << ", " << kew::bench::hardware_threads()
            << " hardware threads, build " << KEW_BUILD_TYPE << "\n";
  std::vector<Result> results;
  std::vector<double> decode_rates;
  for (const std::size_t aircraft : prm.fleets) {
    std::cerr << "generating " << aircraft << " aircraft × " << std::max(prm.seconds, prm.live_seconds + 10.0)
              << " s...\n";
    const std::vector<kew::TrackReport> records = global_traffic(aircraft, std::max(prm.seconds, prm.live_seconds + 10.0));
    const auto end = std::find_if(records.begin(), records.end(),
                                  [&](const kew::TrackReport& r) { return r.t >= records.front().t + prm.seconds; });
    const std::vector<kew::TrackReport> timed(records.begin(), end);
    decode_rates.push_back(decode_records_per_s(timed));
    for (const std::size_t threads : {std::size_t{1}, std::size_t{2}}) {
      std::cerr << aircraft << " aircraft, " << threads << " thread(s)...\n";
      Result r;
      r.aircraft = aircraft;
      r.threads = threads;
      throughput(timed, r);
      live(records, prm.live_seconds, r);
      results.push_back(r);
    }
  }
  std::printf("\n| aircraft | threads | records | zones | records/s (wall) | CPU s | × 1 thread | live p50 µs | p99 µs | max µs | heap B/track | alerts |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Result& r = results[i];
    const Result& one = results[i - (r.threads == 2 ? 1 : 0)];
    std::printf("| %zu | %zu | %llu | %zu | %.0f | %.2f | %.2f | %.0f | %.0f | %.0f | %.0f | %llu |\n", r.aircraft, r.threads,
                static_cast<unsigned long long>(r.records), r.zones_max, r.records_per_s(), r.cpu_s,
                r.records_per_s() / one.records_per_s(), r.p50_us, r.p99_us, r.max_us, r.heap_bytes_per_track,
                static_cast<unsigned long long>(r.alerts_new));
  }
  for (const Result& r : results)
    std::printf("paced, %zu aircraft, %zu thread(s): %llu polls of %.1f records, each judged in p50 %.0f µs, p99 %.0f µs "
                "(CPU of every thread p99 %.0f µs); %.1f µs CPU per record; a fixed spin of that per record: "
                "p50 %.0f µs, p99 %.0f µs\n",
                r.aircraft, r.threads, static_cast<unsigned long long>(r.reads),
                static_cast<double>(r.live_records) / static_cast<double>(std::max<std::uint64_t>(1, r.reads)),
                r.read_p50_us, r.read_p99_us, r.read_cpu_p99_us, r.cpu_per_record_us, r.floor_p50_us, r.floor_p99_us);
  for (std::size_t i = 0; i < prm.fleets.size(); ++i)
    std::printf("NDJSON decoding alone, %zu aircraft: %.0f records/s\n", prm.fleets[i], decode_rates[i]);
  if (!prm.json_path.empty()) {
    kew::bench::JsonText j;
    j.begin_object();
    kew::bench::put_machine(j, KEW_BUILD_TYPE);
    j.key("scenario").value("global");
    j.key("period_s").value(1.0);
    j.key("seconds").value(prm.seconds);
    j.key("live_seconds").value(prm.live_seconds);
    j.key("runs").begin_array();
    for (const Result& r : results) {
      j.begin_object();
      j.key("aircraft").value(std::uint64_t{r.aircraft});
      j.key("threads").value(std::uint64_t{r.threads});
      j.key("records").value(r.records);
      j.key("zones_max").value(std::uint64_t{r.zones_max});
      j.key("wall_s").value(r.wall_s);
      j.key("cpu_s").value(r.cpu_s);
      j.key("records_per_s").value(r.records_per_s());
      j.key("live_records").value(r.live_records);
      j.key("live_p50_us").value(r.p50_us);
      j.key("live_p99_us").value(r.p99_us);
      j.key("live_max_us").value(r.max_us);
      j.key("live_reads").value(r.reads);
      j.key("live_read_p50_us").value(r.read_p50_us);
      j.key("live_read_p99_us").value(r.read_p99_us);
      j.key("live_read_cpu_p99_us").value(r.read_cpu_p99_us);
      j.key("live_cpu_per_record_us").value(r.cpu_per_record_us);
      j.key("floor_p50_us").value(r.floor_p50_us);
      j.key("floor_p99_us").value(r.floor_p99_us);
      j.key("heap_bytes_per_track").value(r.heap_bytes_per_track);
      j.key("alerts_new").value(r.alerts_new);
      j.end_object();
    }
    j.end_array();
    j.key("ndjson_decode_records_per_s").begin_array();
    for (const double d : decode_rates) j.value(d);
    j.end_array();
    j.end_object();
    if (!j.save(prm.json_path)) std::cerr << "kew_zones_bench: cannot write " << prm.json_path << "\n";
  }
  return 0;
}
