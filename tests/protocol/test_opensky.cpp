// OpenSky state vectors: CSV (historical "states" files) and the traffic library's JSON
// (recordings/traffic-opensky; expected values from python3, see tests/data/text/SOURCE.md).
#include <gtest/gtest.h>

#include "kew/protocol/gzip.hpp"
#include "kew/protocol/opensky.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::decode_all;

const std::string kHeader =
    "time,icao24,lat,lon,velocity,heading,vertrate,callsign,onground,alert,spi,squawk,"
    "baroaltitude,geoaltitude,lastposupdate,lastcontact\n";

TEST(OpenskyCsvDecoder, BundledSampleConvertsUnitsAndPrefersTheRightColumns) {
  auto decoder = make_opensky_csv_decoder();
  const auto reports = decode_all(*decoder, test::read_file(test::bundled_path("opensky_states_sample.csv")));
  ASSERT_EQ(reports.size(), 4u);
  EXPECT_EQ(decoder->rejections().count("no_altitude"), 1u);  // 3c6dc5: both altitudes empty
  EXPECT_EQ(decoder->rejections().count("no_position"), 1u);  // a0d724: no lat/lon
  EXPECT_EQ(decoder->rejections().total(), 2u);

  const TrackReport& baw = reports[0];
  EXPECT_EQ(baw.id, "4CA7B4");
  EXPECT_EQ(baw.address, std::optional<std::uint32_t>(0x4CA7B4));
  EXPECT_EQ(baw.source, "opensky");
  EXPECT_EQ(baw.t, 1590364799.25);  // lastposupdate, not time
  EXPECT_EQ(baw.lat_deg, 51.47);
  EXPECT_EQ(baw.lon_deg, -0.45);
  EXPECT_EQ(baw.alt_ft, 35000.0);  // 10668 m
  EXPECT_EQ(baw.gs_kt, 450.0);     // 231.5 m/s
  EXPECT_EQ(baw.trk_deg, 270.0);
  EXPECT_EQ(baw.vr_fpm, 0.0);
  EXPECT_EQ(baw.callsign, "BAW123");
  EXPECT_EQ(baw.mode3a, std::optional<std::uint16_t>(01000));
  EXPECT_FALSE(baw.on_ground);

  const TrackReport& ezy = reports[1];
  EXPECT_EQ(ezy.id, "406B2E");
  EXPECT_EQ(ezy.t, 1590364800.0);  // lastposupdate empty: time
  EXPECT_EQ(ezy.alt_ft, 12000.0);
  EXPECT_EQ(ezy.vr_fpm, 9.14 * 60.0 / 0.3048);
  EXPECT_EQ(ezy.callsign, "EZY45AB");  // quoted, trailing blank trimmed

  EXPECT_EQ(reports[2].alt_ft, 10972.8 / 0.3048);  // baroaltitude empty: geoaltitude
  EXPECT_EQ(reports[3].alt_ft, 3694.2 / 0.3048);
}

TEST(OpenskyCsvDecoder, ColumnsAreFoundByNameInAnyOrder) {
  auto decoder = make_opensky_csv_decoder();
  const auto reports = decode_all(*decoder,
                                  "geoaltitude,lon,icao24,extra,lat,time,onground\n"
                                  "100,2.5,00abcd,whatever,45.5,1000,TRUE\n");
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].id, "00ABCD");
  EXPECT_EQ(reports[0].address, std::optional<std::uint32_t>(0x00ABCD));
  EXPECT_EQ(reports[0].lat_deg, 45.5);
  EXPECT_EQ(reports[0].lon_deg, 2.5);
  EXPECT_EQ(reports[0].alt_ft, 100 / 0.3048);
  EXPECT_EQ(reports[0].t, 1000.0);
  EXPECT_TRUE(reports[0].on_ground);
  EXPECT_FALSE(reports[0].gs_kt);
}

TEST(OpenskyCsvDecoder, HeaderIsRequiredAndBadRowsAreCountedByReason) {
  auto decoder = make_opensky_csv_decoder();
  const std::string good = "1,4ca7b4,51,0,1,2,3,CS,False,False,False,1000,100,110,,\n";
  const std::string input =
      good +                                                       // no_header
      "time,icao24,lat,lon\n" +                                    // bad_header (no altitude)
      good +                                                       // no_header
      kHeader + good +                                             // header, report
      "1,4ca7b4,51,0\n" +                                          // malformed_line (4 fields)
      "1,4ca7b4,51,0,1,2,3,\"CS,False,False,False,1000,100,110,,\n" +  // unclosed quote
      "1,4ca7bz,51,0,1,2,3,CS,False,False,False,1000,100,110,,\n" +    // bad_address
      "x,4ca7b4,51,0,1,2,3,CS,False,False,False,1000,100,110,,\n" +    // bad_number
      "1,4ca7b4,51,0,1,2,3,CS,maybe,False,False,1000,100,110,,\n" +    // bad_value
      "1,4ca7b4,51,0,1,2,3,CS,False,False,False,8000,100,110,,\n" +    // bad_mode3a
      "1,4ca7b4,-91,0,1,2,3,CS,False,False,False,1000,100,110,,\n" +   // lat range
      "1,4ca7b4,51,0,-1,2,3,CS,False,False,False,1000,100,110,,\n" +   // decoded: gs for the track table
      ",4ca7b4,51,0,1,2,3,CS,False,False,False,1000,100,110,,\n" +     // missing time
      kHeader + good;                                              // a repeated header is fine
  const auto reports = decode_all(*decoder, input);
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_LT(*reports[1].gs_kt, 0.0);
  const Rejections& r = decoder->rejections();
  EXPECT_EQ(r.by_reason(), (test::Counts{{"bad_address", 1}, {"bad_header", 1}, {"bad_mode3a", 1},
                                          {"bad_number", 1}, {"bad_value", 1},
                                          {"lat_out_of_range", 1},
                                          {"malformed_line", 2}, {"missing_field", 1},
                                          {"no_header", 2}}));
}

TEST(OpenskyCsvDecoder, HeaderIsForgottenAtEndOfStream) {
  auto decoder = make_opensky_csv_decoder();
  const std::string row = "1,4ca7b4,51,0,1,2,3,CS,False,False,False,1000,100,110,,\n";
  EXPECT_EQ(decode_all(*decoder, kHeader + row).size(), 1u);
  EXPECT_EQ(decode_all(*decoder, row).size(), 0u);
  EXPECT_EQ(decoder->rejections().count("no_header"), 1u);
}

TEST(OpenskyCsvDecoder, IsIncremental) {
  std::string input = test::read_file(test::bundled_path("opensky_states_sample.csv"));
  input += "1,4ca7b4,51,0,1,2,3,\"quoted \"\"callsign\"\"\",False,False,False,1000,100,110,,\n";
  input += "1,4ca7b4,51,0,1,2,3,CS,False,False,False,1000,100,110,,";
  test::expect_incremental([] { return make_opensky_csv_decoder(); }, input);
}

TEST(OpenskyJsonDecoder, MapsMembersAndTimestampUnits) {
  auto decoder = make_opensky_json_decoder();
  const auto reports = decode_all(
      *decoder,
      R"([{"timestamp":1533101250000,"altitude":34975.0,"callsign":"DLH8JW","groundspeed":443.4869334744,)"
      R"("icao24":"3003ae","latitude":45.8189849854,"longitude":9.2295455933,"track":324.2670817753,)"
      R"("vertical_rate":960.0},)"
      "\n  "
      R"({"timestamp":1717664319.5,"icao24":"3461ce","latitude":43.6,"longitude":1.37,"geoaltitude":1200,)"
      R"("onground":true,"squawk":"7000","callsign":null,"frame":"8c3461ce"}])");
  ASSERT_EQ(reports.size(), 2u);
  const TrackReport& a = reports[0];
  EXPECT_EQ(a.t, 1533101250.0);  // milliseconds
  EXPECT_EQ(a.id, "3003AE");
  EXPECT_EQ(a.address, std::optional<std::uint32_t>(0x3003AE));
  EXPECT_EQ(a.source, "opensky");
  EXPECT_EQ(a.lat_deg, 45.8189849854);
  EXPECT_EQ(a.lon_deg, 9.2295455933);
  EXPECT_EQ(a.alt_ft, 34975.0);
  EXPECT_EQ(a.gs_kt, 443.4869334744);
  EXPECT_EQ(a.trk_deg, 324.2670817753);
  EXPECT_EQ(a.vr_fpm, 960.0);
  EXPECT_EQ(a.callsign, "DLH8JW");
  const TrackReport& b = reports[1];
  EXPECT_EQ(b.t, 1717664319.5);  // seconds
  EXPECT_EQ(b.alt_ft, 1200.0);
  EXPECT_TRUE(b.on_ground);
  EXPECT_EQ(b.mode3a, std::optional<std::uint16_t>(07000));
  EXPECT_EQ(b.address, std::optional<std::uint32_t>(0x3461CE));
  EXPECT_EQ(b.callsign, "");
  EXPECT_EQ(decoder->rejections().total(), 0u);
}

TEST(OpenskyJsonDecoder, BadElementsAreCountedAndScanningResumes) {
  OpenskyJsonOptions options;
  options.max_object_bytes = 256;
  auto decoder = make_opensky_json_decoder(options);
  std::vector<std::string> messages;
  decoder->rejections().set_reporter(
      [&](std::string_view, std::string_view message) { messages.emplace_back(message); });
  const std::string good = R"({"timestamp":1000,"icao24":"abcdef","latitude":1,"longitude":2,"altitude":3})";
  const std::string input =
      "[" + good + ",\n" +
      R"({"timestamp":1000,"icao24":"abcdef","latitude":1,"longitude":2},)" +       // no_altitude
      R"({"timestamp":1000,"icao24":"abcdef","altitude":3},)" +                     // no_position
      R"({"icao24":"abcdef","latitude":1,"longitude":2,"altitude":3},)" +           // missing
      R"({"timestamp":1000,"icao24":"abcdeff","latitude":1,"longitude":2,"altitude":3},)" +  // address
      R"({"timestamp":1000,"icao24":"abcdef","latitude":1,"longitude":2,"altitude":"3"},)" +  // type
      R"({"timestamp":1000,"icao24":"abcdef","latitude":1,"longitude":2,"altitude":3,}, )" +  // json
      "garbage here, " +                                                         // bad_json once
      R"({"timestamp":1000,"icao24":"a{b}c\"[","latitude":1,"longitude":2,"altitude":3},)" +  // address
      R"({"timestamp":1000,"pad":")" + std::string(400, 'p') + R"(","icao24":"abcdef"},)" +  // too long
      good + "," + good + "]\n" + good + "\n" + "{\"timestamp\":1000,";          // truncated
  const auto reports = decode_all(*decoder, input);
  EXPECT_EQ(reports.size(), 4u);
  const Rejections& r = decoder->rejections();
  EXPECT_EQ(r.by_reason(), (test::Counts{{"bad_address", 2}, {"bad_json", 2},
                                          {"missing_field", 1}, {"no_altitude", 1},
                                          {"no_position", 1}, {"object_too_long", 1},
                                          {"truncated", 1}, {"wrong_type", 1}}));
  ASSERT_EQ(messages.size(), 10u);
  EXPECT_NE(messages[0].find("element 2"), std::string::npos) << messages[0];
}

TEST(OpenskyJsonDecoder, BundledSwitzerlandExcerptGolden) {
  // Two gzip members, the second starting inside element 1001.
  auto decoder = make_gzip_decoder(make_opensky_json_decoder());
  const auto reports = decode_all(
      *decoder, test::read_file(test::bundled_path("opensky_switzerland_first2000.json.gz")));
  const auto summary = test::summarize(reports);
  EXPECT_EQ(summary.count, 2000u);
  EXPECT_EQ(summary.ids.size(), 14u);
  EXPECT_EQ(summary.ids.count("3003AE"), 1u);
  EXPECT_EQ(summary.ids.count("02A18F"), 1u);
  EXPECT_EQ(summary.t_min, 1533101040.0);
  EXPECT_EQ(summary.t_max, 1533152170.0);
  EXPECT_EQ(decoder->rejections().total(), 0u);

  EXPECT_EQ(reports[0].id, "3003AE");
  EXPECT_EQ(reports[0].t, 1533101250.0);  // 2018-08-01 05:27:30 UTC
  EXPECT_EQ(reports[0].callsign, "DLH8JW");
  EXPECT_EQ(reports[0].lat_deg, 45.8189849854);
  EXPECT_EQ(reports[0].gs_kt, 443.4869334744);
  EXPECT_EQ(reports[999].id, "342086");
  EXPECT_EQ(reports[999].t, 1533136630.0);
  EXPECT_EQ(reports[999].alt_ft, 35000.0);
  EXPECT_EQ(reports[1000].callsign, "PVG7344");
  EXPECT_EQ(reports[1000].lat_deg, 47.3953399658);  // the element cut by the member boundary
  EXPECT_EQ(reports[1000].lon_deg, 7.0913314819);
  EXPECT_EQ(reports[1000].gs_kt, 413.2066129493);
  EXPECT_EQ(reports[1000].trk_deg, 233.4628911356);
  EXPECT_EQ(reports.back().id, "345314");
  EXPECT_EQ(reports.back().callsign, "VLG67MT");
  EXPECT_EQ(reports.back().vr_fpm, -64.0);
  EXPECT_EQ(reports.back().alt_ft, 34975.0);
}

TEST(OpenskyJsonDecoder, IsIncremental) {
  std::string input = R"([{"timestamp":1000,"icao24":"abcdef","latitude":1,"longitude":2,"altitude":3,)"
                      R"("callsign":"}{\"]["},)";
  for (int i = 0; i < 200; ++i)
    input += R"( {"timestamp":)" + std::to_string(1000 + i) +
             R"(,"icao24":"abcdef","latitude":1.5,"longitude":2,"altitude":3,"x":[{"y":"]"}]},)";
  input += R"(oops {"timestamp":1000,"icao24":"abcdef","latitude":1,"longitude":2,"altitude":3}])";
  test::expect_incremental([] { return make_opensky_json_decoder(); }, input);
}

TEST(OpenskyJsonDecoder, IsIncrementalThroughGzip) {
  const std::string compressed =
      test::read_file(test::bundled_path("opensky_switzerland_first2000.json.gz"));
  test::expect_incremental([] { return make_gzip_decoder(make_opensky_json_decoder()); }, compressed);
}

TEST(OpenskyJsonDecoder, SharedSwitzerlandWhole) {
  const std::string path = test::shared_path("traffic-opensky/switzerland.json.gz");
  if (!test::exists(path)) GTEST_SKIP() << "shared recordings absent: " << path;
  auto decoder = make_gzip_decoder(make_opensky_json_decoder());
  const auto reports = decode_all(*decoder, test::read_file(path));
  const auto summary = test::summarize(reports);
  // MANIFEST: 139,098 rows, 842 icao24, 2018-08-01 05:00–22:00 UTC.
  EXPECT_EQ(summary.count, 139098u);
  EXPECT_EQ(summary.ids.size(), 842u);
  EXPECT_EQ(summary.t_min, 1533099600.0);
  EXPECT_EQ(summary.t_max, 1533160790.0);
  EXPECT_EQ(decoder->rejections().total(), 0u);
  EXPECT_EQ(reports.back().id, "C078B1");
  EXPECT_EQ(reports.back().callsign, "TSC300");
  EXPECT_EQ(reports.back().lon_deg, 10.467576247);
  EXPECT_EQ(reports.back().trk_deg, 101.6611486277);
}

}  // namespace
}  // namespace kew::protocol
