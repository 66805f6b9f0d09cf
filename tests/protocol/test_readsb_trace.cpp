// readsb traces (readsb_trace.hpp): every field of a row and its variants (flags, nulls,
// "ground", the details object, older and newer row lengths), one record per point across
// trace_full and trace_recent, refusals, gzip, detection, the decoder contract (split
// anywhere, the same records), and the bundled traces made from real readsb positions.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "kew/protocol/formats.hpp"
#include "kew/protocol/gzip.hpp"
#include "kew/protocol/readsb.hpp"
#include "kew/protocol/readsb_trace.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::bytes_of;
using test::decode_all;

std::vector<TrackReport> decode(std::string_view text, Rejections* rejections = nullptr,
                                const AircraftJsonOptions& options = {}) {
  return test::decode_counted(*make_readsb_trace_decoder(options), text, rejections);
}

/// A trace of `icao` from `timestamp` holding `rows` (the text of the array's elements),
/// laid out as readsb writes it.
std::string trace(std::string_view icao, std::string_view timestamp, std::string_view rows) {
  return "{\"icao\":\"" + std::string(icao) + "\",\n\"r\":\"D-AIUP\",\n\"t\":\"A320\",\n\"dbFlags\":0,\"desc\":\"AIRBUS A-320\",\n"
         "\"timestamp\": " + std::string(timestamp) + ",\n\"trace\":[ \n" + std::string(rows) + " ]\n }\n";
}

// readsb's documented example (README-json.md), one row with its details object.
constexpr std::string_view kRows =
    R"([7016.59,49.263300,10.614239,25125,446.5,309.0,0,-2176,)"
    R"({"type":"adsb_icao","flight":"DLH7YA  ","alt_geom":25875,"ias":335,"track":309.00,"track_rate":-0.53,)"
    R"("baro_rate":-2176,"geom_rate":-2208,"squawk":"1000","category":"A3","nav_qnh":1012.8,"nav_altitude_mcp":14016,)"
    R"("nic":8,"rc":186,"version":2,"alert":0,"spi":0},"adsb_icao",25875,-2208,335,-10.7],)"
    "\n"
    R"([7024.85,49.273589,10.593278,24825,446.0,306.6,0,-2176,null,"mlat",25550,-2144,337,-1.6])";

TEST(ReadsbTrace, ReadsEveryFieldOfARowAndTheDetailsObject) {
  Rejections rejections;
  const std::vector<TrackReport> r = decode(trace("3c66b0", "1663259853.016", kRows), &rejections);
  EXPECT_EQ(rejections.total(), 0u) << rejections.last_reason();
  ASSERT_EQ(r.size(), 2u);
  const TrackReport& a = r[0];
  EXPECT_EQ(a.source, "readsb-trace");
  EXPECT_EQ(a.id, "3C66B0");
  EXPECT_EQ(a.address, 0x3c66b0u);
  EXPECT_DOUBLE_EQ(a.t, 1663259853.016 + 7016.59) << "timestamp + the row's offset";
  EXPECT_EQ(a.lat_deg, 49.2633);
  EXPECT_EQ(a.lon_deg, 10.614239);
  EXPECT_EQ(a.alt_ft, 25125.0) << "field 3, barometric without flag 8";
  EXPECT_EQ(a.gs_kt, 446.5);
  EXPECT_EQ(a.trk_deg, 309.0);
  EXPECT_EQ(a.vr_fpm, -2176.0) << "field 7, barometric without flag 4";
  EXPECT_EQ(a.callsign, "DLH7YA");
  EXPECT_EQ(a.mode3a, 01000);
  EXPECT_EQ(a.sel_ft, 14016.0) << "nav_altitude_mcp of the row's own object";
  EXPECT_EQ(a.sel_src, SelectedAltitudeSource::Mcp);
  EXPECT_EQ(a.tar_dps, -0.53);
  EXPECT_EQ(a.position_source, "adsb_icao");
  EXPECT_FALSE(a.on_ground);
  const TrackReport& b = r[1];
  EXPECT_DOUBLE_EQ(b.t, 1663259853.016 + 7024.85);
  EXPECT_EQ(b.callsign, "DLH7YA") << "the last object's callsign and squawk hold for later rows";
  EXPECT_EQ(b.mode3a, 01000);
  EXPECT_FALSE(b.sel_ft) << "a selected altitude only from the row's own object";
  EXPECT_FALSE(b.tar_dps);
  EXPECT_EQ(b.position_source, "mlat") << "field 9";
}

TEST(ReadsbTrace, FlagsNullsAndTheGroundSayWhichAltitudeAndRate) {
  const std::string rows =
      R"([0,1,2,5000,100,90,8,640,null,"adsb_icao",5100,700],)"      // 8: field 3 is geometric
      R"([1,1,2,5000,100,90,4,640,null,"adsb_icao",5100,700],)"      // 4: field 7 is geometric
      R"([2,1,2,null,100,90,0,null,null,"adsb_icao",5100,700],)"     // geometric 10 and 11 when 3 and 7 are null
      R"([3,1,2,"ground",5,181.5,0,null,null,"adsb_icao",null,null],)"  // on the ground, no altitude: 0
      R"([4,1,2,"ground",5,181.5,0,null,null,"adsb_icao",12,null],)"    // on the ground: the geometric altitude
      R"([5,1,2,6000,100,90,1,null,null,"adsb_icao"],)"               // 1: a gap before it, a record like others
      R"([6,1,2,6000,100,90,2,null,null,"adsb_icao",null,null,null,null,"extra",7],)"  // 2, and later fields
      R"([7,1,2,null,100,90,0,null,null,"adsb_icao",null,null])";  // no altitude at all
  Rejections rejections;
  const std::vector<TrackReport> r = decode(trace("a1b2c3", "1700000000.000", rows), &rejections);
  EXPECT_EQ(rejections.count("no_altitude"), 1u);
  EXPECT_EQ(rejections.total(), 1u);
  ASSERT_EQ(r.size(), 7u);
  // Flag 8: field 3 is the geometric altitude (the only altitude, so the report's).
  EXPECT_EQ(r[0].alt_ft, 5000.0);
  EXPECT_EQ(r[0].vr_fpm, 640.0);
  EXPECT_EQ(r[1].alt_ft, 5000.0);
  EXPECT_EQ(r[1].vr_fpm, 640.0) << "flag 4: field 7 read as the geometric rate";
  EXPECT_EQ(r[2].alt_ft, 5100.0);
  EXPECT_EQ(r[2].vr_fpm, 700.0);
  EXPECT_TRUE(r[3].on_ground);
  EXPECT_EQ(r[3].alt_ft, 0.0);
  EXPECT_EQ(r[3].trk_deg, 181.5) << "on the ground readsb writes the heading there";
  EXPECT_TRUE(r[4].on_ground);
  EXPECT_EQ(r[4].alt_ft, 12.0);
  EXPECT_DOUBLE_EQ(r[5].t, 1700000005.0);
  EXPECT_FALSE(r[5].vr_fpm);
  EXPECT_DOUBLE_EQ(r[6].t, 1700000006.0);
  for (const TrackReport& report : r) EXPECT_EQ(report.callsign, "");
}

TEST(ReadsbTrace, ShortRowsNonIcaoAddressesAndTheSourceFromTheObject) {
  const std::string rows =
      R"([0,1,2,1000],)"                                                    // the least a row holds
      R"([1,1,2,1000,100,90,0,null,{"type":"tisb_other","flight":"N1"}],)"  // before 2022: nine fields
      R"([2,1,2])";                                                         // too short
  Rejections rejections;
  const std::vector<TrackReport> r = decode(trace("~a1b2c3", "1700000000", rows), &rejections);
  EXPECT_EQ(rejections.count("missing_field"), 1u);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].id, "~A1B2C3");
  EXPECT_FALSE(r[0].address) << "a non-ICAO address is no aircraft's";
  EXPECT_FALSE(r[0].gs_kt);
  EXPECT_EQ(r[1].position_source, "tisb_other") << "the object's type without field 9";
  EXPECT_EQ(r[1].callsign, "N1");
}

TEST(ReadsbTrace, APointInTraceFullAndTraceRecentIsReportedOnce) {
  // trace_recent dates its points from another timestamp: the same point's time differs
  // by the rounding of the offsets.
  const std::string full = trace("3c66b0", "1700000000.000",
                                 "[0.00,1,2,1000],\n[10.00,1,2,1100],\n[20.00,1,2,1200],\n[30.00,1,2,1300]");
  const std::string recent = trace("3c66b0", "1700000019.995",
                                   "[0.01,1,2,1200],\n[10.00,1,2,1300],\n[20.01,1,2,1400]");
  const std::vector<TrackReport> r = decode(full + recent);
  ASSERT_EQ(r.size(), 5u);
  EXPECT_EQ(r[4].alt_ft, 1400.0);
  EXPECT_DOUBLE_EQ(r[4].t, 1700000040.005);
  // One trace a message (a poll of trace_recent): remembered until the stream ends.
  auto decoder = make_readsb_trace_decoder();
  EXPECT_EQ(test::reports_of_messages(*decoder, {full, recent, recent}, true), 5u);
  EXPECT_EQ(test::reports_of_messages(*decoder, {recent}, true), 3u) << "after the end of the stream the decoder is as new";
}

TEST(ReadsbTrace, BadInputIsCountedAndTheRestDecoded) {
  const std::string text =
      trace("000001", "1700000000",
            "7,\n[\"0\",1,2,1000],\n[1,null,2,1000],\n[2,1,2,1000,1,1,1.5],\n[3,1,2,1000,1,1,0,0,[]],\n"
            "[4,1,2,1000,1,1,0,0,{\"squawk\":\"9999\"}],\n[5,1,2,1000,1,1,0,0,null,7],\n[6,91,2,1000],\n[7,1,2,\"high\"],\n"
            "[8,1,2,1000]") +
      "garbage\n" + trace("xyz", "1700000000", "[0,1,2,1000]") + R"({"timestamp":1,"trace":[]})" +
      R"({"icao":"000002","trace":[]})" + R"({"icao":"000002","timestamp":1})" +
      R"({"icao":"000002","timestamp":1,"trace":{}})" + trace("000003", "1700000000", "[0,1,2,1000]") +
      R"({"icao":"000004","timestamp":1,"trace":[[0,1,)";
  Rejections rejections;
  const std::vector<TrackReport> r = decode(text, &rejections);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].id, "000001");
  EXPECT_DOUBLE_EQ(r[0].t, 1700000008.0);
  EXPECT_EQ(r[1].id, "000003");
  EXPECT_EQ(rejections.count("wrong_type"), 5u)
      << "a row not an array, an offset not a number, details not an object, a source type not a string, "
         "trace an object";
  EXPECT_EQ(rejections.count("no_position"), 1u);
  EXPECT_EQ(rejections.count("bad_number"), 2u) << "flags 1.5; altitude \"high\"";
  EXPECT_EQ(rejections.count("bad_mode3a"), 1u);
  EXPECT_EQ(rejections.count("lat_out_of_range"), 1u);
  EXPECT_EQ(rejections.count("bad_json"), 1u);
  EXPECT_EQ(rejections.count("bad_address"), 1u);
  EXPECT_EQ(rejections.count("missing_field"), 3u) << "no icao, no timestamp, no trace";
  EXPECT_EQ(rejections.count("truncated"), 1u);
  EXPECT_EQ(rejections.total(), 16u);

  AircraftJsonOptions small;
  small.max_snapshot_bytes = 200;
  Rejections limited;
  EXPECT_EQ(decode(trace("000001", "1", std::string(300, ' ') + "[0,1,2,3]") + trace("000002", "1", "[0,1,2,3]"),
                   &limited, small)
                .size(),
            1u);
  EXPECT_EQ(limited.count("object_too_long"), 1u);
}

TEST(ReadsbTrace, SplitAnywhereGivesTheSameRecords) {
  const std::string stream = trace("3c66b0", "1663259853.016", kRows) +
                             trace("a1b2c3", "1700000000", "[0,1,2,\"ground\"],\n[1,1,2,1000,1,1,9,1]");
  test::expect_incremental([] { return make_readsb_trace_decoder(); }, stream);
}

std::string bundled_trace(const std::string& name) {
  return test::read_file(test::bundled_path("readsb_traces/" + name));
}

TEST(ReadsbTrace, IsDetectedPlainOrGzipAndReadThroughAuto) {
  const std::string plain = trace("3c66b0", "1663259853.016", kRows);
  EXPECT_EQ(detect_format(bytes_of(plain)), Format::ReadsbTrace);
  EXPECT_EQ(detect_format(bytes_of(plain.substr(0, 150))), Format::ReadsbTrace) << "the head of a trace";
  EXPECT_EQ(detect_format(bytes_of(test::gzip_member(plain))), Format::ReadsbTrace);
  EXPECT_EQ(detect_format(bytes_of("{\"trace\":[]}")), Format::Auto) << "no icao";
  EXPECT_EQ(to_string(Format::ReadsbTrace), "readsb-trace");
  const std::string gzipped = bundled_trace("trace_full_aab1cf.json");
  ASSERT_TRUE(protocol::has_gzip_magic(bytes_of(gzipped)));
  EXPECT_EQ(detect_format(bytes_of(gzipped)), Format::ReadsbTrace);
  auto explicit_decoder = make_decoder(Format::ReadsbTrace);
  const std::vector<TrackReport> expected = decode_all(*explicit_decoder, gzipped);
  EXPECT_EQ(expected.size(), 212u);
  auto automatic = make_decoder(Format::Auto);
  test::expect_same_reports(expected, decode_all(*automatic, gzipped));
}

TEST(ReadsbTrace, TheBundledTracesGiveEachRealPositionOnce) {
  // 19 traces made from the real readsb lines (tests/data/text/SOURCE.md): every position
  // of the lines (the last of an aircraft in a second) once, at its own time.
  const std::string lines = test::read_file(test::bundled_path("readsb_20minutes.json"));
  auto readsb = make_readsb_decoder();
  std::map<std::pair<std::string, double>, TrackReport> positions;
  for (const TrackReport& r : decode_all(*readsb, lines)) positions[{r.id, r.t}] = r;
  std::size_t records = 0;
  std::size_t flagged_after_a_gap = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::bundled_path("readsb_traces"))) {
    const std::string text = test::read_file(entry.path().string());
    auto decoder = make_decoder(Format::ReadsbTrace);
    const std::vector<TrackReport> r = decode_all(*decoder, text);
    EXPECT_EQ(decoder->rejections().total(), 0u) << entry.path();
    for (std::size_t i = 0; i < r.size(); ++i) {
      const auto line = positions.find({r[i].id, r[i].t});
      ASSERT_NE(line, positions.end()) << r[i].id << " at " << r[i].t;
      EXPECT_EQ(r[i].lat_deg, line->second.lat_deg);
      EXPECT_EQ(r[i].lon_deg, line->second.lon_deg);
      EXPECT_EQ(r[i].alt_ft, line->second.alt_ft);
      EXPECT_EQ(r[i].gs_kt, line->second.gs_kt);
      EXPECT_EQ(r[i].trk_deg, line->second.trk_deg);
      if (!line->second.callsign.empty()) {
        EXPECT_EQ(r[i].callsign, line->second.callsign);
      }
      if (i > 0 && r[i].t - r[i - 1].t >= 15) ++flagged_after_a_gap;
      EXPECT_EQ(r[i].position_source, "adsb_icao");
    }
    records += r.size();
  }
  EXPECT_EQ(records, positions.size());
  EXPECT_EQ(records, 1182u);
  EXPECT_EQ(flagged_after_a_gap, 159u) << "rows flagged 1 are records";
}

}  // namespace
}  // namespace kew::protocol
