// Format names, auto-detection on every bundled and shared recording, the decoder factory,
// the auto-detecting decoder.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <optional>
#include <random>
#include <set>

#include "kew/protocol/formats.hpp"
#include "kew/protocol/ndjson.hpp"
#include "kew/protocol/opensky.hpp"
#include "kew/protocol/readsb.hpp"
#include "kew/protocol/sbs.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::decode_all;

constexpr Format kAllFormats[] = {Format::Auto,         Format::Ndjson,      Format::Sbs,
                                  Format::OpenskyCsv,   Format::OpenskyJson, Format::ReadsbJson,
                                  Format::AircraftJson, Format::OpenskyRest, Format::ReadsbTrace,
                                  Format::AsterixRaw,   Format::AsterixFinalFormat, Format::AsterixPcap,
                                  Format::AsterixDatagram};

Format detect_file(const std::string& path, std::size_t head_bytes = 64 * 1024) {
  std::string head = test::read_file(path);
  if (head.size() > head_bytes) head.resize(head_bytes);
  return detect_format(test::bytes_of(head));
}

TEST(Formats, NamesRoundTrip) {
  EXPECT_EQ(to_string(Format::OpenskyCsv), "opensky-csv");
  EXPECT_EQ(to_string(Format::AsterixFinalFormat), "asterix-ff");
  EXPECT_EQ(to_string(Format::ReadsbJson), "readsb");
  std::set<std::string_view> names;
  for (const Format format : kAllFormats) {
    const std::optional<Format> parsed = kFormatNames.parse(to_string(format));
    ASSERT_TRUE(parsed) << to_string(format);
    EXPECT_EQ(*parsed, format);
    names.insert(to_string(format));
  }
  EXPECT_EQ(names.size(), std::size(kAllFormats));
  EXPECT_EQ(kFormatNames.entries().size(), std::size(kAllFormats));
  EXPECT_FALSE(kFormatNames.parse("NDJSON"));
  EXPECT_FALSE(kFormatNames.parse(""));
  EXPECT_EQ(kFormatNames.list({Format::Auto, Format::AsterixDatagram}),
            "ndjson, sbs, opensky-csv, opensky-json, readsb, aircraft-json, opensky-rest, readsb-trace, asterix-raw, "
            "asterix-ff, asterix-pcap");
}

TEST(Formats, DetectsEveryBundledTextFile) {
  const std::map<std::string, Format> expected = {
      {"canonical_sample.ndjson", Format::Ndjson},
      {"sbs_japan_13501-16500.csv", Format::Sbs},
      {"readsb_20minutes.json", Format::ReadsbJson},
      {"opensky_switzerland_first2000.json.gz", Format::OpenskyJson},
      {"opensky_states_sample.csv", Format::OpenskyCsv},
      {"aircraft_json_history.json", Format::AircraftJson},
      {"readsb_traces/trace_full_a08846.json", Format::ReadsbTrace},
      {"readsb_traces/trace_full_aab1cf.json", Format::ReadsbTrace},
  };
  for (const auto& [name, format] : expected)
    EXPECT_EQ(detect_file(test::bundled_path(name)), format) << name;
  // A small head is enough for the text formats.
  for (const auto& [name, format] : expected)
    EXPECT_EQ(detect_file(test::bundled_path(name), 600), format) << name << " (600 bytes)";
}

TEST(Formats, DetectsNothingInUnknownOrEmptyInput) {
  const auto detect = [](std::string_view text) { return detect_format(test::bytes_of(text)); };
  EXPECT_EQ(detect(""), Format::Auto);
  EXPECT_EQ(detect("hello world\nthis is prose\n"), Format::Auto);
  EXPECT_EQ(detect("{\"some\":\"json\"}\n"), Format::Auto);
  EXPECT_EQ(detect("# only a comment\n\n"), Format::Auto);
  // Comments before the first record, a byte order mark, CRLF.
  EXPECT_EQ(detect("\xEF\xBB\xBF# recorded by kew\r\n{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\r\n"),
            Format::Ndjson);
  EXPECT_EQ(detect("{\"flight\": \"N/A\", \"now\": 1693383001}\n"), Format::ReadsbJson);
  EXPECT_EQ(detect("CLK,,,,,,2024/04/29,14:13:20.000,2024/04/29,14:13:20.000\n"), Format::Sbs);
}

// The formats that are one JSON object after another are told apart by their members,
// wherever those stand, and none of them takes another's stream.
TEST(Formats, TellsTheJsonSnapshotFormatsApart) {
  const auto detect = [](std::string_view text) { return detect_format(test::bytes_of(text)); };
  EXPECT_EQ(detect(R"({"now":1,"aircraft":[{"hex":"a1b2c3","flight":"states"}]})"), Format::AircraftJson);
  EXPECT_EQ(detect(R"({"now":1,"messages":2,"ac":[]})"), Format::AircraftJson);
  EXPECT_EQ(detect(R"({"time":1,"states":[["a1b2c3","aircraft","trace",1,1,1,1,1,false]]})"), Format::OpenskyRest);
  EXPECT_EQ(detect(R"({"states" : null, "time" : 1})"), Format::OpenskyRest);
  EXPECT_EQ(detect(R"({"icao":"a1b2c3","timestamp":1,"trace":[[0,1,2,"ground"]]})"), Format::ReadsbTrace);
  EXPECT_EQ(detect("{\"timestamp\": 1,\n\"trace\":[ \n[0,1,2,3] ],\n\"icao\":\"a1b2c3\" }"), Format::ReadsbTrace)
      << "whatever the members' order";
  EXPECT_EQ(detect(R"([{"timestamp":1533101250000,"icao24":"3003ae","latitude":45.8,"longitude":9.2,"altitude":1}])"),
            Format::OpenskyJson);
  EXPECT_EQ(detect(R"({"now":1693383000,"hex":"ab80bc","lat":39.8,"lon":-119.8,"alt_baro":9975})" "\n"),
            Format::ReadsbJson);
  EXPECT_EQ(detect(R"({"trace":[],"states":{}})"), Format::Auto) << "neither an icao nor a states array";
}

TEST(Formats, DetectsEverySharedRecording) {
  const std::string root = test::shared_path("");
  if (!test::exists(root)) GTEST_SKIP() << "shared recordings absent: " << root;
  // GPS framing (reader_network .gps: blocks each followed by a 10-byte trailer) is not
  // a framing of ours: detection may name it raw (the raw decoder resynchronises over
  // the trailers) or nothing, depending on the ASTERIX heuristics' confidence.
  const std::set<Format> kGps = {Format::Auto, Format::AsterixRaw};
  const std::map<std::string, std::set<Format>> expected = {
      {"adsb_actions-readsb/1hr.json", {Format::ReadsbJson}},
      {"adsb_actions-readsb/20minutes.json", {Format::ReadsbJson}},
      {"adsb_actions-readsb/grid_20250601_36_-122.jsonl.gz", {Format::ReadsbJson}},
      {"adsb_actions-readsb/grid_20250602_36_-122.jsonl.gz", {Format::ReadsbJson}},
      {"croatiacontrol-samples/asterix.pcap", {Format::AsterixPcap}},
      {"croatiacontrol-samples/cat034.raw", {Format::AsterixRaw}},
      {"croatiacontrol-samples/cat048.raw", {Format::AsterixRaw}},
      {"croatiacontrol-samples/cat062cat065.raw", {Format::AsterixRaw}},
      {"croatiacontrol-samples/cat21_re.ast", {Format::AsterixRaw}},
      {"croatiacontrol-samples/cat_001_002.pcap", {Format::AsterixPcap}},
      {"croatiacontrol-samples/cat_034_048.pcap", {Format::AsterixPcap}},
      {"croatiacontrol-samples/cat_062_065.pcap", {Format::AsterixPcap}},
      {"jade-cat062-ff/final_frame_062_30min.ff", {Format::AsterixFinalFormat}},
      {"jasterix-vectors/JADE_NATS_CAT048_119bytes_TCAS.ff", {Format::AsterixFinalFormat}},
      {"jasterix-vectors/JADE_final_frame_062_one_packet_sample2.ff", {Format::AsterixFinalFormat}},
      {"jasterix-vectors/asterix4py_cat062.ast", {Format::AsterixRaw}},
      {"reader_network-es/068test_bds30.gps", kGps},
      {"reader_network-es/068test_rrd3.gps", kGps},
      {"reader_network-es/canalA.gps", kGps},
      {"reader_network-es/canalB.gps", kGps},
      {"reader_network-es/sdpb-op-cat20.ast", {Format::AsterixRaw}},
      {"sbs-japan/adsb202201082242.csv", {Format::Sbs}},
      {"traffic-opensky/switzerland.json.gz", {Format::OpenskyJson}},
      // Decoded Mode S messages (icao24, timestamp in s, latitude/longitude on position
      // messages): read as OpenSky JSON lines, the messages without position refused.
      {"traffic-opensky/tutorial.jsonl.gz", {Format::OpenskyJson}},
      {"upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast", {Format::AsterixRaw}},
  };
  std::size_t checked = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    const std::string relative = std::filesystem::relative(entry.path(), root).string();
    if (relative.ends_with(".md") || relative.ends_with(".txt")) continue;
    const Format detected = detect_file(entry.path().string());
    if (relative.starts_with("jasterix-vectors/cat") && relative.ends_with(".bin")) {
      EXPECT_EQ(detected, Format::AsterixRaw) << relative;  // one data block each
    } else {
      const auto it = expected.find(relative);
      ASSERT_NE(it, expected.end()) << "a recording the test does not know: " << relative;
      EXPECT_TRUE(it->second.count(detected)) << relative << " detected as " << to_string(detected);
    }
    ++checked;
  }
  EXPECT_GE(checked, expected.size() + 20);
}

TEST(Formats, MakeDecoderHandlesGzipForEveryTextFormat) {
  const std::string compressed =
      test::read_file(test::bundled_path("opensky_switzerland_first2000.json.gz"));
  auto decoder = make_decoder(Format::OpenskyJson);
  EXPECT_EQ(decode_all(*decoder, compressed).size(), 2000u);
  EXPECT_EQ(decoder->format_name(), "opensky-json");
  auto plain = make_decoder(Format::Ndjson);
  EXPECT_EQ(decode_all(*plain, test::read_file(test::bundled_path("canonical_sample.ndjson"))).size(), 16u);
  EXPECT_EQ(make_decoder(Format::Sbs)->format_name(), "sbs");
  EXPECT_EQ(make_decoder(Format::ReadsbJson)->format_name(), "readsb");
  EXPECT_EQ(make_decoder(Format::OpenskyCsv)->format_name(), "opensky-csv");
  EXPECT_EQ(make_decoder(Format::AsterixRaw)->format_name(), "asterix-raw");
  EXPECT_EQ(make_decoder(Format::AsterixDatagram)->format_name(), "asterix-datagram");
}

TEST(Formats, OptionsReachTheDecoders) {
  DecoderOptions options;
  options.sbs_utc_offset_s = 3600;
  options.max_line_bytes = 100;
  auto sbs = make_decoder(Format::Sbs, options);
  const auto reports = decode_all(
      *sbs, "MSG,3,1,1,4CA123,1,2024/04/29,15:13:20.000,2024/04/29,15:13:20.000,,1000,,,1,2,,,0,0,0,0\n" +
                std::string(150, 'x') + "\n");
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].t, 1714400000.0);
  EXPECT_EQ(sbs->rejections().count("line_too_long"), 1u);
  EXPECT_EQ(sbs->max_message_bytes(), 100u);

  options.aircraft_json.max_snapshot_bytes = 5000;
  options.aircraft_json.max_position_age_s = 2.0;
  auto snapshots = make_decoder(Format::AircraftJson, options);
  EXPECT_EQ(snapshots->max_message_bytes(), 5000u);
  EXPECT_EQ(decode_all(*snapshots, R"({"now":1700000000,"aircraft":[)"
                                   R"({"hex":"000001","alt_baro":1,"lat":1,"lon":1,"seen_pos":1.9},)"
                                   R"({"hex":"000002","alt_baro":1,"lat":1,"lon":1,"seen_pos":2.1}]})")
                .size(),
            1u);
}

class AutoDecoderOnBundledFile : public testing::TestWithParam<std::pair<const char*, Format>> {};

TEST_P(AutoDecoderOnBundledFile, GivesTheSameReportsAsTheExplicitDecoder) {
  const auto& [name, format] = GetParam();
  const std::string input = test::read_file(test::bundled_path(name));
  auto explicit_decoder = make_decoder(format);
  const auto expected = decode_all(*explicit_decoder, input);
  auto automatic = make_decoder(Format::Auto);
  EXPECT_EQ(automatic->format_name(), "auto");
  test::expect_same_reports(expected, test::decode_random_chunks(*automatic, input, 7));
  EXPECT_EQ(automatic->rejections().by_reason(), explicit_decoder->rejections().by_reason());
  // And again on the same decoder: finish() starts a new stream, detected afresh.
  test::expect_same_reports(expected, decode_all(*automatic, input));
}

INSTANTIATE_TEST_SUITE_P(
    Files, AutoDecoderOnBundledFile,
    testing::Values(std::pair{"canonical_sample.ndjson", Format::Ndjson},
                    std::pair{"sbs_japan_13501-16500.csv", Format::Sbs},
                    std::pair{"readsb_20minutes.json", Format::ReadsbJson},
                    std::pair{"opensky_switzerland_first2000.json.gz", Format::OpenskyJson},
                    std::pair{"opensky_states_sample.csv", Format::OpenskyCsv},
                    std::pair{"aircraft_json_history.json", Format::AircraftJson},
                    std::pair{"readsb_traces/trace_full_aab1cf.json", Format::ReadsbTrace}));

TEST(AutoDecoder, UnknownStreamIsCountedOnceAndIgnored) {
  auto decoder = make_decoder(Format::Auto);
  std::string prose;
  while (prose.size() < 100000) prose += "This is not a recording of anything at all.\n";
  EXPECT_TRUE(decode_all(*decoder, prose).empty());
  EXPECT_EQ(decoder->rejections().count("unknown_format"), 1u);
  EXPECT_EQ(decoder->rejections().total(), 1u);
  // A short unknown stream is judged at finish().
  auto short_decoder = make_decoder(Format::Auto);
  EXPECT_TRUE(decode_all(*short_decoder, "hello\n").empty());
  EXPECT_EQ(short_decoder->rejections().count("unknown_format"), 1u);
}

// A stream opening with noise (binary or text) is still detected, from the first
// line after the noise; the noise is counted once, wherever the feed boundaries fall.
TEST(AutoDecoder, FindsTheFormatAfterNoise) {
  const std::string sample = test::read_file(test::bundled_path("canonical_sample.ndjson"));
  auto explicit_decoder = make_decoder(Format::Ndjson);
  const auto expected = decode_all(*explicit_decoder, sample);
  ASSERT_FALSE(expected.empty());
  std::mt19937 random(3);
  std::string binary(4096, '\0');
  for (char& c : binary) c = static_cast<char>(random() & 0xff);
  std::string prose;
  for (int i = 0; i < 40; ++i) prose += "not a record, line " + std::to_string(i) + "\n";
  for (const std::string& noise : {binary + "\n", prose}) {
    auto automatic = make_decoder(Format::Auto);
    test::expect_same_reports(expected, test::decode_random_chunks(*automatic, noise + sample, 5));
    EXPECT_EQ(automatic->rejections().count("unknown_format"), 1u);
    auto whole = make_decoder(Format::Auto);
    test::expect_same_reports(expected, decode_all(*whole, noise + sample));
  }
}

// End_message() closes a datagram. A last line without its newline is whole;
// nothing (a partial line, an over-long line being skipped) reaches the next datagram.
TEST(Decoder, EachDatagramIsDecodedAlone) {
  const std::string record = R"({"t":1714400000,"id":"A1","lat":50,"lon":8,"alt_ft":30000})";
  for (const Format format : {Format::Ndjson, Format::Auto}) {
    auto decoder = make_decoder(format);
    std::vector<TrackReport> reports;
    const ReportSink sink = [&](const TrackReport& r) { reports.push_back(r); };
    const auto datagram = [&](const std::string& text) {
      decoder->feed_text(text, sink);
      decoder->end_message(sink);
    };
    datagram(record);                        // without its newline: whole
    datagram(R"({"t":1714400001,"id":"B)");  // cut: bad, and not joined to what follows
    datagram(record + "\n");
    datagram(std::string(10000, 'x'));      // over-long: skipped, but only in its datagram
    datagram(record + "\n");
    EXPECT_EQ(reports.size(), 3u) << to_string(format);
    EXPECT_EQ(decoder->rejections().count("truncated"), 0u) << to_string(format);
    EXPECT_EQ(decoder->rejections().count("line_too_long"), format == Format::Ndjson ? 1u : 0u);
    EXPECT_EQ(decoder->rejections().total(), 2u) << decoder->rejections().by_reason().size();
  }
}

}  // namespace
}  // namespace kew::protocol
