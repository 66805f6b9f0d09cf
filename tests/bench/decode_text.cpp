// Decoding throughput of the text formats, reports per second on one core
// (items_per_second). Goal for canonical NDJSON: >= 1M lines/s.
//   build/tests/bench/kew_decode_bench --benchmark_filter=Text
// Inputs: NDJSON is generated in memory (100k canonical lines); SBS, readsb and OpenSky
// JSON use the shared recordings when present (../shared/data/recordings), else the
// bundled excerpts in tests/data/text.
#include <benchmark/benchmark.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "kew/protocol/gzip.hpp"
#include "kew/protocol/ndjson.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/protocol/opensky.hpp"
#include "kew/protocol/readsb.hpp"
#include "kew/protocol/sbs.hpp"

namespace kew::protocol {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The shared recording when present, else the bundled excerpt.
std::string shared_or_bundled(const std::string& shared, const std::string& bundled) {
  const std::string shared_path = std::string(KEW_SHARED_RECORDINGS_DIR) + "/" + shared;
  if (std::filesystem::exists(shared_path)) return read_file(shared_path);
  return read_file(std::string(KEW_TEST_DATA_DIR) + "/text/" + bundled);
}

std::string inflate_all(const std::string& compressed) {
  std::string out;
  z_stream z{};
  inflateInit2(&z, 16 + MAX_WBITS);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  z.avail_in = static_cast<uInt>(compressed.size());
  char buffer[65536];
  int status = Z_OK;
  while (status == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buffer);
    z.avail_out = sizeof buffer;
    status = inflate(&z, Z_NO_FLUSH);
    out.append(buffer, sizeof buffer - z.avail_out);
  }
  inflateEnd(&z);
  return out;
}

/// 100k canonical lines of 1,000 aircraft with every optional member, as recorded.
const std::string& canonical_lines() {
  static const std::string text = [] {
    std::mt19937_64 random(1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::string out;
    TrackReport r;
    r.source = "adsb";
    for (int i = 0; i < 100000; ++i) {
      r.t = 1714400000.0 + i * 0.004;
      r.id = "4CA" + std::to_string(100 + i % 1000);
      r.callsign = "BAW" + std::to_string(i % 1000);
      r.lat_deg = 45 + 10 * unit(random);
      r.lon_deg = -5 + 10 * unit(random);
      r.alt_ft = std::round(1000 + 40000 * unit(random));
      r.gs_kt = std::round(200 + 300 * unit(random));
      r.trk_deg = std::round(3600 * unit(random)) / 10;
      r.vr_fpm = std::round(-2000 + 4000 * unit(random));
      append_ndjson(out, r);
      out += '\n';
    }
    return out;
  }();
  return text;
}

template <class MakeDecoder>
void run(benchmark::State& state, const std::string& input, MakeDecoder make) {
  std::size_t reports = 0;
  for (auto _ : state) {
    auto decoder = make();
    std::size_t n = 0;
    const ReportSink sink = [&](const TrackReport& r) {
      benchmark::DoNotOptimize(r.lat_deg);
      ++n;
    };
    decoder->feed_text(input, sink);
    decoder->finish(sink);
    reports = n;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * reports));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * input.size()));
  state.counters["reports"] = static_cast<double>(reports);
}

void BM_TextNdjson(benchmark::State& state) {
  run(state, canonical_lines(), [] { return make_ndjson_decoder(); });
}
BENCHMARK(BM_TextNdjson)->Unit(benchmark::kMillisecond);

void BM_TextNdjsonWrite(benchmark::State& state) {
  auto decoder = make_ndjson_decoder();
  std::vector<TrackReport> reports;
  decoder->feed_text(canonical_lines(), [&](const TrackReport& r) { reports.push_back(r); });
  std::string out;
  for (auto _ : state) {
    out.clear();
    for (const TrackReport& r : reports) append_ndjson(out, r);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * reports.size()));
}
BENCHMARK(BM_TextNdjsonWrite)->Unit(benchmark::kMillisecond);

void BM_TextSbs(benchmark::State& state) {
  static const std::string input =
      shared_or_bundled("sbs-japan/adsb202201082242.csv", "sbs_japan_13501-16500.csv");
  run(state, input, [] { return make_sbs_decoder(); });
}
BENCHMARK(BM_TextSbs)->Unit(benchmark::kMillisecond);

void BM_TextReadsb(benchmark::State& state) {
  static const std::string input = [] {
    const std::string grid =
        std::string(KEW_SHARED_RECORDINGS_DIR) + "/adsb_actions-readsb/grid_20250601_36_-122.jsonl.gz";
    if (std::filesystem::exists(grid)) return inflate_all(read_file(grid));
    return read_file(std::string(KEW_TEST_DATA_DIR) + "/text/readsb_20minutes.json");
  }();
  run(state, input, [] { return make_readsb_decoder(); });
}
BENCHMARK(BM_TextReadsb)->Unit(benchmark::kMillisecond);

void BM_TextOpenskyJson(benchmark::State& state) {
  static const std::string input = inflate_all(
      shared_or_bundled("traffic-opensky/switzerland.json.gz", "opensky_switzerland_first2000.json.gz"));
  run(state, input, [] { return make_opensky_json_decoder(); });
}
BENCHMARK(BM_TextOpenskyJson)->Unit(benchmark::kMillisecond);

void BM_TextOpenskyJsonGzip(benchmark::State& state) {
  static const std::string input =
      shared_or_bundled("traffic-opensky/switzerland.json.gz", "opensky_switzerland_first2000.json.gz");
  run(state, input, [] { return make_gzip_decoder(make_opensky_json_decoder()); });
}
BENCHMARK(BM_TextOpenskyJsonGzip)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace kew::protocol
