// aircraft.json snapshots (aircraft_json.hpp): every member name of readsb, dump1090-fa
// and dump1090-mutability, the position's time and age, one record per fresh position
// across snapshots, the aggregators' "ac" and millisecond "now", refusals, and the
// decoder contract (split anywhere, the same records).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "kew/protocol/aircraft_json.hpp"
#include "kew/protocol/formats.hpp"
#include "kew/protocol/readsb.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::bytes_of;
using test::decode_all;

std::vector<TrackReport> decode(std::string_view text, Rejections* rejections = nullptr,
                                const AircraftJsonOptions& options = {}) {
  return test::decode_counted(*make_aircraft_json_decoder(options), text, rejections);
}

// readsb / dump1090-fa as written to /run/readsb/aircraft.json (pretty-printed as they do).
constexpr std::string_view kReadsb = R"({ "now" : 1700000000.0,
  "messages" : 123456,
  "aircraft" : [
    {"hex":"3c6586","type":"adsb_icao","flight":"DLH4AB  ","alt_baro":36000,"alt_geom":36500,"gs":451.2,"track":92.1,"baro_rate":-64,"squawk":"1000","nav_altitude_mcp":36000,"track_rate":0.5,"lat":49.100000,"lon":11.200000,"seen_pos":0.4,"seen":0.1,"rssi":-20.1},
    {"hex":"~a1b2c3","type":"tisb_other","alt_geom":5000,"geom_rate":640,"nav_altitude_fms":7000,"lat":49.2,"lon":11.3,"seen_pos":2.5},
    {"hex":"4b1803","type":"mode_s","alt_baro":12000,"seen":0.5},
    {"hex":"440123","alt_baro":"ground","gs":12,"lat":49.3,"lon":11.4,"seen_pos":1.0}
  ]
}
)";

TEST(AircraftJson, ReadsEveryReadsbMemberAndDatesEachPositionByItsAge) {
  Rejections rejections;
  const std::vector<TrackReport> r = decode(kReadsb, &rejections);
  EXPECT_EQ(rejections.total(), 0u) << rejections.last_reason();
  ASSERT_EQ(r.size(), 3u) << "the Mode S aircraft without a position is no record";
  // In data-time order: 2.5 s old, 1.0 s, 0.4 s.
  EXPECT_EQ(r[0].id, "~A1B2C3");
  EXPECT_EQ(r[0].position_source, "tisb_other") << "type kept as the position's source";
  EXPECT_EQ(r[1].position_source, "") << "none given";
  EXPECT_FALSE(r[0].address) << "a non-ICAO address is no aircraft's";
  EXPECT_DOUBLE_EQ(r[0].t, 1700000000.0 - 2.5);
  EXPECT_EQ(r[0].alt_ft, 5000.0) << "alt_geom without alt_baro";
  EXPECT_EQ(r[0].vr_fpm, 640.0) << "geom_rate without baro_rate";
  EXPECT_EQ(r[0].sel_ft, 7000.0);
  EXPECT_EQ(r[0].sel_src, SelectedAltitudeSource::Fms);
  EXPECT_EQ(r[1].id, "440123");
  EXPECT_TRUE(r[1].on_ground);
  EXPECT_EQ(r[1].alt_ft, 0.0);
  const TrackReport& a = r[2];
  EXPECT_EQ(a.source, "aircraft-json");
  EXPECT_EQ(a.position_source, "adsb_icao");
  EXPECT_EQ(a.id, "3C6586");
  EXPECT_EQ(a.address, 0x3c6586u);
  EXPECT_DOUBLE_EQ(a.t, 1700000000.0 - 0.4);
  EXPECT_EQ(a.callsign, "DLH4AB");
  EXPECT_EQ(a.alt_ft, 36000.0) << "alt_baro before alt_geom";
  EXPECT_EQ(a.gs_kt, 451.2);
  EXPECT_EQ(a.trk_deg, 92.1);
  EXPECT_EQ(a.vr_fpm, -64.0);
  EXPECT_EQ(a.mode3a, 01000);
  EXPECT_EQ(a.sel_ft, 36000.0);
  EXPECT_EQ(a.sel_src, SelectedAltitudeSource::Mcp);
  EXPECT_EQ(a.tar_dps, 0.5);
  EXPECT_DOUBLE_EQ(a.lat_deg, 49.1);
}

TEST(AircraftJson, ReadsDump1090MutabilitysOlderNames) {
  const std::string text = R"({"now":1700000000,"messages":5,"aircraft":[)"
                           R"({"hex":"3c6586","squawk":"7000","flight":"TEST1   ","lat":49.1,"lon":11.2,"nucp":7,)"
                           R"("seen_pos":0.8,"altitude":24000,"vert_rate":-1024,"track":271,"speed":402,)"
                           R"("messages":77,"seen":0.2,"rssi":-3.3},)"
                           R"({"hex":"3c6587","lat":49.0,"lon":11.0,"altitude":"ground","speed":5,"seen_pos":0.0}]})";
  Rejections rejections;
  const std::vector<TrackReport> r = decode(text, &rejections);
  EXPECT_EQ(rejections.total(), 0u) << rejections.last_reason();
  ASSERT_EQ(r.size(), 2u);
  const TrackReport& a = r[0];
  EXPECT_EQ(a.id, "3C6586");
  EXPECT_EQ(a.alt_ft, 24000.0);
  EXPECT_EQ(a.vr_fpm, -1024.0);
  EXPECT_EQ(a.gs_kt, 402.0);
  EXPECT_EQ(a.trk_deg, 271.0);
  EXPECT_EQ(a.callsign, "TEST1");
  EXPECT_DOUBLE_EQ(a.t, 1700000000.0 - 0.8);
  EXPECT_TRUE(r[1].on_ground);
}

TEST(AircraftJson, APositionIsReportedOnceHoweverManySnapshotsShowIt) {
  // A snapshot every second of a position first seen 0.2 s old, not updated for 5 s,
  // then a fresh one: two records, not six.
  std::string stream;
  for (int i = 0; i < 6; ++i) {
    const double now = 1700000000.0 + i;
    const double seen_pos = i < 5 ? 0.2 + i : 0.3;
    const double lat = i < 5 ? 49.0 : 49.01;
    stream += R"({"now":)" + std::to_string(now) + R"(,"aircraft":[{"hex":"3c6586","alt_baro":10000,"lat":)" +
              std::to_string(lat) + R"(,"lon":11.0,"seen_pos":)" + std::to_string(seen_pos) + "}]}\n";
  }
  const std::vector<TrackReport> r = decode(stream);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_DOUBLE_EQ(r[0].t, 1700000000.0 - 0.2);
  EXPECT_DOUBLE_EQ(r[1].t, 1700000005.0 - 0.3);
  EXPECT_DOUBLE_EQ(r[1].lat_deg, 49.01);
}

TEST(AircraftJson, OneSnapshotADatagramRemembersWhatWasReportedUntilTheStreamEnds) {
  const std::string snapshot = R"({"now":1700000000,"aircraft":[{"hex":"3c6586","alt_baro":1,"lat":1,"lon":1,"seen_pos":1}]})";
  const std::string later = R"({"now":1700000001,"aircraft":[{"hex":"3c6586","alt_baro":1,"lat":1,"lon":1,"seen_pos":2}]})";
  auto decoder = make_aircraft_json_decoder();
  // Each a NATS message, a fetched snapshot.
  EXPECT_EQ(test::reports_of_messages(*decoder, {snapshot, later}, true), 1u)
      << "the same position in two messages is one record";
  EXPECT_EQ(test::reports_of_messages(*decoder, {later}, true), 1u) << "after the end of the stream the decoder is as new";
}

TEST(AircraftJson, ThroughAutoDetectionDatagramsRememberWhatWasReportedToo) {
  // A watched file or a NATS subject of snapshots with format = "auto": each message is
  // detected afresh, and the decoder of its format keeps what it reported.
  const std::string snapshot = R"({"now":1700000000,"aircraft":[{"hex":"3c6586","alt_baro":1,"lat":1,"lon":1,"seen_pos":1}]})";
  const std::string later = R"({"now":1700000001,"aircraft":[{"hex":"3c6586","alt_baro":1,"lat":1,"lon":1,"seen_pos":2}]})";
  auto decoder = make_decoder(Format::Auto);
  EXPECT_EQ(test::reports_of_messages(*decoder, {snapshot, later, later}, true), 1u);
  EXPECT_EQ(test::reports_of_messages(*decoder, {later}, false), 1u) << "finish() forgets";
}

TEST(AircraftJson, PositionsOlderThanTheLimitAreNotReported) {
  const std::string text = R"({"now":1700000000,"aircraft":[)"
                           R"({"hex":"000001","alt_baro":1000,"lat":1,"lon":1,"seen_pos":9.9},)"
                           R"({"hex":"000002","alt_baro":1000,"lat":1,"lon":1,"seen_pos":10.1},)"
                           R"({"hex":"000003","alt_baro":1000,"lat":1,"lon":1,"seen":3},)"
                           R"({"hex":"000004","alt_baro":1000,"lat":1,"lon":1}]})";
  std::vector<TrackReport> r = decode(text);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].id, "000001");
  EXPECT_DOUBLE_EQ(r[1].t, 1700000000.0 - 3.0) << "seen when seen_pos is missing";
  EXPECT_DOUBLE_EQ(r[2].t, 1700000000.0) << "now when neither is given";
  AircraftJsonOptions options;
  options.max_position_age_s = 30.0;
  EXPECT_EQ(decode(text, nullptr, options).size(), 4u);
}

TEST(AircraftJson, ReadsTheAggregatorsAcArrayAndMillisecondNow) {
  const std::string text = R"({"ac":[{"hex":"a1b2c3","alt_baro":3000,"lat":29.9,"lon":-95.3,"seen_pos":1.5}],)"
                           R"("msg":"No error","now":1700000000000,"total":1,"ctime":1700000000000,"ptime":12})";
  const std::vector<TrackReport> r = decode(text);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_DOUBLE_EQ(r[0].t, 1700000000.0 - 1.5);
}

TEST(AircraftJson, SplitAnywhereGivesTheSameRecords) {
  std::string stream = std::string(kReadsb);
  stream += R"({"now":1700000001.0,"aircraft":[{"hex":"3c6586","alt_baro":36000,"lat":49.11,"lon":11.2,"seen_pos":0.1}]})";
  auto whole = make_aircraft_json_decoder();
  auto bytes = make_aircraft_json_decoder();
  auto chunks = make_aircraft_json_decoder();
  const std::vector<TrackReport> a = decode_all(*whole, stream);
  const std::vector<TrackReport> b = test::decode_byte_by_byte(*bytes, stream);
  const std::vector<TrackReport> c = test::decode_random_chunks(*chunks, stream, 7);
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), a.size());
  ASSERT_EQ(c.size(), a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(test::bits(a[i].t), test::bits(b[i].t));
    EXPECT_EQ(a[i].id, c[i].id);
    EXPECT_EQ(test::bits(a[i].lat_deg), test::bits(c[i].lat_deg));
  }
}

TEST(AircraftJson, BadInputIsCountedAndTheRestDecoded) {
  const std::string text =
      R"({"now":1700000000,"aircraft":[7,{"alt_baro":1000,"lat":1,"lon":1},{"hex":"xyz","alt_baro":1,"lat":1,"lon":1},)"
      R"({"hex":"000005","lat":1,"lon":1},{"hex":"000006","alt_baro":1000,"lat":91,"lon":1},)"
      R"({"hex":"000007","alt_baro":1000,"lat":1,"lon":1}]})"
      "\ngarbage\n"
      R"({"aircraft":[]})"
      R"({"now":1700000001,"aircraft":{}})"
      R"({"now":1700000002,"aircraft":[{"hex":"000008","alt_baro":1000,"lat":1,"lon":1}]})"
      R"({"now":1700000003,"aircraft":[{"hex":)";
  Rejections rejections;
  const std::vector<TrackReport> r = decode(text, &rejections);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].id, "000007");
  EXPECT_EQ(r[1].id, "000008");
  EXPECT_EQ(rejections.count("bad_json"), 2u) << "an aircraft that is not an object, the garbage";
  EXPECT_EQ(rejections.count("missing_field"), 2u) << "no hex; no now";
  EXPECT_EQ(rejections.count("bad_address"), 1u);
  EXPECT_EQ(rejections.count("no_altitude"), 1u);
  EXPECT_EQ(rejections.count("lat_out_of_range"), 1u);
  EXPECT_EQ(rejections.count("wrong_type"), 1u);
  EXPECT_EQ(rejections.count("truncated"), 1u);
}

TEST(AircraftJson, ASnapshotOverTheSizeLimitIsSkippedAndTheNextRead) {
  std::string big = R"({"now":1700000000,"aircraft":[)";
  for (int i = 0; i < 100; ++i)
    big += R"({"hex":"00000)" + std::to_string(i % 10) + R"(","alt_baro":1000,"lat":1,"lon":1},)";
  big += R"({"hex":"000001","alt_baro":1000,"lat":1,"lon":1}]})";
  const std::string text = big + "\n" + R"({"now":1700000001,"aircraft":[{"hex":"0000AA","alt_baro":1,"lat":1,"lon":1}]})" + "\n";
  AircraftJsonOptions options;
  options.max_snapshot_bytes = 1000;
  Rejections rejections;
  const std::vector<TrackReport> r = decode(text, &rejections, options);
  EXPECT_EQ(rejections.count("object_too_long"), 1u);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].id, "0000AA");
}

TEST(AircraftJson, IsDetectedWhereverItsArrayStands) {
  EXPECT_EQ(detect_format(bytes_of(kReadsb.substr(0, 200))), Format::AircraftJson)
      << "the head of a pretty-printed snapshot";
  EXPECT_EQ(detect_format(bytes_of(R"({"ac":[{"hex":"a1b2c3"}],"now":1700000000000})")), Format::AircraftJson);
  EXPECT_EQ(detect_format(bytes_of(R"({"now":1700000000,"hex":"a1b2c3","lat":1,"lon":1,"alt_baro":1})" "\n")),
            Format::ReadsbJson)
      << "readsb JSON lines stay readsb";
  auto decoder = make_decoder(Format::Auto, {});
  EXPECT_EQ(decode_all(*decoder, kReadsb).size(), 3u);
}

TEST(AircraftJson, ABundledHistoryGivesEachRealPositionOnce) {
  // 120 snapshots made from the first 120 s of real readsb lines (tests/data/text/
  // SOURCE.md): every position of the lines once, at its own time, however many
  // snapshots show it.
  const std::string lines = test::read_file(test::bundled_path("readsb_20minutes.json"));
  auto readsb = make_readsb_decoder();
  std::map<std::pair<std::string, long>, TrackReport> positions;  // the last line of an aircraft in a second
  for (const TrackReport& r : decode_all(*readsb, lines))
    if (r.t < 1693383000.0 + 120) positions[{r.id, std::lround(r.t)}] = r;
  Rejections rejections;
  const std::vector<TrackReport> snapshots =
      decode(test::read_file(test::bundled_path("aircraft_json_history.json")), &rejections);
  EXPECT_EQ(rejections.total(), 0u) << rejections.last_reason();
  ASSERT_EQ(snapshots.size(), positions.size());
  for (const TrackReport& r : snapshots) {
    const auto line = positions.find({r.id, std::lround(r.t)});
    ASSERT_NE(line, positions.end()) << r.id << " at " << r.t;
    EXPECT_NEAR(r.t, line->second.t, 1e-3);
    EXPECT_EQ(r.lat_deg, line->second.lat_deg);
    EXPECT_EQ(r.alt_ft, line->second.alt_ft);
    EXPECT_EQ(r.callsign, line->second.callsign);
  }
  EXPECT_EQ(detect_format(bytes_of(test::read_file(test::bundled_path("aircraft_json_history.json")).substr(0, 4096))),
            Format::AircraftJson);
}

}  // namespace
}  // namespace kew::protocol
