// Decoding throughput of the ASTERIX framings, records per second on one core
// (items_per_second counts reports produced):
//   build/tests/bench/kew_decode_bench --benchmark_filter=Asterix
// Inputs: the JADE CAT062 half hour (final format, and the same blocks as raw blocks and
// as a pcap of one UDP datagram per block) from the shared recordings when present, else
// the bundled 3-minute excerpt; the UPC Barcelona CAT048 hour only from the shared
// recordings (no licence: never bundled), skipped when absent.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "kew/protocol/asterix/asterix_decoder.hpp"

namespace kew::protocol {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string shared_path(const std::string& relative) {
  return std::string(KEW_SHARED_RECORDINGS_DIR) + "/" + relative;
}

const std::string& cat062_ff() {
  static const std::string data = [] {
    const std::string shared = shared_path("jade-cat062-ff/final_frame_062_30min.ff");
    if (std::filesystem::exists(shared)) return read_file(shared);
    return read_file(std::string(KEW_TEST_DATA_DIR) + "/asterix/jade/final_frame_062_first3min.ff");
  }();
  return data;
}

std::size_t be16(const std::string& s, std::size_t at) {
  return (std::size_t{static_cast<std::uint8_t>(s[at])} << 8) | static_cast<std::uint8_t>(s[at + 1]);
}

/// The data blocks of the final-format input, back to back.
const std::string& cat062_raw() {
  static const std::string data = [] {
    const std::string& ff = cat062_ff();
    std::string raw;
    for (std::size_t at = 0; at + 2 <= ff.size(); at += be16(ff, at)) raw += ff.substr(at + 8, be16(ff, at) - 12);
    return raw;
  }();
  return data;
}

void put_le32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
}

/// The same blocks as a pcap file: one Ethernet/IPv4/UDP packet per block.
const std::string& cat062_pcap() {
  static const std::string data = [] {
    const std::string& raw = cat062_raw();
    std::string out;
    put_le32(out, 0xA1B2C3D4);
    out += std::string("\x02\x00\x04\x00", 4);
    put_le32(out, 0);
    put_le32(out, 0);
    put_le32(out, 65535);
    put_le32(out, 1);
    std::uint32_t n = 0;
    for (std::size_t at = 0; at + 3 <= raw.size(); ++n) {
      const std::size_t length = be16(raw, at + 1);
      const auto udp_length = static_cast<std::uint32_t>(8 + length);
      const std::uint32_t ip_length = 20 + udp_length;
      std::string frame(12, '\0');
      frame += std::string("\x08\x00\x45\x00", 4);
      frame += static_cast<char>(ip_length >> 8);
      frame += static_cast<char>(ip_length & 0xFF);
      frame += std::string("\x00\x00\x00\x00\x40\x11\x00\x00\x0a\x00\x00\x01\x0a\x00\x00\x02", 16);
      frame += std::string("\x21\x98\x21\x98", 4);  // ports 8600
      frame += static_cast<char>(udp_length >> 8);
      frame += static_cast<char>(udp_length & 0xFF);
      frame += std::string(2, '\0');
      frame += raw.substr(at, length);
      put_le32(out, 1714348800 + n / 10);
      put_le32(out, (n % 10) * 100000);
      put_le32(out, static_cast<std::uint32_t>(frame.size()));
      put_le32(out, static_cast<std::uint32_t>(frame.size()));
      out += frame;
      at += length;
    }
    return out;
  }();
  return data;
}

void decode(benchmark::State& state, AsterixFraming framing, const std::string& input,
            const AsterixOptions& options = {}) {
  std::int64_t reports = 0;
  const ReportSink sink = [&](const TrackReport&) { ++reports; };
  for (auto _ : state) {
    auto decoder = make_asterix_decoder(framing, options);
    decoder->feed(std::as_bytes(std::span<const char>(input.data(), input.size())), sink);
    decoder->finish(sink);
  }
  state.SetItemsProcessed(reports);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(input.size()));
}

void BM_AsterixCat062Raw(benchmark::State& state) { decode(state, AsterixFraming::RawBlocks, cat062_raw()); }
void BM_AsterixCat062FinalFormat(benchmark::State& state) {
  decode(state, AsterixFraming::FinalFormat, cat062_ff());
}
void BM_AsterixCat062Pcap(benchmark::State& state) { decode(state, AsterixFraming::Pcap, cat062_pcap()); }

void BM_AsterixCat048RawBarcelona(benchmark::State& state) {
  static const std::string path = shared_path("upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast");
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("shared UPC Barcelona CAT048 recording absent (never bundled)");
    return;
  }
  static const std::string input = read_file(path);
  AsterixOptions options;
  options.radars.push_back({20, 129, 41.0 + 18.0 / 60 + 2.5284 / 3600, 2.0 + 6.0 / 60 + 7.4095 / 3600, 27.0});
  decode(state, AsterixFraming::RawBlocks, input, options);
}

BENCHMARK(BM_AsterixCat062Raw)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AsterixCat062FinalFormat)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AsterixCat062Pcap)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AsterixCat048RawBarcelona)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace kew::protocol
