// OpenSky REST API responses (opensky_rest.hpp): every field of a state vector, its nulls
// and units, short vectors and the API's first layout, one record per fresh position
// across responses, the age limit, refusals, gzip, detection, and the decoder contract
// (split anywhere, the same records).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "kew/protocol/formats.hpp"
#include "kew/protocol/opensky_rest.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::bytes_of;
using test::decode_all;

std::vector<TrackReport> decode(std::string_view text, Rejections* rejections = nullptr,
                                const AircraftJsonOptions& options = {}) {
  return test::decode_counted(*make_opensky_rest_decoder(options), text, rejections);
}

/// A response at `time` holding `states` (the text of the array's elements).
std::string response(long time, std::string_view states) {
  return "{\"time\":" + std::to_string(time) + ",\"states\":[" + std::string(states) + "]}\n";
}

// The example of the API's documentation, with every field set.
constexpr std::string_view kFull =
    R"(["3c6444","DLH9LF  ","Germany",1458564120,1458564121,6.1546,50.1964,9639.3,false,232.88,98.26,4.55,null,9547.86,"1000",false,0])";

TEST(OpenskyRest, ReadsEveryFieldInKewsUnits) {
  Rejections rejections;
  const std::vector<TrackReport> r = decode(response(1458564121, kFull), &rejections);
  EXPECT_EQ(rejections.total(), 0u) << rejections.last_reason();
  ASSERT_EQ(r.size(), 1u);
  const TrackReport& a = r[0];
  EXPECT_EQ(a.source, "opensky");
  EXPECT_EQ(a.id, "3C6444");
  EXPECT_EQ(a.address, 0x3c6444u);
  EXPECT_EQ(a.t, 1458564120.0) << "time_position, not last_contact nor the response's time";
  EXPECT_EQ(a.lat_deg, 50.1964) << "latitude is field 6, longitude field 5";
  EXPECT_EQ(a.lon_deg, 6.1546);
  // By the defining constants: 1 ft = 0.3048 m, 1 kt = 1852 m / 3600 s.
  EXPECT_DOUBLE_EQ(a.alt_ft, 9639.3 / 0.3048) << "baro_altitude before geo_altitude";
  EXPECT_NEAR(a.alt_ft, 31625.0, 0.1);
  EXPECT_DOUBLE_EQ(*a.gs_kt, 232.88 * 3600.0 / 1852.0);
  EXPECT_NEAR(*a.gs_kt, 452.68, 0.01);
  EXPECT_EQ(a.trk_deg, 98.26);
  EXPECT_DOUBLE_EQ(*a.vr_fpm, 4.55 * 60.0 / 0.3048);
  EXPECT_NEAR(*a.vr_fpm, 895.67, 0.01);
  EXPECT_EQ(a.callsign, "DLH9LF") << "the 8-character callsign trimmed";
  EXPECT_EQ(a.mode3a, 01000);
  EXPECT_FALSE(a.on_ground);
  EXPECT_EQ(a.position_source, "adsb");
  EXPECT_FALSE(a.sel_ft);
}

TEST(OpenskyRest, NullsMeanAbsentAndTheGroundNeedsNoAltitude) {
  const std::string states =
      // geo_altitude when baro_altitude is null; no callsign, speed, track, rate, squawk, source
      R"(["000001",null,"X",1700000000,1700000000,1.0,2.0,null,false,null,null,null,null,1000.0,null,false,null],)"
      // on the ground without either altitude: 0 ft
      R"(["000002","GND1    ","X",1700000001,1700000001,1.0,2.0,null,true,5.0,90.0,null,null,null,null,false,0],)"
      // in the air without either: refused
      R"(["000003","AIR1    ","X",1700000002,1700000002,1.0,2.0,null,false,5.0,90.0,null,null,null,null,false,0],)"
      // no position: no record, no refusal
      R"(["000004","NOPOS   ","X",null,1700000002,null,null,null,false,null,null,null,null,null,"7000",false,0],)"
      R"(["000005","NOLAT   ","X",1700000002,1700000002,1.0,null,100.0,false,null,null,null,null,null,"7000",false,0],)"
      // on the ground with a barometric altitude: kept
      R"(["000006",null,"X",1700000003,1700000003,1.0,2.0,30.48,true,null,null,null,null,null,null,false,0])";
  Rejections rejections;
  const std::vector<TrackReport> r = decode(response(1700000003, states), &rejections);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(rejections.total(), 1u);
  EXPECT_EQ(rejections.count("no_altitude"), 1u);
  EXPECT_EQ(r[0].id, "000001");
  EXPECT_DOUBLE_EQ(r[0].alt_ft, 1000.0 / 0.3048);
  EXPECT_EQ(r[0].callsign, "");
  EXPECT_FALSE(r[0].gs_kt);
  EXPECT_FALSE(r[0].trk_deg);
  EXPECT_FALSE(r[0].vr_fpm);
  EXPECT_FALSE(r[0].mode3a);
  EXPECT_EQ(r[0].position_source, "");
  EXPECT_EQ(r[1].id, "000002");
  EXPECT_TRUE(r[1].on_ground);
  EXPECT_EQ(r[1].alt_ft, 0.0);
  EXPECT_EQ(r[2].id, "000006");
  EXPECT_TRUE(r[2].on_ground);
  EXPECT_DOUBLE_EQ(r[2].alt_ft, 100.0);
}

TEST(OpenskyRest, ShortVectorsThePositionSourcesAndTheFirstLayout) {
  const std::string states =
      R"(["00000a",null,"X",1700000000,1700000000,1.0,2.0,100.0,false],)"                  // up to on_ground
      R"(["00000b",null,"X",1700000000,1700000000,1.0,2.0,100.0,false,1,2,3,null,4,"7700"],)"  // up to squawk
      R"(["00000c",null,"X",1700000000,1700000000,1.0,2.0,100.0,false,null,null,null,null,null,null,false,1],)"
      R"(["00000d",null,"X",1700000000,1700000000,1.0,2.0,100.0,false,null,null,null,null,null,null,false,2,4],)"
      R"(["00000e",null,"X",1700000000,1700000000,1.0,2.0,100.0,false,null,null,null,null,null,null,false,3],)"
      R"(["00000f",null,"X",1700000000,1700000000,1.0,2.0,100.0,false,null,null,null,null,null,null,false,9],)"
      // the first layout: alert at 15, spi at 16, position_source at 17
      R"(["000010",null,"X",1700000000,1700000000,1.0,2.0,100.0,false,null,null,null,null,null,null,false,false,2],)"
      R"(["000011",null,"X",1700000000,1700000000,1.0,2.0,100.0])";  // without on_ground
  Rejections rejections;
  const std::vector<TrackReport> r = decode(response(1700000000, states), &rejections);
  EXPECT_EQ(rejections.count("missing_field"), 1u) << "fields 0 to 8 are needed";
  EXPECT_EQ(rejections.total(), 1u);
  ASSERT_EQ(r.size(), 7u);
  EXPECT_EQ(r[0].position_source, "");
  EXPECT_EQ(r[1].mode3a, 07700);
  EXPECT_DOUBLE_EQ(*r[1].gs_kt, 3600.0 / 1852.0);
  EXPECT_EQ(r[1].trk_deg, 2.0);
  EXPECT_DOUBLE_EQ(*r[1].vr_fpm, 3 * 60.0 / 0.3048);
  EXPECT_EQ(r[2].position_source, "asterix");
  EXPECT_EQ(r[3].position_source, "mlat") << "category (17) is not read";
  EXPECT_EQ(r[4].position_source, "flarm");
  EXPECT_EQ(r[5].position_source, "9") << "an unknown source is kept as its number";
  EXPECT_EQ(r[6].position_source, "mlat") << "the first layout's position_source";
}

TEST(OpenskyRest, APositionIsReportedOnceHoweverManyResponsesShowIt) {
  // A poll every 5 s; the position is updated at 1700000000 and 1700000012.
  std::string stream;
  for (int i = 0; i < 5; ++i) {
    const long time = 1700000000 + 5 * i;
    const long position = time < 1700000012 ? 1700000000 : 1700000012;
    stream += response(time, R"(["3c6444","DLH9LF  ","Germany",)" + std::to_string(position) + "," +
                                 std::to_string(time) + ",6.0,50.0,9000.0,false,200.0,90.0,0.0,null,9100.0,\"1000\",false,0]");
  }
  const std::vector<TrackReport> r = decode(stream);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].t, 1700000000.0);
  EXPECT_EQ(r[1].t, 1700000012.0);
}

TEST(OpenskyRest, OneResponseADatagramRemembersWhatWasReportedUntilTheStreamEnds) {
  const std::string first = response(1700000001, R"(["3c6444",null,"X",1700000000,0,1,1,1,false])");
  const std::string older = response(1700000002, R"(["3c6444",null,"X",1699999999,0,1,1,1,false])");
  auto decoder = make_opensky_rest_decoder();
  // Each one poll.
  EXPECT_EQ(test::reports_of_messages(*decoder, {first, first, older}, true), 1u)
      << "the same or an older time_position is not reported again";
  EXPECT_EQ(test::reports_of_messages(*decoder, {first}, true), 1u) << "after the end of the stream the decoder is as new";
}

TEST(OpenskyRest, PositionsOlderThanTheLimitAreNotReportedAndEachResponseIsInDataOrder) {
  const std::string states = R"(["000001",null,"X",1699999991,0,1,1,1,false],)"   // 9 s old
                             R"(["000002",null,"X",1699999989,0,1,1,1,false],)"   // 11 s old
                             R"(["000003",null,"X",1699999995,0,1,1,1,false],)"   // 5 s old
                             R"(["000004",null,"X",1700000001,0,1,1,1,false])";   // after the response's time
  const std::vector<TrackReport> r = decode(response(1700000000, states));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].id, "000001") << "data-time order, not the response's order";
  EXPECT_EQ(r[1].id, "000003");
  AircraftJsonOptions options;
  options.max_position_age_s = 30.0;
  EXPECT_EQ(decode(response(1700000000, states), nullptr, options).size(), 3u);
}

TEST(OpenskyRest, AnEmptyOrNullStatesIsNoRecordAndNoRefusal) {
  Rejections rejections;
  EXPECT_TRUE(decode("{\"time\":1700000000,\"states\":null}\n{\"time\":1700000001,\"states\":[]}", &rejections).empty());
  EXPECT_EQ(rejections.total(), 0u);
}

TEST(OpenskyRest, BadInputIsCountedAndTheRestDecoded) {
  const std::string text =
      response(1700000000, R"(7,["xyz",null,"X",1700000000,0,1,1,1,false],)"
                           R"(["000005",null,"X",1700000000,0,1,91,1,false],)"
                           R"(["000006",null,"X",1700000000,0,1,1,1,false,"fast"],)"
                           R"(["000007",null,"X",1700000000,0,1,1,1,false,null,null,null,null,null,"7778"],)"
                           R"(["000008",null,"X",1700000000,0,1,1,1,false])") +
      "garbage\n" + R"({"states":[]})" + R"({"time":1700000001,"states":{}})" + R"({"time":1700000002})" +
      response(1700000003, R"(["000009",null,"X",1700000003,0,1,1,1,false])") + R"({"time":1700000004,"states":[[)";
  Rejections rejections;
  const std::vector<TrackReport> r = decode(text, &rejections);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].id, "000008");
  EXPECT_EQ(r[1].id, "000009");
  EXPECT_EQ(rejections.count("wrong_type"), 3u) << "a vector not an array, a speed not a number, states an object";
  EXPECT_EQ(rejections.count("bad_address"), 1u);
  EXPECT_EQ(rejections.count("lat_out_of_range"), 1u);
  EXPECT_EQ(rejections.count("bad_mode3a"), 1u);
  EXPECT_EQ(rejections.count("bad_json"), 1u) << "the garbage";
  EXPECT_EQ(rejections.count("missing_field"), 2u) << "no time; no states";
  EXPECT_EQ(rejections.count("truncated"), 1u);
  EXPECT_EQ(rejections.total(), 10u);
}

TEST(OpenskyRest, AResponseOverTheSizeLimitIsSkippedAndTheNextRead) {
  std::string states;
  for (int i = 0; i < 100; ++i) states += R"(["000001",null,"X",1700000000,0,1,1,1,false],)";
  const std::string text = response(1700000000, states + R"(["000002",null,"X",1700000000,0,1,1,1,false])") +
                           response(1700000001, R"(["0000aa",null,"X",1700000001,0,1,1,1,false])");
  AircraftJsonOptions options;
  options.max_snapshot_bytes = 1000;
  Rejections rejections;
  const std::vector<TrackReport> r = decode(text, &rejections, options);
  EXPECT_EQ(rejections.count("object_too_long"), 1u);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].id, "0000AA");
}

// Three polls of three aircraft, pretty-printed as some clients save them.
std::string three_polls() {
  std::string stream;
  for (int i = 0; i < 3; ++i) {
    const long time = 1700000000 + 10 * i;
    std::string states;
    for (int a = 0; a < 3; ++a) {
      if (a > 0) states += ",\n  ";
      states += "[\"3c64" + std::to_string(10 + a) + "\",\"DLH" + std::to_string(a) + "   \",\"Germany\"," +
                std::to_string(time - a) + "," + std::to_string(time) + "," + std::to_string(6.0 + 0.01 * i) +
                ",50.0," + std::to_string(9000 + 30 * a) + ".5,false,230.5,98.25,-4.5,[1,2],9100.0,\"1000\",false," +
                std::to_string(a) + "]";
    }
    stream += "{\n \"time\": " + std::to_string(time) + ",\n \"states\": [\n  " + states + "\n ]\n}\n";
  }
  return stream;
}

TEST(OpenskyRest, SplitAnywhereGivesTheSameRecords) {
  test::expect_incremental([] { return make_opensky_rest_decoder(); }, three_polls());
  EXPECT_EQ(decode(three_polls()).size(), 9u);
}

TEST(OpenskyRest, IsDetectedAndReadThroughGzipAndAuto) {
  const std::string polls = three_polls();
  EXPECT_EQ(detect_format(bytes_of(polls)), Format::OpenskyRest);
  EXPECT_EQ(detect_format(bytes_of(response(1700000000, kFull))), Format::OpenskyRest);
  EXPECT_EQ(detect_format(bytes_of("{\"time\":1700000000,\"states\":null}")), Format::OpenskyRest);
  EXPECT_EQ(detect_format(bytes_of("{\"time\":1700000000,\"states\":[]}")), Format::OpenskyRest);
  EXPECT_EQ(detect_format(bytes_of("{\"states\":[1,2]}")), Format::Auto) << "an array of vectors, not of numbers";
  EXPECT_EQ(detect_format(bytes_of(test::gzip_member(polls))), Format::OpenskyRest);
  EXPECT_EQ(to_string(Format::OpenskyRest), "opensky-rest");
  auto explicit_decoder = make_decoder(Format::OpenskyRest);
  EXPECT_EQ(explicit_decoder->format_name(), "opensky-rest");
  const std::vector<TrackReport> expected = decode(polls);
  test::expect_same_reports(expected, decode_all(*explicit_decoder, test::gzip_member(polls)));
  auto automatic = make_decoder(Format::Auto);
  test::expect_same_reports(expected, decode_all(*automatic, test::gzip_member(polls)));
}

}  // namespace
}  // namespace kew::protocol
