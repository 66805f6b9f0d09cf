// Parsing an aircraft.json snapshot as large as the busiest aggregator query: 25,000
// aircraft of kew-gen's worldwide traffic (Scenario::Global) written as readsb writes
// aircraft.json. Time per snapshot (the live input reads one a second) and aircraft per
// second; goal: under 50 ms a snapshot.
//   build/tests/bench/kew_snapshot_bench --benchmark_out_format=json --benchmark_out=snapshot.json
#include <benchmark/benchmark.h>

#include <string>

#include <fmt/format.h>

#include "kew/config/aerodromes.hpp"
#include "kew/protocol/aircraft_json.hpp"
#include "kew/replay/traffic_generator.hpp"

namespace {

constexpr std::size_t kAircraft = 25000;

/// One snapshot of `aircraft` aircraft: each one's first record, seen 0.1 to 2 s ago.
std::string snapshot_of(std::size_t aircraft) {
  kew::replay::GeneratorConfig g;
  g.scenario = kew::replay::Scenario::Global;
  g.aircraft = aircraft;
  g.duration_s = 20.0;
  g.period_s = 5.0;
  g.seed = 20261206;
  g.aerodromes = kew::config::load_default_aerodromes();
  kew::replay::TrafficGenerator generator(g);
  const double now = g.start_time + 5.0;
  std::string json = fmt::format(R"({{ "now" : {:.1f},
  "messages" : 123456789,
  "aircraft" : [
)", now);
  std::size_t written = 0;
  for (kew::TrackReport r; written < aircraft && generator.next(r);) {
    if (r.t > now) break;
    if (written > 0) json += ",\n";
    json += fmt::format(
        R"({{"hex":"{}","type":"adsb_icao","flight":"{:<8}","alt_baro":{:.0f},"alt_geom":{:.0f},"gs":{:.1f},)"
        R"("track":{:.2f},"baro_rate":{:.0f},"squawk":"{:04o}","nav_altitude_mcp":{:.0f},"lat":{:.6f},"lon":{:.6f},)"
        R"("nic":8,"rc":186,"seen_pos":{:.1f},"version":2,"nac_p":9,"messages":1234,"seen":0.1,"rssi":-18.4}})",
        r.id, r.callsign.empty() ? "TEST" : r.callsign, r.alt_ft, r.alt_ft + 125.0, r.gs_kt.value_or(0.0),
        r.trk_deg.value_or(0.0), r.vr_fpm.value_or(0.0), r.mode3a.value_or(01000), r.alt_ft, r.lat_deg, r.lon_deg,
        now - r.t);
    ++written;
  }
  json += "\n]}\n";
  return json;
}

void BM_AircraftJsonSnapshot(benchmark::State& state) {
  static const std::string snapshot = snapshot_of(kAircraft);
  std::size_t reports = 0;
  // One decoder, as a live input keeps; finish() after each snapshot makes it report
  // every aircraft again, as in a first snapshot (the most a snapshot can cost).
  auto decoder = kew::protocol::make_aircraft_json_decoder();
  const kew::protocol::ReportSink count = [&](const kew::TrackReport&) { ++reports; };
  for (auto _ : state) {
    reports = 0;
    decoder->feed_text(snapshot, count);
    decoder->finish(count);
    benchmark::DoNotOptimize(reports);
  }
  state.counters["aircraft"] = static_cast<double>(reports);
  state.counters["snapshot_bytes"] = static_cast<double>(snapshot.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * reports));
}
BENCHMARK(BM_AircraftJsonSnapshot)->Unit(benchmark::kMillisecond);

}  // namespace
