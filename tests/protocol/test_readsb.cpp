// readsb JSON lines: member mapping, bad lines, golden values on recordings/adsb_actions-readsb
// (expected values from python3's json module, see tests/data/text/SOURCE.md).
#include <gtest/gtest.h>

#include "kew/protocol/gzip.hpp"
#include "kew/protocol/readsb.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::decode_all;

TEST(ReadsbDecoder, MapsMembersAndUnits) {
  auto decoder = make_readsb_decoder();
  const auto reports = decode_all(
      *decoder,
      R"({"now": 1693383000, "alt_baro": 9975, "gscp": 240, "lat": 39.854628, "lon": -119.856323, )"
      R"("track": 164.1, "hex": "ab80bc", "flight": "N840KB  ", "squawk": "1200", "baro_rate": -256})"
      "\n");
  ASSERT_EQ(reports.size(), 1u);
  const TrackReport& r = reports[0];
  EXPECT_EQ(r.t, 1693383000.0);
  EXPECT_EQ(r.id, "AB80BC");
  EXPECT_EQ(r.address, std::optional<std::uint32_t>(0xAB80BC));
  EXPECT_EQ(r.source, "readsb");
  EXPECT_EQ(r.lat_deg, 39.854628);
  EXPECT_EQ(r.lon_deg, -119.856323);
  EXPECT_EQ(r.alt_ft, 9975.0);
  EXPECT_EQ(r.gs_kt, 240.0);
  EXPECT_EQ(r.trk_deg, 164.1);
  EXPECT_EQ(r.vr_fpm, -256.0);
  EXPECT_EQ(r.callsign, "N840KB");
  EXPECT_EQ(r.mode3a, std::optional<std::uint16_t>(01200));
  EXPECT_FALSE(r.on_ground);
}

TEST(ReadsbDecoder, GsPreferredOverGscpAndFlightdictFillsWhatTheTopLevelLacks) {
  auto decoder = make_readsb_decoder();
  const auto reports = decode_all(
      *decoder,
      // flightdict before and after the top-level members: the top level wins either way.
      R"({"flightdict":{"geom_rate":-576,"baro_rate":111,"squawk":"3327","alt_geom":4425},"now":1,)"
      R"("hex":"a4e625","lat":36.8,"lon":-121.7,"alt_baro":4300,"gs":120,"gscp":116,"baro_rate":-64})"
      "\n"
      R"({"now":2,"hex":"a4e625","lat":36.8,"lon":-121.7,"alt_baro":4300,"gscp":116,)"
      R"("flightdict":{"type":"adsr_icao","flight":"N41459  ","geom_rate":-576,"squawk":"3327"}})"
      "\n");
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].gs_kt, 120.0);
  EXPECT_EQ(reports[0].vr_fpm, -64.0);
  EXPECT_EQ(reports[0].mode3a, std::optional<std::uint16_t>(03327));
  EXPECT_EQ(reports[1].gs_kt, 116.0);
  EXPECT_EQ(reports[1].vr_fpm, -576.0);  // geom_rate when no baro_rate anywhere
  EXPECT_EQ(reports[1].callsign, "");    // flightdict's flight is not used
}

TEST(ReadsbDecoder, SelectedAltitudeMcpElseFmsAndTrackRate) {
  auto decoder = make_readsb_decoder();
  const std::string head = R"({"now":1,"hex":"a4e625","lat":36.8,"lon":-121.7,"alt_baro":4300)";
  const auto reports = decode_all(
      *decoder,
      head + R"(,"nav_altitude_mcp":8512,"track_rate":-0.94})" "\n" +
      head + R"(,"nav_altitude_fms":11008})" "\n" +
      head + R"(,"nav_altitude_fms":11008,"nav_altitude_mcp":8512})" "\n" +  // MCP first
      head + R"(,"flightdict":{"nav_altitude_mcp":6016,"nav_modes":["vnav"],"track_rate":1.5}})" "\n" +
      head + R"(,"nav_altitude_mcp":null,"flightdict":{"nav_altitude_fms":7008}})" "\n" +
      head + "}\n");
  ASSERT_EQ(reports.size(), 6u);
  EXPECT_EQ(reports[0].sel_ft, 8512.0);
  EXPECT_EQ(reports[0].sel_src, SelectedAltitudeSource::Mcp);
  EXPECT_EQ(reports[0].tar_dps, -0.94);
  EXPECT_EQ(reports[1].sel_ft, 11008.0);
  EXPECT_EQ(reports[1].sel_src, SelectedAltitudeSource::Fms);
  EXPECT_FALSE(reports[1].tar_dps);
  EXPECT_EQ(reports[2].sel_ft, 8512.0);
  EXPECT_EQ(reports[2].sel_src, SelectedAltitudeSource::Mcp);
  EXPECT_EQ(reports[3].sel_ft, 6016.0);  // from the flightdict
  EXPECT_EQ(reports[3].sel_src, SelectedAltitudeSource::Mcp);
  EXPECT_EQ(reports[3].tar_dps, 1.5);
  EXPECT_EQ(reports[4].sel_ft, 7008.0);
  EXPECT_EQ(reports[4].sel_src, SelectedAltitudeSource::Fms);
  EXPECT_FALSE(reports[5].sel_ft);
  EXPECT_FALSE(reports[5].tar_dps);
  EXPECT_EQ(decoder->rejections().total(), 0u);
}

TEST(ReadsbDecoder, GroundNumericStringsNullsAndNonIcaoAddresses) {
  auto decoder = make_readsb_decoder();
  const auto reports = decode_all(
      *decoder,
      R"({"now":1,"hex":"~2b1fcc","lat":36.9,"lon":-121.4,"alt_baro":"ground","alt_geom":95,"track":null,"flight":null})"
      "\n"
      R"({"now":2,"hex":"a9d63a","lat":36.8,"lon":-121.4,"alt_baro":"0","flight":"N/A"})"
      "\n"
      R"({"now":3,"hex":"a9d63a","lat":36.8,"lon":-121.4,"alt_geom":3525})"
      "\n");
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_EQ(reports[0].id, "~2B1FCC");
  EXPECT_FALSE(reports[0].address.has_value());  // non-ICAO: no aircraft address
  EXPECT_EQ(reports[1].address, std::optional<std::uint32_t>(0xA9D63A));
  EXPECT_TRUE(reports[0].on_ground);
  EXPECT_EQ(reports[0].alt_ft, 95.0);
  EXPECT_FALSE(reports[0].trk_deg);
  EXPECT_EQ(reports[0].callsign, "");
  EXPECT_FALSE(reports[1].on_ground);
  EXPECT_EQ(reports[1].alt_ft, 0.0);
  EXPECT_EQ(reports[1].callsign, "");
  EXPECT_EQ(reports[2].alt_ft, 3525.0);
}

TEST(ReadsbDecoder, BadLinesAreCountedByReasonAndLaterLinesDecoded) {
  auto decoder = make_readsb_decoder();
  const std::string good = R"({"now":1,"hex":"abcdef","lat":1,"lon":2,"alt_baro":3})" "\n";
  const std::string input =
      good +
      R"({"flight": "N/A", "now": 1693383001})" "\n" +                          // no_position
      R"({"now":1,"lat":1,"lon":2,"alt_baro":3})" "\n" +                        // missing hex
      R"({"hex":"abcdef","lat":1,"lon":2,"alt_baro":3})" "\n" +                 // missing now
      R"({"now":1,"hex":"abcdeg","lat":1,"lon":2,"alt_baro":3})" "\n" +         // bad_address
      R"({"now":1,"hex":"abcdef","lat":1,"lon":2})" "\n" +                      // no_altitude
      R"({"now":1,"hex":"abcdef","lat":1,"lon":2,"alt_baro":"high"})" "\n" +    // bad_number
      R"({"now":1,"hex":"abcdef","lat":1,"lon":2,"alt_baro":3,"gs":"x"})" "\n" +   // wrong_type
      R"({"now":1,"hex":"abcdef","lat":1,"lon":2,"alt_baro":3,"flightdict":7})" "\n" +  // wrong_type
      R"({"now":1,"hex":"abcdef","lat":1,"lon":200,"alt_baro":3})" "\n" +       // lon range
      R"({"now":1,"hex":"abcdef","lat":1,"lon":2,"alt_baro":3,"squawk":"12"})" "\n" +  // bad_mode3a
      R"({"now":1,"hex":"abcdef",)" "\n" +                                      // bad_json
      good;
  const auto reports = decode_all(*decoder, input);
  EXPECT_EQ(reports.size(), 2u);
  const Rejections& r = decoder->rejections();
  EXPECT_EQ(r.by_reason(), (test::Counts{{"bad_address", 1}, {"bad_json", 1}, {"bad_mode3a", 1},
                                          {"bad_number", 1}, {"lon_out_of_range", 1},
                                          {"missing_field", 2}, {"no_altitude", 1},
                                          {"no_position", 1}, {"wrong_type", 2}}));
}

TEST(ReadsbDecoder, Bundled20MinutesGolden) {
  auto decoder = make_readsb_decoder();
  const auto reports = decode_all(*decoder, test::read_file(test::bundled_path("readsb_20minutes.json")));
  const auto summary = test::summarize(reports);
  EXPECT_EQ(summary.count, 1194u);
  EXPECT_EQ(summary.ids.size(), 19u);
  EXPECT_EQ(summary.ids.count("C087D6"), 1u);
  EXPECT_EQ(summary.ids.count("A08846"), 1u);
  EXPECT_EQ(summary.t_min, 1693383000.0);  // 2023-08-30 08:10:00 UTC
  EXPECT_EQ(summary.t_max, 1693384199.0);
  EXPECT_EQ(decoder->rejections().count("no_position"), 418u);
  EXPECT_EQ(decoder->rejections().total(), 418u);

  EXPECT_EQ(reports[0].id, "AB80BC");
  EXPECT_EQ(reports[0].alt_ft, 9975.0);
  EXPECT_EQ(reports[0].gs_kt, 240.0);
  EXPECT_EQ(reports[0].trk_deg, 164.1);
  EXPECT_EQ(reports[0].callsign, "N840KB");
  EXPECT_EQ(reports[1].id, "A77D11");
  EXPECT_EQ(reports[1].lat_deg, 40.785393);
  EXPECT_EQ(reports[1].lon_deg, -119.159962);
  EXPECT_EQ(reports[500].id, "A27D3C");
  EXPECT_EQ(reports[500].t, 1693383519.0);
  EXPECT_EQ(reports[500].alt_ft, 5225.0);
  EXPECT_EQ(reports[500].gs_kt, 73.0);
  EXPECT_EQ(reports[500].trk_deg, 152.4);
  EXPECT_EQ(reports.back().id, "C087D6");
  EXPECT_EQ(reports.back().callsign, "CGZLL");
  EXPECT_EQ(reports.back().lat_deg, 40.789581);

  std::size_t without_track = 0, without_callsign = 0;
  for (const TrackReport& r : reports) {
    without_track += r.trk_deg ? 0 : 1;
    without_callsign += r.callsign.empty() ? 1 : 0;
  }
  EXPECT_EQ(without_track, 113u);
  EXPECT_EQ(without_callsign, 34u);
}

TEST(ReadsbDecoder, IsIncremental) {
  std::string input = test::read_file(test::bundled_path("readsb_20minutes.json"));
  input.resize(60000);  // ends mid-line
  input += "\n{\"now\":1,\"hex\":\"abcdef\",\"lat\":1,\"lon\":2,\"alt_baro\":3}";
  test::expect_incremental([] { return make_readsb_decoder(); }, input);
}

struct SharedReadsbFile {
  const char* name;
  std::size_t reports;
  std::size_t ids;
  double t_min, t_max;
};

class ReadsbSharedRecording : public testing::TestWithParam<SharedReadsbFile> {};

TEST_P(ReadsbSharedRecording, Golden) {
  const SharedReadsbFile& expected = GetParam();
  const std::string path = test::shared_path(std::string("adsb_actions-readsb/") + expected.name);
  if (!test::exists(path)) GTEST_SKIP() << "shared recordings absent: " << path;
  auto decoder = make_gzip_decoder(make_readsb_decoder());
  const auto reports = decode_all(*decoder, test::read_file(path));
  const auto summary = test::summarize(reports);
  EXPECT_EQ(summary.count, expected.reports);
  EXPECT_EQ(summary.ids.size(), expected.ids);
  EXPECT_EQ(summary.t_min, expected.t_min);
  EXPECT_EQ(summary.t_max, expected.t_max);
  EXPECT_EQ(decoder->rejections().total() + summary.count,
            std::string_view(expected.name) == "1hr.json" ? 5767u : expected.reports);
}

INSTANTIATE_TEST_SUITE_P(
    Files, ReadsbSharedRecording,
    testing::Values(SharedReadsbFile{"1hr.json", 4920, 59, 1693303200, 1693306799},
                    SharedReadsbFile{"grid_20250601_36_-122.jsonl.gz", 44120, 521, 1748719389,
                                     1748822398},
                    SharedReadsbFile{"grid_20250602_36_-122.jsonl.gz", 41294, 507, 1748822400,
                                     1748908799}));

TEST(ReadsbDecoder, SharedGridSampleValues) {
  const std::string path = test::shared_path("adsb_actions-readsb/grid_20250601_36_-122.jsonl.gz");
  if (!test::exists(path)) GTEST_SKIP() << "shared recordings absent: " << path;
  auto decoder = make_gzip_decoder(make_readsb_decoder());
  const auto reports = decode_all(*decoder, test::read_file(path));
  ASSERT_GT(reports.size(), 2u);
  // Line 3: {"now":1748719393,"alt_baro":1400,"gscp":93,"lat":36.396881,"lon":-121.410542,
  // "track":281.1,"hex":"a7f426","flight":"N611TH","flightdict":{...,"baro_rate":-256,...},
  // "category":"A7","baro_rate":-256}
  EXPECT_EQ(reports[2].t, 1748719393.0);
  EXPECT_EQ(reports[2].id, "A7F426");
  EXPECT_EQ(reports[2].alt_ft, 1400.0);
  EXPECT_EQ(reports[2].gs_kt, 93.0);
  EXPECT_EQ(reports[2].lat_deg, 36.396881);
  EXPECT_EQ(reports[2].lon_deg, -121.410542);
  EXPECT_EQ(reports[2].trk_deg, 281.1);
  EXPECT_EQ(reports[2].vr_fpm, -256.0);
  EXPECT_EQ(reports[2].callsign, "N611TH");
  std::size_t non_icao = 0, without_address = 0;
  for (const TrackReport& r : reports) {
    non_icao += r.id.front() == '~' ? 1 : 0;
    without_address += r.address ? 0 : 1;
  }
  EXPECT_EQ(non_icao, 1337u);
  EXPECT_EQ(without_address, non_icao);
}

}  // namespace
}  // namespace kew::protocol
