// SBS-1 BaseStation decoder: merge rules, time, bad lines, golden values on the bundled
// excerpt of recordings/sbs-japan (expected values from python3, see tests/data/text/SOURCE.md).
#include <gtest/gtest.h>

#include "kew/protocol/sbs.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::decode_all;

// 2024-04-29 14:13:20 UTC.
constexpr double kT0 = 1714400000.0;

std::string msg(int type, const std::string& hex, const std::string& time,
                const std::string& rest_from_callsign) {
  return "MSG," + std::to_string(type) + ",1,1," + hex + ",1,2024/04/29," + time +
         ",2024/04/29," + time + "," + rest_from_callsign + "\n";
}
// Fields 11..22: callsign, alt, gs, track, lat, lon, vrate, squawk, alert, emerg, spi, ground.
std::string position(const std::string& hex, const std::string& time, const std::string& alt,
                     const std::string& lat, const std::string& lon, const std::string& ground = "0") {
  return msg(3, hex, time, "," + alt + ",,," + lat + "," + lon + ",,,0,0,0," + ground);
}
std::string velocity(const std::string& hex, const std::string& time, const std::string& gs,
                     const std::string& track, const std::string& rate) {
  return msg(4, hex, time, ",," + gs + "," + track + ",,," + rate + ",,,,,0");
}
std::string identification(const std::string& hex, const std::string& time, const std::string& cs) {
  return msg(1, hex, time, cs + ",,,,,,,,,,,0");
}
std::string squawk(const std::string& hex, const std::string& time, const std::string& code) {
  return msg(6, hex, time, ",,,,,,," + code + ",0,0,0,0");
}

TEST(SbsDecoder, PositionCarriesLatestVelocityCallsignAndSquawkOfItsAddress) {
  auto decoder = make_sbs_decoder();
  const auto reports = decode_all(
      *decoder, velocity("4ca123", "14:13:18.000", "450", "270.5", "-64") +
                    identification("4ca123", "14:13:19.000", "BAW123  ") +
                    squawk("4ca123", "14:13:19.500", "7700") +
                    velocity("3c6dc5", "14:13:19.700", "300", "90", "0") +
                    position("4ca123", "14:13:20.250", "35000", "51.47", "-0.45"));
  ASSERT_EQ(reports.size(), 1u);
  const TrackReport& r = reports[0];
  EXPECT_DOUBLE_EQ(r.t, kT0 + 0.25);
  EXPECT_EQ(r.id, "4CA123");
  EXPECT_EQ(r.address, std::optional<std::uint32_t>(0x4CA123));
  EXPECT_EQ(r.source, "sbs");
  EXPECT_EQ(r.lat_deg, 51.47);
  EXPECT_EQ(r.lon_deg, -0.45);
  EXPECT_EQ(r.alt_ft, 35000.0);
  EXPECT_EQ(r.gs_kt, 450.0);
  EXPECT_EQ(r.trk_deg, 270.5);
  EXPECT_EQ(r.vr_fpm, -64.0);
  EXPECT_EQ(r.callsign, "BAW123");
  EXPECT_EQ(r.mode3a, std::optional<std::uint16_t>(07700));
  EXPECT_FALSE(r.on_ground);
}

TEST(SbsDecoder, VelocityOlderThanTheMaximumAgeIsNotUsed) {
  SbsOptions options;
  options.velocity_max_age_s = 10;
  auto decoder = make_sbs_decoder(options);
  const auto reports =
      decode_all(*decoder, velocity("4CA123", "14:13:00.000", "450", "270", "0") +
                               position("4CA123", "14:13:10.000", "35000", "51", "0") +  // 10 s: used
                               position("4CA123", "14:13:10.001", "35000", "51", "0"));  // too old
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].gs_kt, 450.0);
  EXPECT_FALSE(reports[1].gs_kt);
  EXPECT_FALSE(reports[1].trk_deg);
  EXPECT_FALSE(reports[1].vr_fpm);
}

TEST(SbsDecoder, AddressesAreMergedSeparately) {
  auto decoder = make_sbs_decoder();
  const auto reports =
      decode_all(*decoder, identification("AAAAAA", "14:13:19.000", "ONE") +
                               velocity("AAAAAA", "14:13:19.000", "100", "10", "0") +
                               position("BBBBBB", "14:13:20.000", "1000", "1", "2") +
                               position("AAAAAA", "14:13:20.000", "2000", "3", "4"));
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].id, "BBBBBB");
  EXPECT_EQ(reports[0].callsign, "");
  EXPECT_FALSE(reports[0].gs_kt);
  EXPECT_EQ(reports[1].callsign, "ONE");
  EXPECT_EQ(reports[1].gs_kt, 100.0);
}

TEST(SbsDecoder, NonIcaoAddressHasNoAddressAttribute) {
  // '~' marks a non-ICAO (TIS-B, anonymous) address: its digits name no aircraft.
  auto decoder = make_sbs_decoder();
  const auto reports = decode_all(*decoder, position("4ca123", "14:13:20.000", "1000", "1", "2") +
                                                position("~4ca123", "14:13:21.000", "1000", "1", "2"));
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].address, std::optional<std::uint32_t>(0x4CA123));
  EXPECT_EQ(reports[1].id, "~4CA123");
  EXPECT_FALSE(reports[1].address.has_value());
}

TEST(SbsDecoder, OnGroundFlagAndUtcOffset) {
  SbsOptions options;
  options.utc_offset_s = 9 * 3600;  // Japan: local = UTC + 9 h
  auto decoder = make_sbs_decoder(options);
  const auto reports = decode_all(*decoder, position("4CA123", "23:13:20.000", "0", "35", "136", "-1") +
                                                position("4CA123", "23:13:21.000", "0", "35", "136", "1") +
                                                position("4CA123", "23:13:22.000", "0", "35", "136", "0"));
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_DOUBLE_EQ(reports[0].t, kT0);  // 23:13:20 JST is 14:13:20 UTC
  EXPECT_TRUE(reports[0].on_ground);
  EXPECT_TRUE(reports[1].on_ground);
  EXPECT_FALSE(reports[2].on_ground);
}

TEST(SbsDecoder, LoggedTimeIsUsedWhenGeneratedTimeIsEmpty) {
  auto decoder = make_sbs_decoder();
  const auto reports = decode_all(
      *decoder, "MSG,3,1,1,4CA123,1,,,2024/04/29,14:13:21.500,,1000,,,10,20,,,0,0,0,0\n");
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_DOUBLE_EQ(reports[0].t, kT0 + 1.5);
}

TEST(SbsDecoder, BadAndIgnoredLinesAreCountedByReasonAndLaterLinesDecoded) {
  auto decoder = make_sbs_decoder();
  std::vector<std::string> messages;
  decoder->rejections().set_reporter(
      [&](std::string_view, std::string_view message) { messages.emplace_back(message); });
  const std::string good = position("4CA123", "14:13:20.000", "1000", "1", "2");
  const std::string input =
      good +                                                                    // line 1
      "MSG,5,1,1,4CA123,1,2024/04/29,14:13:20.000,2024/04/29,14:13:20.000,,1000,,,,,,,0,,0,0\n" +
      "MSG,8,1,1,4CA123,1,2024/04/29,14:13:20.000,2024/04/29,14:13:20.000,,,,,,,,,,,,0\n" +
      "STA,,1,1,4CA123,1,2024/04/29,14:13:20.000,2024/04/29,14:13:20.000,RM\n" +  // 4 ignored
      "hello world\n" +                                                          // 5 malformed
      "MSG,9,1,1,4CA123,1,2024/04/29,14:13:20.000,2024/04/29,14:13:20.000\n" +  // 6 malformed
      "MSG,3,1,1\n" +                                                           // 7 malformed
      position("4CA12G", "14:13:20.000", "1000", "1", "2") +                    // 8 bad_address
      position("4CA123", "25:13:20.000", "1000", "1", "2") +                    // 9 bad_time
      position("4CA123", "14:13:20.000", "1000", "", "2") +                     // 10 no_position
      position("4CA123", "14:13:20.000", "", "1", "2") +                        // 11 no_altitude
      position("4CA123", "14:13:20.000", "1000", "1x", "2") +                   // 12 bad_number
      position("4CA123", "14:13:20.000", "1000", "nan", "2") +                  // 13 bad_number
      position("4CA123", "14:13:20.000", "1000", "95", "2") +                   // 14 lat range
      velocity("4CA123", "14:13:20.000", "fast", "1", "2") +                    // 15 bad_number
      squawk("4CA123", "14:13:20.000", "9999") +                                // 16 bad_mode3a
      good;                                                                     // 17
  const auto reports = decode_all(*decoder, input);
  EXPECT_EQ(reports.size(), 2u);
  const Rejections& r = decoder->rejections();
  EXPECT_EQ(r.by_reason(), (test::Counts{{"bad_address", 1}, {"bad_mode3a", 1}, {"bad_number", 3},
                                          {"bad_time", 1}, {"ignored_message_type", 3},
                                          {"lat_out_of_range", 1}, {"malformed_line", 3},
                                          {"no_altitude", 1}, {"no_position", 1}}));
  ASSERT_EQ(messages.size(), 15u);
  EXPECT_NE(messages[3].find("sbs line 5"), std::string::npos) << messages[3];
  EXPECT_NE(messages[14].find("sbs line 16"), std::string::npos) << messages[14];
}

TEST(SbsDecoder, FullAddressTableForgetsStaleAddressesThenPassesPositionsUnmerged) {
  SbsOptions options;
  options.max_addresses = 2;
  options.address_stale_after_s = 60;
  auto decoder = make_sbs_decoder(options);
  const auto reports =
      decode_all(*decoder, identification("AAAAAA", "14:00:00.000", "OLD") +
                               identification("BBBBBB", "14:13:00.000", "B") +
                               identification("CCCCCC", "14:13:10.000", "C") +   // evicts AAAAAA
                               identification("DDDDDD", "14:13:20.000", "D") +   // table full
                               position("DDDDDD", "14:13:20.000", "1000", "1", "2") +
                               position("CCCCCC", "14:13:20.000", "1000", "1", "2"));
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].callsign, "");
  EXPECT_EQ(reports[1].callsign, "C");
  EXPECT_EQ(decoder->rejections().count("address_table_full"), 2u);
}

TEST(SbsDecoder, BundledJapanExcerptGolden) {
  auto decoder = make_sbs_decoder();
  const auto reports =
      decode_all(*decoder, test::read_file(test::bundled_path("sbs_japan_13501-16500.csv")));
  const auto summary = test::summarize(reports);
  EXPECT_EQ(summary.count, 442u);
  EXPECT_EQ(summary.ids, (std::set<std::string>{"4D2322", "76CCD0", "7816BE", "861B47", "869582",
                                                "86E488", "A3B1A0"}));
  EXPECT_NEAR(summary.t_min, 1641683541.994, 1e-6);  // 2022-01-08 23:12:21.994 as UTC
  EXPECT_NEAR(summary.t_max, 1641685156.480, 1e-6);
  EXPECT_EQ(decoder->rejections().count("ignored_message_type"), 1429u);
  EXPECT_EQ(decoder->rejections().total(), 1429u);

  const TrackReport& first = reports.front();
  EXPECT_EQ(first.id, "7816BE");
  EXPECT_EQ(first.lat_deg, 34.48801);
  EXPECT_EQ(first.lon_deg, 134.47389);
  EXPECT_EQ(first.alt_ft, 34000.0);
  EXPECT_EQ(first.gs_kt, 371.0);
  EXPECT_EQ(first.trk_deg, 258.0);
  EXPECT_EQ(first.vr_fpm, 0.0);
  EXPECT_EQ(first.callsign, "");

  const TrackReport& second = reports[1];  // no MSG,4 within 10 s yet, squawk already known
  EXPECT_EQ(second.id, "86E488");
  EXPECT_FALSE(second.gs_kt);
  EXPECT_EQ(second.mode3a, std::optional<std::uint16_t>(03205));
  EXPECT_EQ(second.alt_ft, 32000.0);

  const TrackReport& hundredth = reports[100];
  EXPECT_EQ(hundredth.id, "869582");
  EXPECT_NEAR(hundredth.t, 1641683664.891, 1e-6);
  EXPECT_EQ(hundredth.lat_deg, 34.88741);
  EXPECT_EQ(hundredth.lon_deg, 135.14214);
  EXPECT_EQ(hundredth.callsign, "ANA967");
  EXPECT_EQ(hundredth.mode3a, std::optional<std::uint16_t>(03615));
  EXPECT_EQ(hundredth.gs_kt, 374.0);
  EXPECT_EQ(hundredth.trk_deg, 257.0);

  const TrackReport& last = reports.back();
  EXPECT_EQ(last.id, "861B47");
  EXPECT_EQ(last.callsign, "ANA8517");
  EXPECT_EQ(last.lat_deg, 34.81);
  EXPECT_EQ(last.gs_kt, 355.0);

  std::size_t without_velocity = 0, with_callsign = 0;
  for (const TrackReport& r : reports) {
    without_velocity += r.gs_kt ? 0 : 1;
    with_callsign += r.callsign.empty() ? 0 : 1;
  }
  EXPECT_EQ(without_velocity, 16u);
  EXPECT_EQ(with_callsign, 381u);
}

TEST(SbsDecoder, IsIncremental) {
  std::string input = test::read_file(test::bundled_path("sbs_japan_13501-16500.csv"));
  input.resize(120000);  // cut mid-line: the last line is truncated
  input += "\ngarbage line\n";
  input += position("4CA123", "14:13:20.000", "1000", "1", "2");
  test::expect_incremental([] { return make_sbs_decoder(); }, input);
}

TEST(SbsDecoder, SharedJapanRecordingWhole) {
  const std::string path = test::shared_path("sbs-japan/adsb202201082242.csv");
  if (!test::exists(path)) GTEST_SKIP() << "shared recordings absent: " << path;
  SbsOptions options;
  options.utc_offset_s = 9 * 3600;  // the receiver was in Japan (JST, UTC+9)
  auto decoder = make_sbs_decoder(options);
  const auto reports = decode_all(*decoder, test::read_file(path));
  const auto summary = test::summarize(reports);
  // MANIFEST: 30,796 MSG lines, 4,884 MSG,3 with position, 15 addresses with positions.
  EXPECT_EQ(summary.count, 4884u);
  EXPECT_EQ(summary.ids.size(), 15u);
  EXPECT_NEAR(summary.t_min, 1641649335.605, 1e-6);  // 2022-01-08 22:42:15.605 JST
  EXPECT_NEAR(summary.t_max, 1641656076.964, 1e-6);  // 2022-01-09 00:34:36.964 JST
  // MSG,5 (8,430), MSG,7 (1,440), MSG,8 (4,375) are the only refusals.
  EXPECT_EQ(decoder->rejections().count("ignored_message_type"), 14245u);
  EXPECT_EQ(decoder->rejections().total(), 14245u);
}

}  // namespace
}  // namespace kew::protocol
