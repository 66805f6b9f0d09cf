// Canonical NDJSON: decoder (design §5.1), writer, and the write → read round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "kew/protocol/ndjson.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::decode_all;

TEST(NdjsonDecoder, DecodesEveryMember) {
  auto decoder = make_ndjson_decoder();
  const auto reports = decode_all(
      *decoder,
      R"({"t":1714400000.25,"id":"4CA123","lat":51.47,"lon":-0.45,"alt_ft":35000,"gs_kt":450,)"
      R"("trk_deg":270.5,"vr_fpm":-64,"cs":"BAW123","src":"adsb","gnd":true,"sq":"7700",)"
      R"("addr":"4ca12F","coast":true,"end":true})"
      "\n");
  ASSERT_EQ(reports.size(), 1u);
  const TrackReport& r = reports[0];
  EXPECT_EQ(r.t, 1714400000.25);
  EXPECT_EQ(r.id, "4CA123");
  EXPECT_EQ(r.lat_deg, 51.47);
  EXPECT_EQ(r.lon_deg, -0.45);
  EXPECT_EQ(r.alt_ft, 35000.0);
  EXPECT_EQ(r.gs_kt, 450.0);
  EXPECT_EQ(r.trk_deg, 270.5);
  EXPECT_EQ(r.vr_fpm, -64.0);
  EXPECT_EQ(r.callsign, "BAW123");
  EXPECT_EQ(r.source, "adsb");
  EXPECT_TRUE(r.on_ground);
  EXPECT_EQ(r.mode3a, std::optional<std::uint16_t>(07700));
  EXPECT_EQ(r.address, std::optional<std::uint32_t>(0x4CA12F));  // hex digits of either case
  EXPECT_TRUE(r.coasting);
  EXPECT_TRUE(r.track_end);
  EXPECT_EQ(decoder->rejections().total(), 0u);
}

TEST(NdjsonDecoder, SelectedAltitudeItsSourceAndTrackAngleRate) {
  auto decoder = make_ndjson_decoder();
  const std::string head = R"({"t":1,"id":"A","lat":0,"lon":0,"alt_ft":100)";
  const auto reports = decode_all(
      *decoder, head + R"(,"sel_ft":24000,"sel_src":"fms","tar_dps":-2.5})" "\n" +
                    head + R"(,"sel_src":"fms","sel_ft":-1000})" "\n" +  // order does not matter
                    head + R"(,"sel_ft":35000})" "\n" +                 // source defaults to mcp
                    head + R"(,"sel_ft":35000,"sel_src":null,"tar_dps":null})" "\n" +
                    head + R"(,"sel_ft":null,"sel_src":"mcp","tar_dps":3})" "\n" +
                    head + R"(,"sel_ft":35000,"sel_src":"FMS"})" "\n" +    // bad_sel_src
                    head + R"(,"sel_ft":35000,"sel_src":2})" "\n" +        // wrong_type
                    head + R"(,"sel_ft":"35000"})" "\n" +                  // wrong_type
                    head + R"(,"tar_dps":true})" "\n");                    // wrong_type
  ASSERT_EQ(reports.size(), 5u);
  EXPECT_EQ(reports[0].sel_ft, 24000.0);
  EXPECT_EQ(reports[0].sel_src, SelectedAltitudeSource::Fms);
  EXPECT_EQ(reports[0].tar_dps, -2.5);
  EXPECT_EQ(reports[1].sel_ft, -1000.0);
  EXPECT_EQ(reports[1].sel_src, SelectedAltitudeSource::Fms);
  EXPECT_EQ(reports[2].sel_ft, 35000.0);
  EXPECT_EQ(reports[2].sel_src, SelectedAltitudeSource::Mcp);
  EXPECT_FALSE(reports[2].tar_dps);
  EXPECT_EQ(reports[3].sel_src, SelectedAltitudeSource::Mcp);
  EXPECT_FALSE(reports[3].tar_dps);
  EXPECT_FALSE(reports[4].sel_ft);
  EXPECT_EQ(reports[4].tar_dps, 3.0);
  EXPECT_EQ(decoder->rejections().by_reason(), (test::Counts{{"bad_sel_src", 1}, {"wrong_type", 3}}));
}

TEST(NdjsonDecoder, OptionalMembersAbsentOrNullAndUnknownKeysIgnored) {
  auto decoder = make_ndjson_decoder();
  const auto reports = decode_all(
      *decoder,
      "{\"t\":1,\"id\":\"A\",\"lat\":0,\"lon\":0,\"alt_ft\":100}\n"
      "{\"t\":2,\"id\":\"A\",\"lat\":0,\"lon\":0,\"alt_ft\":100,\"gs_kt\":null,\"cs\":null,"
      "\"extra\":{\"nested\":[1,2,{\"x\":\"y\"}]},\"gnd\":null,\"addr\":null,\"coast\":null,"
      "\"end\":false}\n");
  ASSERT_EQ(reports.size(), 2u);
  for (const TrackReport& r : reports) {
    EXPECT_FALSE(r.gs_kt);
    EXPECT_FALSE(r.trk_deg);
    EXPECT_FALSE(r.vr_fpm);
    EXPECT_FALSE(r.sel_ft);
    EXPECT_FALSE(r.tar_dps);
    EXPECT_FALSE(r.mode3a);
    EXPECT_EQ(r.callsign, "");
    EXPECT_EQ(r.source, "");
    EXPECT_FALSE(r.on_ground);
    EXPECT_FALSE(r.address);
    EXPECT_FALSE(r.coasting);
    EXPECT_FALSE(r.track_end);
  }
  EXPECT_EQ(decoder->rejections().total(), 0u);
}

TEST(NdjsonDecoder, CommentsBlankLinesCrlfAndMissingFinalNewline) {
  auto decoder = make_ndjson_decoder();
  const auto reports = decode_all(*decoder,
                                  "# a comment\r\n"
                                  "\r\n"
                                  "   \n"
                                  "  # indented comment\n"
                                  "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\r\n"
                                  "{\"t\":2,\"id\":\"B\",\"lat\":1,\"lon\":2,\"alt_ft\":3}");
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[1].id, "B");
  EXPECT_EQ(decoder->rejections().total(), 0u);
}

TEST(NdjsonDecoder, TrackAngleIsWrappedIntoZeroTo360) {
  auto decoder = make_ndjson_decoder();
  const auto reports =
      decode_all(*decoder,
                 "{\"t\":1,\"id\":\"A\",\"lat\":0,\"lon\":0,\"alt_ft\":0,\"trk_deg\":-90}\n"
                 "{\"t\":1,\"id\":\"A\",\"lat\":0,\"lon\":0,\"alt_ft\":0,\"trk_deg\":360}\n"
                 "{\"t\":1,\"id\":\"A\",\"lat\":0,\"lon\":0,\"alt_ft\":0,\"trk_deg\":-1e-17}\n");
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_EQ(reports[0].trk_deg, 270.0);
  EXPECT_EQ(reports[1].trk_deg, 0.0);
  EXPECT_EQ(reports[2].trk_deg, 0.0);
}

TEST(NdjsonDecoder, BadLinesAreCountedByReasonWithTheirLineNumberAndLaterLinesDecoded) {
  NdjsonOptions options;
  options.max_line_bytes = 200;
  auto decoder = make_ndjson_decoder(options);
  std::vector<std::string> messages;
  decoder->rejections().set_reporter(
      [&](std::string_view, std::string_view message) { messages.emplace_back(message); });
  const std::string good = "{\"t\":1,\"id\":\"OK\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\n";
  const std::string input =
      good +                                                                     // line 1
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2\n" +                            // 2 bad_json
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2}\n" +                           // 3 missing alt_ft
      "{\"t\":\"1\",\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\n" +          // 4 wrong_type
      "{\"t\":1,\"id\":7,\"lat\":1,\"lon\":2,\"alt_ft\":3}\n" +                  // 5 wrong_type
      "{\"t\":1,\"id\":\"A\",\"lat\":91,\"lon\":2,\"alt_ft\":3}\n" +             // 6 lat range
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":-180.5,\"alt_ft\":3}\n" +         // 7 lon range
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3,\"gs_kt\":-1}\n" + // 8 decoded
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3,\"sq\":\"7800\"}\n" +  // 9 bad sq
      "{\"t\":1,\"id\":\"\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\n" +               // 10 bad_id
      "{\"t\":1e999,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\n" +          // 11 bad_number
      std::string(300, 'x') + "\n" +                                             // 12 too long
      "[1,2,3]\n" +                                                              // 13 bad_json
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3} trailing\n" +     // 14 bad_json
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3,\"gnd\":1}\n" +    // 15 wrong_type
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":null}\n" +           // 16 wrong_type
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3,\"addr\":\"4CA12\"}\n" +  // 17 bad addr
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3,\"addr\":\"~4CA123\"}\n" +  // 18
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3,\"addr\":\" 4CA123\"}\n" +  // 19
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3,\"coast\":1}\n" +    // 20 wrong_type
      good +                                                                     // 21
      "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt";                         // 22 truncated
  const auto reports = decode_all(*decoder, input);
  ASSERT_EQ(reports.size(), 3u);
  // A bad optional field is the track table's to drop (design §4.3): the line is decoded.
  EXPECT_EQ(reports[1].gs_kt, -1.0);
  EXPECT_EQ(reports[2].id, "OK");
  const Rejections& r = decoder->rejections();
  EXPECT_EQ(r.by_reason(), (test::Counts{{"bad_address", 3}, {"bad_id", 1}, {"bad_json", 3},
                                          {"bad_mode3a", 1}, {"bad_number", 1},
                                          {"lat_out_of_range", 1},
                                          {"line_too_long", 1}, {"lon_out_of_range", 1},
                                          {"missing_field", 1}, {"truncated", 1},
                                          {"wrong_type", 5}}));
  ASSERT_EQ(messages.size(), 19u);
  EXPECT_NE(messages[0].find("line 2"), std::string::npos) << messages[0];
  EXPECT_NE(messages[1].find("line 3"), std::string::npos) << messages[1];
  EXPECT_NE(messages[1].find("alt_ft"), std::string::npos) << messages[1];
  EXPECT_NE(messages[9].find("line 12"), std::string::npos) << messages[9];
  EXPECT_NE(messages[14].find("line 17"), std::string::npos) << messages[14];
  EXPECT_NE(messages[14].find("addr"), std::string::npos) << messages[14];
  EXPECT_NE(messages[18].find("line 22"), std::string::npos) << messages[18];
}

TEST(NdjsonDecoder, OverlongLineSplitAcrossFeedsIsSkippedToItsNewline) {
  NdjsonOptions options;
  options.max_line_bytes = 64;
  auto decoder = make_ndjson_decoder(options);
  std::vector<TrackReport> reports;
  const ReportSink sink = [&](const TrackReport& r) { reports.push_back(r); };
  decoder->feed_text(std::string(40, ' ') + "{\"t\":1,", sink);
  decoder->feed_text(std::string(100, ' '), sink);
  decoder->feed_text("\"id\":\"X\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\n", sink);
  decoder->feed_text("{\"t\":1,\"id\":\"Y\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\n", sink);
  decoder->finish(sink);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].id, "Y");
  EXPECT_EQ(decoder->rejections().count("line_too_long"), 1u);
  EXPECT_EQ(decoder->rejections().total(), 1u);
  EXPECT_EQ(decoder->max_message_bytes(), 64u);
}

TEST(NdjsonDecoder, BundledCanonicalSample) {
  auto decoder = make_ndjson_decoder();
  const auto reports = decode_all(*decoder, test::read_file(test::bundled_path("canonical_sample.ndjson")));
  ASSERT_EQ(reports.size(), 16u);
  EXPECT_EQ(decoder->rejections().total(), 0u);
  const auto summary = test::summarize(reports);
  EXPECT_EQ(summary.ids, (std::set<std::string>{"4CA123", "406B2E", "3C6DC5", "43EAF1"}));
  EXPECT_EQ(summary.t_min, 1714400000.0);
  EXPECT_EQ(summary.t_max, 1714400016.5);
  EXPECT_EQ(reports[1].mode3a, std::optional<std::uint16_t>(05211));
  EXPECT_EQ(reports[1].callsign, "EZY45AB");
  EXPECT_EQ(reports[15].on_ground, true);
  EXPECT_EQ(reports[15].alt_ft, 83.0);
}

TEST(NdjsonDecoder, IsIncremental) {
  std::string input = test::read_file(test::bundled_path("canonical_sample.ndjson"));
  input += "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2\r\n";  // one bad line in the mix
  input += std::string(5000, 'z') + "\n";
  input += "{\"t\":3,\"id\":\"Z\",\"lat\":1,\"lon\":2,\"alt_ft\":3}";  // no final newline
  test::expect_incremental([] { return make_ndjson_decoder(); }, input);
}

TEST(NdjsonWriter, WritesShortestRoundTripNumbersAndOnlyPresentMembers) {
  TrackReport r;
  r.t = 1714400000.25;
  r.id = "4CA123";
  r.lat_deg = 51.47;
  r.lon_deg = -0.45;
  r.alt_ft = 35000;
  EXPECT_EQ(to_ndjson_line(r),
            "{\"t\":1714400000.25,\"id\":\"4CA123\",\"lat\":51.47,\"lon\":-0.45,\"alt_ft\":35000}\n");
  r.gs_kt = 450;
  r.trk_deg = 0.1;
  r.vr_fpm = -1e-7;
  r.callsign = "BAW123";
  r.source = "sbs";
  r.on_ground = true;
  r.mode3a = 0;
  r.address = 0x00ABCF;
  r.coasting = true;
  r.track_end = true;
  std::string line;
  append_ndjson(line, r);
  EXPECT_EQ(line,
            "{\"t\":1714400000.25,\"id\":\"4CA123\",\"lat\":51.47,\"lon\":-0.45,\"alt_ft\":35000,"
            "\"gs_kt\":450,\"trk_deg\":0.1,\"vr_fpm\":-1e-07,\"cs\":\"BAW123\",\"src\":\"sbs\","
            "\"gnd\":true,\"sq\":\"0000\",\"addr\":\"00ABCF\",\"coast\":true,\"end\":true}");
}

TEST(NdjsonWriter, SelectedAltitudeIsWrittenWithItsSourceAndTrackAngleRateWhenPresent) {
  TrackReport r;
  r.t = 10;
  r.id = "A";
  r.sel_src = SelectedAltitudeSource::Fms;  // without sel_ft: not written
  r.tar_dps = -1.5;
  EXPECT_EQ(to_ndjson_line(r),
            "{\"t\":10,\"id\":\"A\",\"lat\":0,\"lon\":0,\"alt_ft\":0,\"tar_dps\":-1.5}\n");
  r.sel_ft = 24000;
  r.tar_dps.reset();
  EXPECT_EQ(to_ndjson_line(r), "{\"t\":10,\"id\":\"A\",\"lat\":0,\"lon\":0,\"alt_ft\":0,"
                               "\"sel_ft\":24000,\"sel_src\":\"fms\"}\n");
  r.sel_src = SelectedAltitudeSource::Mcp;
  EXPECT_NE(to_ndjson_line(r).find("\"sel_ft\":24000,\"sel_src\":\"mcp\""), std::string::npos);
}

TEST(NdjsonWriter, EscapesStringsAndReplacesInvalidUtf8) {
  std::string out;
  append_json_string(out, std::string("a\"b\\c\n\t\x01\x1f\x7f", 10));
  EXPECT_EQ(out, "\"a\\\"b\\\\c\\n\\t\\u0001\\u001f\x7f\"");
  out.clear();
  append_json_string(out, "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x9B\xAB");  // é € 🛫 kept
  EXPECT_EQ(out, "\"caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x9B\xAB\"");
  out.clear();
  // A lone continuation byte, an overlong '/', a surrogate, a cut sequence.
  append_json_string(out, "\x80|\xC0\xAF|\xED\xA0\x80|\xE2\x82");
  EXPECT_EQ(out, "\"\\ufffd|\\ufffd\\ufffd|\\ufffd\\ufffd\\ufffd|\\ufffd\\ufffd\"");
}

TEST(NdjsonWriter, NonFiniteNumbersAreWrittenNullAndRefusedOnReading) {
  TrackReport r;
  r.t = 1;
  r.id = "A";
  r.alt_ft = std::numeric_limits<double>::quiet_NaN();
  const std::string line = to_ndjson_line(r);
  EXPECT_NE(line.find("\"alt_ft\":null"), std::string::npos);
  auto decoder = make_ndjson_decoder();
  EXPECT_TRUE(decode_all(*decoder, line).empty());
  EXPECT_EQ(decoder->rejections().count("wrong_type"), 1u);
}

// Strings with the characters writers get wrong: quotes, backslashes, every control
// character, multi-byte UTF-8 (2, 3 and 4 bytes), and the JSON-significant ASCII.
std::string random_text(std::mt19937_64& random, std::size_t max_length) {
  static const std::vector<std::string> kPieces = {
      "\"", "\\", "/", "\b", "\f", "\n", "\r", "\t", std::string(1, '\0'), "\x01", "\x1f",
      "\x7f", "A", "z", "0", " ", "{", "}", "[", "]", ":", ",", "\xC3\xA9", "\xC2\x80",
      "\xDF\xBF", "\xE2\x82\xAC", "\xEF\xBF\xBF", "\xE0\xA0\x80", "\xF0\x90\x80\x80",
      "\xF4\x8F\xBF\xBF", "\\u0000", "\\\""};
  std::string text;
  const std::size_t length = random() % (max_length + 1);
  for (std::size_t i = 0; i < length; ++i) text += kPieces[random() % kPieces.size()];
  return text;
}

double random_double(std::mt19937_64& random, double lo, double hi) {
  switch (random() % 8) {
    case 0: return lo;
    case 1: return hi;
    case 2: return 0.0;
    case 3: return -0.0;
    case 4: {  // a random bit pattern in range: every digit of the mantissa matters
      double v = std::uniform_real_distribution<double>(lo, hi)(random);
      return std::nextafter(v, hi);
    }
    case 5:  // subnormals
      return std::ldexp(static_cast<double>(random() % 1000), -1074 + static_cast<int>(random() % 3));
    default: return std::uniform_real_distribution<double>(lo, hi)(random);
  }
}

TEST(NdjsonRoundTrip, RandomReportsReadBackEqual) {
  std::mt19937_64 random(0x6b6577);
  std::string stream;
  std::vector<TrackReport> written;
  for (int i = 0; i < 5000; ++i) {
    TrackReport r;
    r.t = random_double(random, -1e10, 4e9);
    do {
      r.id = random_text(random, 12);
    } while (r.id.empty());
    r.source = random_text(random, 6);
    if (random() % 2) r.position_source = random_text(random, 10);
    r.callsign = random_text(random, 10);
    r.lat_deg = random_double(random, -90, 90);
    r.lon_deg = random_double(random, -180, 180);
    r.alt_ft = random_double(random, -1500, 1e6);
    if (random() % 2) r.gs_kt = random_double(random, 0, 1e4);
    if (random() % 2) r.trk_deg = std::min(random_double(random, 0, 360), std::nextafter(360.0, 0.0));
    if (random() % 2) r.vr_fpm = random_double(random, -1e5, 1e5);
    if (random() % 2) {
      r.sel_ft = random_double(random, -1300, 1e5);
      r.sel_src = random() % 2 ? SelectedAltitudeSource::Fms : SelectedAltitudeSource::Mcp;
    }
    if (random() % 2) r.tar_dps = random_double(random, -30, 30);
    if (random() % 2) r.mode3a = static_cast<std::uint16_t>(random() % 010000);
    r.on_ground = random() % 2 == 0;
    if (random() % 2) r.address = static_cast<std::uint32_t>(random() & 0xFFFFFF);
    r.coasting = random() % 2 == 0;
    r.track_end = random() % 2 == 0;
    append_ndjson(stream, r);
    stream += '\n';
    written.push_back(r);
  }
  auto decoder = make_ndjson_decoder();
  const auto read = decode_all(*decoder, stream);
  EXPECT_EQ(decoder->rejections().total(), 0u) << decoder->rejections().by_reason().begin()->first;
  test::expect_same_reports(written, read);
}

TEST(NdjsonRoundTrip, InvalidUtf8IsReplacedNotLost) {
  TrackReport r;
  r.t = 5;
  r.id = "AB\xFF";
  r.callsign = "X\xC3";
  auto decoder = make_ndjson_decoder();
  const auto read = decode_all(*decoder, to_ndjson_line(r));
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].id, "AB\xEF\xBF\xBD");
  EXPECT_EQ(read[0].callsign, "X\xEF\xBF\xBD");
}

}  // namespace
}  // namespace kew::protocol
