// CAT004 against Wireshark's ASTERIX dissector (tshark), design §5.4:
//  - what kew's encoder writes is decoded by tshark to the values encoded, without
//    malformed-packet or expert reports;
//  - the jASTERIX CAT004 test vectors (bundled, GPL-3.0, see tests/data/cat004/SOURCE.md)
//    are read by kew's reader to the values tshark shows.
// The datagrams are wrapped into a pcap (Ethernet/IPv4/UDP, port 8600, the dissector's
// default) by tests/support/tshark.hpp. Without tshark on PATH the tshark checks skip
// loudly; the reader checks on the bundled vectors always run.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "kew/protocol/encoders/cat004.hpp"
#include "kew/protocol/encoders/cat004_reader.hpp"
#include "tshark.hpp"

namespace kew::protocol {
namespace {

using tshark::Datagram;
using tshark::FieldValues;

std::string write_pcap(const std::vector<Datagram>& datagrams, const std::string& name) {
  return tshark::write_pcap(datagrams, ::testing::TempDir() + "kew_" + name + "_" +
                                           std::to_string(::getpid()) + ".pcap");
}

double number(const std::string& text) { return std::strtod(text.c_str(), nullptr); }
long integer(const std::string& text) { return std::strtol(text.c_str(), nullptr, 0); }  // "0x0c"

std::vector<Cat004Record> read_records(const std::vector<Datagram>& datagrams, Cat004Reader& reader) {
  std::vector<Cat004Record> records;
  for (const auto& d : datagrams) reader.read(d, [&](const Cat004Record& r) { records.push_back(r); });
  return records;
}

// ---------------------------------------------------------------------------------------
// kew's encoder → tshark

constexpr double kT = 1714400000.25;  // time of day 51200.25 s

// Alert `number` about aircraft a (BAW123, track 3130), opened at kT, 4 s a number later.
AlertEvent alert_about_a(std::string id, AlertState state, Severity severity, std::uint16_t number) {
  AlertEvent e;
  e.id = std::move(id);
  e.number = number;
  e.state = state;
  e.severity = severity;
  e.t = kT + 4.0 * number;
  e.opened_t = kT;
  e.a.id = "4CA123";
  e.a.callsign = "BAW123";
  e.a.track_number = 3130;
  return e;
}

AlertEvent stca(AlertState state, Severity severity, std::uint16_t number) {
  AlertEvent e = alert_about_a("a1", state, severity, number);
  e.b.id = "3C6586";
  e.b.callsign = "DLH4AB";
  e.b.track_number = 2417;
  e.t_los_s = 41.0;
  e.t_cpa_s = 63.5 + number;
  e.cpa_h_m = 1234.5;
  e.cpa_v_ft = 300.0;
  e.sep_h_m = 15000.0;
  e.sep_v_ft = 1000.0;
  return e;
}

TEST(Cat004Tshark, DecodesEncodedMessagesToTheEncodedValues) {
  KEW_REQUIRE_TSHARK("the CAT004 check");
  Cat004Options options;
  options.sac = 25;
  options.sic = 100;
  options.sdps = Cat004SourceId{25, 7};
  Cat004Encoder encoder(options);
  // Datagram 1: an Alive message. Datagram 2: a new STCA alert and its update in one
  // data block. Datagram 3: the end of the conflict.
  ASSERT_TRUE(encoder.add_alive({kT, true, false, true}));
  std::vector<Datagram> datagrams = encoder.take_datagrams();
  ASSERT_TRUE(encoder.add_alert(stca(AlertState::New, Severity::Caution, 1)));
  ASSERT_TRUE(encoder.add_alert(stca(AlertState::Update, Severity::Warning, 1)));
  for (auto& d : encoder.take_datagrams()) datagrams.push_back(std::move(d));
  AlertEvent end = stca(AlertState::End, Severity::Warning, 1);
  end.end_reason = AlertEndReason::Cleared;
  ASSERT_TRUE(encoder.add_alert(end));
  for (auto& d : encoder.take_datagrams()) datagrams.push_back(std::move(d));
  ASSERT_EQ(datagrams.size(), 3u);

  const std::string pcap = write_pcap(datagrams, "cat004_encoded");
  const std::vector<std::string> fields{
      "asterix.category",          "asterix.004_010_SAC",       "asterix.004_010_SIC",
      "asterix.004_015_SAC",       "asterix.004_015_SIC",       "asterix.004_000_VALUE",
      "asterix.004_020_VALUE",     "asterix.004_040_VALUE",     "asterix.004_045_STAT",
      "asterix.004_060_STCA",      "asterix.004_060_DG",        "asterix.004_060_OF",
      "asterix.004_060_OL",        "asterix.004_030_VALUE",     "asterix.004_035_VALUE",
      "asterix.004_170_AI1_VALUE", "asterix.004_171_AI2_VALUE", "asterix.004_070_TC_VALUE",
      "asterix.004_070_TCA_VALUE",
      "asterix.004_070_CHS_VALUE", "asterix.004_070_MHS_VALUE", "asterix.004_070_CVS_VALUE",
      "asterix.004_070_MVS_VALUE", "asterix.004_120_CC_TID",    "asterix.004_120_CC_CS",
      "asterix.004_120_CD_VALUE",
  };
  const auto frames = tshark::fields(pcap, fields);
  ASSERT_EQ(frames.size(), 3u) << "tshark decoded no frames from " << pcap;

  const FieldValues& alive = frames[0];
  EXPECT_EQ(alive.at("asterix.category"), std::vector<std::string>{"4"});
  EXPECT_EQ(integer(alive.at("asterix.004_010_SAC").at(0)), 25);
  EXPECT_EQ(integer(alive.at("asterix.004_010_SIC").at(0)), 100);
  EXPECT_EQ(integer(alive.at("asterix.004_015_SAC").at(0)), 25);
  EXPECT_EQ(integer(alive.at("asterix.004_015_SIC").at(0)), 7);
  EXPECT_EQ(alive.at("asterix.004_000_VALUE"), std::vector<std::string>{"1"});
  EXPECT_DOUBLE_EQ(number(alive.at("asterix.004_020_VALUE").at(0)), 51200.25);
  EXPECT_EQ(alive.at("asterix.004_060_STCA"), std::vector<std::string>{"1"});
  EXPECT_EQ(alive.at("asterix.004_060_DG"), std::vector<std::string>{"1"});
  EXPECT_EQ(alive.at("asterix.004_060_OF"), std::vector<std::string>{"0"});
  EXPECT_EQ(alive.at("asterix.004_060_OL"), std::vector<std::string>{"1"});

  const FieldValues& alerts = frames[1];  // two records: new (caution), update (warning)
  EXPECT_EQ(alerts.at("asterix.004_000_VALUE"), (std::vector<std::string>{"7", "7"}));
  ASSERT_EQ(alerts.at("asterix.004_020_VALUE").size(), 2u);
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_020_VALUE")[0]), 51204.25);
  EXPECT_EQ(integer(alerts.at("asterix.004_040_VALUE").at(1)), 1);
  EXPECT_EQ(alerts.at("asterix.004_045_STAT"), (std::vector<std::string>{"1", "2"}));
  EXPECT_EQ(integer(alerts.at("asterix.004_030_VALUE").at(0)), 3130);
  EXPECT_EQ(integer(alerts.at("asterix.004_035_VALUE").at(0)), 2417);
  EXPECT_EQ(alerts.at("asterix.004_170_AI1_VALUE").at(0), "BAW123 ");
  EXPECT_EQ(alerts.at("asterix.004_171_AI2_VALUE").at(1), "DLH4AB ");
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_070_TC_VALUE").at(0)), 41.0);
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_070_TCA_VALUE").at(1)), 64.5);
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_070_CHS_VALUE").at(0)), 15000.0);
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_070_MHS_VALUE").at(0)), 1234.5);
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_070_CVS_VALUE").at(0)), 1000.0);
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_070_MVS_VALUE").at(0)), 300.0);
  EXPECT_EQ(alerts.at("asterix.004_120_CC_TID"), (std::vector<std::string>{"1", "1"}));
  EXPECT_EQ(alerts.at("asterix.004_120_CC_CS"), (std::vector<std::string>{"0", "1"}));
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_120_CD_VALUE").at(1)), 4.0);

  const FieldValues& ended = frames[2];
  EXPECT_EQ(ended.at("asterix.004_000_VALUE"), std::vector<std::string>{"17"});
  EXPECT_EQ(integer(ended.at("asterix.004_040_VALUE").at(0)), 1);
  EXPECT_EQ(ended.at("asterix.004_045_STAT"), std::vector<std::string>{"0"});
  EXPECT_EQ(integer(ended.at("asterix.004_030_VALUE").at(0)), 3130);
  EXPECT_EQ(integer(ended.at("asterix.004_035_VALUE").at(0)), 2417);
  EXPECT_TRUE(ended.at("asterix.004_070_TC_VALUE").empty());
  EXPECT_TRUE(ended.at("asterix.004_170_AI1_VALUE").empty());

  EXPECT_EQ(tshark::problems(pcap), "") << "tshark reports malformed frames or expert info";
  std::remove(pcap.c_str());
}

// The filter bits of I004/120 CC (TID 1 of STCA: CPC = LPF, CPF, MHF). Wireshark 4.0's
// dissector shows the Conflict Properties Class as one 3-bit number (the edition's table
// of its meaning per TID is not in it): LPF 4, CPF 2, MHF 1.
TEST(Cat004Tshark, ConflictClassificationCarriesTheFilterOfEachHypothesis) {
  KEW_REQUIRE_TSHARK("the CAT004 filter-bit check");
  const std::vector<Hypothesis> hypotheses{Hypothesis::Linear, Hypothesis::LevelOff,
                                           Hypothesis::Turn, Hypothesis::Proximity};
  Cat004Encoder encoder(Cat004Options{});
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    AlertEvent e = stca(AlertState::Update, i % 2 == 0 ? Severity::Caution : Severity::Loss,
                        static_cast<std::uint16_t>(i + 1));
    e.hypothesis = hypotheses[i];
    e.region = "north";
    ASSERT_TRUE(encoder.add_alert(e));
  }
  const std::vector<Datagram> datagrams = encoder.take_datagrams();
  ASSERT_EQ(datagrams.size(), 1u);
  const std::string pcap = write_pcap(datagrams, "cat004_filters");
  const auto frames = tshark::fields(
      pcap, {"asterix.004_040_VALUE", "asterix.004_120_CC_TID", "asterix.004_120_CC_CP",
             "asterix.004_120_CC_CS"});
  ASSERT_EQ(frames.size(), 1u) << "tshark decoded no frames from " << pcap;
  const FieldValues& f = frames[0];
  std::vector<long> numbers;  // tshark shows the raw 040 in hex, "0x0001"
  for (const std::string& text : f.at("asterix.004_040_VALUE")) numbers.push_back(integer(text));
  EXPECT_EQ(numbers, (std::vector<long>{1, 2, 3, 4}));
  EXPECT_EQ(f.at("asterix.004_120_CC_TID"), (std::vector<std::string>{"1", "1", "1", "1"}));
  // linear: LPF; level_off: LPF; turn: MHF; proximity: CPF.
  EXPECT_EQ(f.at("asterix.004_120_CC_CP"), (std::vector<std::string>{"4", "4", "1", "2"}));
  EXPECT_EQ(f.at("asterix.004_120_CC_CS"), (std::vector<std::string>{"0", "1", "0", "1"}));
  EXPECT_EQ(tshark::problems(pcap), "") << "tshark reports malformed frames or expert info";
  std::remove(pcap.c_str());
}

AlertEvent apw(AlertState state, Severity severity, std::uint16_t number) {
  AlertEvent e = alert_about_a("v1", state, severity, number);
  e.kind = AlertKind::Apw;
  e.t_los_s = severity == Severity::Loss ? 0.0 : 41.0;
  e.volume = "EDR205A";
  e.volume_kind = "restricted";
  return e;
}

// An area proximity warning is message type 5 with the area's name in I004/100 AN (8
// ICAO 6-bit characters, which Wireshark 4.0 decodes as such), aircraft 1 only; its end is
// End Of Conflict (17) with track number 1 only.
TEST(Cat004Tshark, DecodesAnAreaProximityWarningWithItsAreaName) {
  KEW_REQUIRE_TSHARK("the CAT004 APW check");
  Cat004Encoder encoder(Cat004Options{});
  Cat004Alive alive{kT, false, false, false};
  alive.apw = true;
  ASSERT_TRUE(encoder.add_alive(alive));
  std::vector<Datagram> datagrams = encoder.take_datagrams();
  ASSERT_TRUE(encoder.add_alert(apw(AlertState::New, Severity::Warning, 9)));
  AlertEvent inside = apw(AlertState::Update, Severity::Loss, 9);
  inside.volume = "lkr1";  // sent in capitals: the ICAO set has no lower case
  ASSERT_TRUE(encoder.add_alert(inside));
  for (auto& d : encoder.take_datagrams()) datagrams.push_back(std::move(d));
  ASSERT_TRUE(encoder.add_alert(apw(AlertState::End, Severity::Loss, 9)));
  for (auto& d : encoder.take_datagrams()) datagrams.push_back(std::move(d));
  ASSERT_EQ(datagrams.size(), 3u);

  const std::string pcap = write_pcap(datagrams, "cat004_apw");
  const auto frames = tshark::fields(
      pcap, {"asterix.004_000_VALUE", "asterix.004_060_APW", "asterix.004_060_STCA",
             "asterix.004_040_VALUE", "asterix.004_045_STAT", "asterix.004_030_VALUE",
             "asterix.004_035_VALUE", "asterix.004_170_AI1_VALUE", "asterix.004_171_AI2_VALUE",
             "asterix.004_100_AN_VALUE", "asterix.004_120_CC_TID", "asterix.004_120_CC_CP",
             "asterix.004_120_CC_CS", "asterix.004_070_TC_VALUE", "asterix.004_070_TCA_VALUE",
             "asterix.004_070_MHS_VALUE"});
  ASSERT_EQ(frames.size(), 3u) << "tshark decoded no frames from " << pcap;

  EXPECT_EQ(frames[0].at("asterix.004_060_APW"), std::vector<std::string>{"1"});
  EXPECT_EQ(frames[0].at("asterix.004_060_STCA"), std::vector<std::string>{"1"});

  const FieldValues& alerts = frames[1];
  EXPECT_EQ(alerts.at("asterix.004_000_VALUE"), (std::vector<std::string>{"5", "5"}));
  EXPECT_EQ(alerts.at("asterix.004_100_AN_VALUE"), (std::vector<std::string>{"EDR205A ", "LKR1    "}));
  EXPECT_EQ(alerts.at("asterix.004_045_STAT"), (std::vector<std::string>{"2", "3"}));
  EXPECT_EQ(integer(alerts.at("asterix.004_030_VALUE").at(1)), 3130);
  EXPECT_EQ(alerts.at("asterix.004_170_AI1_VALUE"), (std::vector<std::string>{"BAW123 ", "BAW123 "}));
  EXPECT_TRUE(alerts.at("asterix.004_035_VALUE").empty());
  EXPECT_TRUE(alerts.at("asterix.004_171_AI2_VALUE").empty());
  // CC case (5, 1): CPC 1 medium (warning), 2 high (loss); CS HIGH for both.
  EXPECT_EQ(alerts.at("asterix.004_120_CC_TID"), (std::vector<std::string>{"1", "1"}));
  EXPECT_EQ(alerts.at("asterix.004_120_CC_CP"), (std::vector<std::string>{"1", "2"}));
  EXPECT_EQ(alerts.at("asterix.004_120_CC_CS"), (std::vector<std::string>{"1", "1"}));
  ASSERT_EQ(alerts.at("asterix.004_070_TC_VALUE").size(), 2u);
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_070_TC_VALUE")[0]), 41.0);
  EXPECT_DOUBLE_EQ(number(alerts.at("asterix.004_070_TC_VALUE")[1]), 0.0);
  EXPECT_TRUE(alerts.at("asterix.004_070_TCA_VALUE").empty());
  EXPECT_TRUE(alerts.at("asterix.004_070_MHS_VALUE").empty());

  const FieldValues& ended = frames[2];
  EXPECT_EQ(ended.at("asterix.004_000_VALUE"), std::vector<std::string>{"17"});
  EXPECT_EQ(integer(ended.at("asterix.004_040_VALUE").at(0)), 9);
  EXPECT_EQ(integer(ended.at("asterix.004_030_VALUE").at(0)), 3130);
  EXPECT_TRUE(ended.at("asterix.004_035_VALUE").empty());
  EXPECT_TRUE(ended.at("asterix.004_100_AN_VALUE").empty());

  // The names a reader of Wireshark's tree sees.
  const std::string tree = tshark::run("tshark -n -r '" + pcap + "' -V 2>/dev/null");
  EXPECT_NE(tree.find("Message Type: Area Proximity Warning (APW) (5)"), std::string::npos) << tree;
  EXPECT_NE(tree.find("Area Name: EDR205A"), std::string::npos) << tree;
  EXPECT_NE(tree.find("Message Type: End Of Conflict (EOC) (17)"), std::string::npos) << tree;

  EXPECT_EQ(tshark::problems(pcap), "") << "tshark reports malformed frames or expert info";
  std::remove(pcap.c_str());
}

// ---------------------------------------------------------------------------------------
// jASTERIX CAT004 vectors → kew's reader, and tshark

std::vector<Datagram> jasterix_blocks() {
  const std::string path = std::string(KEW_TEST_DATA_DIR) + "/cat004/jasterix-gpl3/cat004ed1.4.bin";
  std::ifstream file(path, std::ios::binary);
  EXPECT_TRUE(file) << "missing bundled fixture " << path;
  const std::vector<char> raw((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  // The file is three data blocks back to back; one datagram each, as a sender would.
  std::vector<Datagram> blocks;
  std::size_t offset = 0;
  while (offset + 3 <= raw.size()) {
    const std::size_t length = static_cast<std::size_t>(static_cast<unsigned char>(raw[offset + 1])) << 8 |
                               static_cast<unsigned char>(raw[offset + 2]);
    if (length < 3 || offset + length > raw.size()) break;
    Datagram block;
    for (std::size_t i = 0; i < length; ++i) block.push_back(static_cast<std::byte>(raw[offset + i]));
    blocks.push_back(std::move(block));
    offset += length;
  }
  EXPECT_EQ(offset, raw.size());
  return blocks;
}

// Values tshark 4.0.17 shows for the three vectors (tests/data/cat004/SOURCE.md).
TEST(Cat004Vectors, ReaderDecodesTheJasterixVectors) {
  const auto blocks = jasterix_blocks();
  ASSERT_EQ(blocks.size(), 3u);
  Cat004Reader reader;
  const auto records = read_records(blocks, reader);
  EXPECT_EQ(reader.rejections().total(), 0u);
  ASSERT_EQ(records.size(), 3u);

  EXPECT_EQ(records[0].source->sac, 0);
  EXPECT_EQ(records[0].source->sic, 1);
  EXPECT_EQ(records[0].message_type, 1);  // Alive
  EXPECT_EQ(records[0].time_of_day_s, 2829.0);
  EXPECT_EQ(records[0].function_status, std::vector<std::uint8_t>{0x0E});  // APW CLAM STCA

  EXPECT_EQ(records[1].message_type, 6);  // CLAM
  EXPECT_EQ(records[1].time_of_day_s, 70666.0);
  EXPECT_EQ(records[1].alert_id, 15496);
  EXPECT_EQ(records[1].track_number_1, 3027);
  EXPECT_FALSE(records[1].track_number_2);

  EXPECT_EQ(records[2].message_type, 7);  // STCA
  EXPECT_EQ(records[2].time_of_day_s, 70658.0);
  EXPECT_EQ(records[2].alert_id, 15497);
  EXPECT_EQ(records[2].alert_status, 3);
  EXPECT_EQ(records[2].track_number_1, 3130);
  EXPECT_EQ(records[2].track_number_2, 2417);
  EXPECT_TRUE(records[2].has_conflict_characteristics);  // an empty I004/120
  EXPECT_FALSE(records[2].conflict_classification);
}

TEST(Cat004Vectors, ReaderAgreesWithTshark) {
  KEW_REQUIRE_TSHARK("the CAT004 check");
  const auto blocks = jasterix_blocks();
  Cat004Reader reader;
  const auto records = read_records(blocks, reader);
  ASSERT_EQ(records.size(), blocks.size());

  const std::string pcap = write_pcap(blocks, "cat004_jasterix");
  const std::vector<std::string> fields{
      "asterix.004_010_SAC",   "asterix.004_010_SIC",   "asterix.004_000_VALUE",
      "asterix.004_020_VALUE", "asterix.004_040_VALUE", "asterix.004_045_STAT",
      "asterix.004_030_VALUE", "asterix.004_035_VALUE", "asterix.004_060_APW",
      "asterix.004_060_CLAM",  "asterix.004_060_STCA",
  };
  const auto frames = tshark::fields(pcap, fields);
  ASSERT_EQ(frames.size(), records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    SCOPED_TRACE("vector " + std::to_string(i + 1));
    const Cat004Record& r = records[i];
    const FieldValues& f = frames[i];
    EXPECT_EQ(integer(f.at("asterix.004_010_SAC").at(0)), r.source->sac);
    EXPECT_EQ(integer(f.at("asterix.004_010_SIC").at(0)), r.source->sic);
    EXPECT_EQ(integer(f.at("asterix.004_000_VALUE").at(0)), *r.message_type);
    EXPECT_DOUBLE_EQ(number(f.at("asterix.004_020_VALUE").at(0)), *r.time_of_day_s);
    const auto optional_field = [&](const std::string& name, auto value) {
      if (value) {
        ASSERT_EQ(f.at(name).size(), 1u) << name;
        EXPECT_EQ(integer(f.at(name)[0]), static_cast<long>(*value)) << name;
      } else {
        EXPECT_TRUE(f.at(name).empty()) << name;
      }
    };
    optional_field("asterix.004_040_VALUE", r.alert_id);
    optional_field("asterix.004_045_STAT", r.alert_status);
    optional_field("asterix.004_030_VALUE", r.track_number_1);
    optional_field("asterix.004_035_VALUE", r.track_number_2);
    if (!r.function_status.empty()) {
      const unsigned octet = r.function_status[0];
      EXPECT_EQ(integer(f.at("asterix.004_060_APW").at(0)), (octet >> 3) & 1);
      EXPECT_EQ(integer(f.at("asterix.004_060_CLAM").at(0)), (octet >> 2) & 1);
      EXPECT_EQ(integer(f.at("asterix.004_060_STCA").at(0)), (octet >> 1) & 1);
    }
  }
  EXPECT_EQ(tshark::problems(pcap), "");
  std::remove(pcap.c_str());
}

}  // namespace
}  // namespace kew::protocol
