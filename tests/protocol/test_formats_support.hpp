#pragma once
// Helpers shared by the text-decoder tests: reading test data, compressing it, feeding a
// decoder in different chunkings, comparing reports field by field, summarising a decode.

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol::test {

/// Rejection counts by reason, as Rejections::by_reason() gives them.
using Counts = std::map<std::string, std::uint64_t, std::less<>>;

inline std::string bundled_path(const std::string& name) {
  return std::string(KEW_TEST_DATA_DIR) + "/text/" + name;
}

inline std::string shared_path(const std::string& relative) {
  return std::string(KEW_SHARED_RECORDINGS_DIR) + "/" + relative;
}

inline bool exists(const std::string& path) { return std::filesystem::exists(path); }

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::span<const std::byte> bytes_of(std::string_view text) {
  return std::as_bytes(std::span<const char>(text.data(), text.size()));
}

/// One gzip member holding `text` (zlib's deflate with the gzip wrapper).
inline std::string gzip_member(std::string_view text, int level = 6) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, level, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&z, static_cast<uLong>(text.size())) + 64, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

/// Feeds `input` cut at `cuts` (sorted offsets), then finish(); returns the reports.
inline std::vector<TrackReport> decode_with_cuts(Decoder& decoder, std::string_view input,
                                                 const std::vector<std::size_t>& cuts) {
  std::vector<TrackReport> reports;
  const ReportSink sink = [&](const TrackReport& r) { reports.push_back(r); };
  std::size_t start = 0;
  for (const std::size_t cut : cuts) {
    decoder.feed_text(input.substr(start, cut - start), sink);
    start = cut;
  }
  decoder.feed_text(input.substr(start), sink);
  decoder.finish(sink);
  return reports;
}

inline std::vector<TrackReport> decode_all(Decoder& decoder, std::string_view input) {
  return decode_with_cuts(decoder, input, {});
}

/// decode_all(), and the decoder's rejections copied to `*rejections` when given.
inline std::vector<TrackReport> decode_counted(Decoder& decoder, std::string_view input, Rejections* rejections) {
  std::vector<TrackReport> reports = decode_all(decoder, input);
  if (rejections) *rejections = decoder.rejections();
  return reports;
}

/// Feeds each of `messages` as one message (a datagram, a poll: feed, then
/// end_message()), then ends the stream when `finish`; the number of reports made.
inline std::size_t reports_of_messages(Decoder& decoder, std::initializer_list<std::string_view> messages,
                                       bool finish) {
  std::size_t reports = 0;
  const ReportSink count = [&](const TrackReport&) { ++reports; };
  for (const std::string_view message : messages) {
    decoder.feed_text(message, count);
    decoder.end_message(count);
  }
  if (finish) decoder.finish(count);
  return reports;
}

inline std::vector<TrackReport> decode_byte_by_byte(Decoder& decoder, std::string_view input) {
  std::vector<std::size_t> cuts(input.empty() ? 0 : input.size() - 1);
  for (std::size_t i = 0; i < cuts.size(); ++i) cuts[i] = i + 1;
  return decode_with_cuts(decoder, input, cuts);
}

inline std::vector<TrackReport> decode_random_chunks(Decoder& decoder, std::string_view input,
                                                     std::uint32_t seed) {
  std::mt19937 random(seed);
  std::vector<std::size_t> cuts;
  std::size_t at = 0;
  while (true) {
    // Mostly small chunks, now and then a large one.
    const std::size_t step = random() % 8 == 0 ? 1 + random() % 20000 : 1 + random() % 300;
    at += step;
    if (at >= input.size()) break;
    cuts.push_back(at);
  }
  return decode_with_cuts(decoder, input, cuts);
}

/// The bits of a double (so -0.0 differs from 0.0); absent optionals map to a NaN
/// pattern no decoder produces.
inline std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }
inline std::uint64_t bits(const std::optional<double>& v) {
  return v ? bits(*v) : 0x7ff4000000000bad;
}

/// Field-by-field equality, doubles compared bit for bit.
inline void expect_same_report(const TrackReport& a, const TrackReport& b, std::size_t index) {
  SCOPED_TRACE("report #" + std::to_string(index) + " id " + a.id);
  EXPECT_EQ(bits(a.t), bits(b.t)) << a.t << " vs " << b.t;
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.position_source, b.position_source);
  EXPECT_EQ(bits(a.lat_deg), bits(b.lat_deg)) << a.lat_deg << " vs " << b.lat_deg;
  EXPECT_EQ(bits(a.lon_deg), bits(b.lon_deg)) << a.lon_deg << " vs " << b.lon_deg;
  EXPECT_EQ(bits(a.alt_ft), bits(b.alt_ft)) << a.alt_ft << " vs " << b.alt_ft;
  EXPECT_EQ(bits(a.gs_kt), bits(b.gs_kt));
  EXPECT_EQ(bits(a.trk_deg), bits(b.trk_deg));
  EXPECT_EQ(bits(a.vr_fpm), bits(b.vr_fpm));
  EXPECT_EQ(bits(a.sel_ft), bits(b.sel_ft));
  if (a.sel_ft) {
    EXPECT_EQ(a.sel_src, b.sel_src);  // meaningful only with sel_ft
  }
  EXPECT_EQ(bits(a.tar_dps), bits(b.tar_dps));
  EXPECT_EQ(a.callsign, b.callsign);
  EXPECT_EQ(a.mode3a, b.mode3a);
  EXPECT_EQ(a.address, b.address);
  EXPECT_EQ(a.on_ground, b.on_ground);
  EXPECT_EQ(a.coasting, b.coasting);
  EXPECT_EQ(a.track_end, b.track_end);
}

inline void expect_same_reports(const std::vector<TrackReport>& a,
                                const std::vector<TrackReport>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    expect_same_report(a[i], b[i], i);
    if (testing::Test::HasFailure()) return;  // one broken report is enough to read
  }
}

/// Decodes `input` in one piece, byte by byte and in random chunks with fresh decoders
/// from `make`; all three must give the same reports and the same rejection counts.
template <class MakeDecoder>
void expect_incremental(MakeDecoder make, std::string_view input) {
  auto whole_decoder = make();
  const auto whole = decode_all(*whole_decoder, input);
  auto bytewise_decoder = make();
  const auto bytewise = decode_byte_by_byte(*bytewise_decoder, input);
  auto chunked_decoder = make();
  const auto chunked = decode_random_chunks(*chunked_decoder, input, 20240429);
  EXPECT_FALSE(whole.empty());
  {
    SCOPED_TRACE("byte by byte");
    expect_same_reports(whole, bytewise);
    EXPECT_EQ(whole_decoder->rejections().by_reason(), bytewise_decoder->rejections().by_reason());
  }
  {
    SCOPED_TRACE("random chunks");
    expect_same_reports(whole, chunked);
    EXPECT_EQ(whole_decoder->rejections().by_reason(), chunked_decoder->rejections().by_reason());
  }
}

struct Summary {
  std::size_t count = 0;
  std::set<std::string> ids;
  double t_min = 0, t_max = 0;
};

inline Summary summarize(const std::vector<TrackReport>& reports) {
  Summary s;
  s.count = reports.size();
  if (reports.empty()) return s;
  s.t_min = s.t_max = reports.front().t;
  for (const TrackReport& r : reports) {
    s.ids.insert(r.id);
    s.t_min = std::min(s.t_min, r.t);
    s.t_max = std::max(s.t_max, r.t);
  }
  return s;
}

}  // namespace kew::protocol::test
