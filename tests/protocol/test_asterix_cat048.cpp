// CAT048 records one field at a time (tests/protocol/asterix_writer.hpp builds them):
// which site places a plot, and a refusal that names the radar without one; the track
// number as identity and the address as attribute; the track status bits.

#include <gtest/gtest.h>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "asterix_writer.hpp"
#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "kew/protocol/asterix/uap.hpp"

namespace kew::protocol {
namespace {

using namespace asterix_writer;

TEST(AsterixCat048Sites, APlotOfARadarWithoutASiteIsRefusedNamingItsSacAndSic) {
  // A new user with a recording of an unknown radar must learn which [[radar]] to add.
  auto decoder = make_asterix_decoder(AsterixFraming::Datagram, {});
  std::vector<std::string> messages;
  decoder->rejections().set_reporter([&](std::string_view, std::string_view m) { messages.emplace_back(m); });
  const Bytes block = data_block(48, {minimal_cat048(5, std::nullopt).bytes()});
  std::size_t reports = 0;
  decoder->feed(std::as_bytes(std::span<const std::uint8_t>(block)), [&](const TrackReport&) { ++reports; });
  EXPECT_EQ(reports, 0U);
  EXPECT_EQ(decoder->rejections().count("cat048_unknown_radar"), 1U);
  ASSERT_EQ(messages.size(), 1U);
  EXPECT_NE(messages[0].find("SAC 25 SIC 7"), std::string::npos) << messages[0];
  EXPECT_NE(messages[0].find("sac = 25, sic = 7"), std::string::npos) << messages[0];
}

TEST(AsterixCat048Identity, TrackNumberIsTheIdentityAndTheAddressAnAttribute) {
  // As in CAT062: a Mode S address that comes and goes within one radar track must not
  // split it. Only a plot without a track number is keyed by its address.
  Rejections rejections;
  const auto reports = decode_bytes(
      data_block(48, {minimal_cat048(0xF123, 0x4B1812).bytes(),  // spare bits above the 12
                      minimal_cat048(0x0123, std::nullopt).bytes(),
                      minimal_cat048(std::nullopt, 0x4B1812).bytes(),
                      minimal_cat048(std::nullopt, std::nullopt).bytes()}),
      radar_25_7(), &rejections);
  ASSERT_EQ(reports.size(), 3U);
  EXPECT_EQ(reports[0].id, "291");
  EXPECT_EQ(reports[0].address, std::optional<std::uint32_t>(0x4B1812));
  EXPECT_EQ(reports[1].id, "291");
  EXPECT_FALSE(reports[1].address.has_value());
  EXPECT_EQ(reports[2].id, "4B1812");
  EXPECT_EQ(reports[2].address, std::optional<std::uint32_t>(0x4B1812));
  for (const TrackReport& r : reports) EXPECT_EQ(r.source, "cat048/25.7");
  EXPECT_EQ(rejections.count("asterix_missing_identity"), 1U);
  EXPECT_EQ(rejections.total(), 1U);
}

TEST(AsterixCat048TrackStatus, TrackEndIsTreOfTheSecondOctetAndNothingIsCoasting) {
  // I048/170: CNF RAD DOU MAH CDM FX | TRE GHO SUP TCC spare FX. No coasting bit exists.
  struct Case {
    Bytes status;
    bool track_end;
  };
  const std::vector<Case> cases = {
      {{0x00}, false},
      {{0x01, 0x80}, true},
      {{0x7F, 0x7E}, false},  // every other bit (CNF would refuse the record)
  };
  std::vector<Bytes> records;
  for (const Case& c : cases) {
    RecordWriter w = minimal_cat048(5, std::nullopt);
    w.set(asterix::cat048::kTrackStatus, c.status);
    records.push_back(w.bytes());
  }
  const auto reports = decode_every_record(48, records);
  ASSERT_EQ(reports.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    EXPECT_EQ(reports[i].track_end, cases[i].track_end);
    EXPECT_FALSE(reports[i].coasting);
  }
}

}  // namespace
}  // namespace kew::protocol
