// CAT004 Area Proximity Warning (message type 5, edition 1.12): byte-exact records worked
// out by hand from the item definitions (I004/100 AN in 6-bit ICAO characters, the CC
// case (5, 1) of I004/120), the end of an APW alert, the Alive APW bit, and a seeded
// random round trip of both kinds of alert through the encoder and the reader. The check
// against Wireshark's decoder is in test_cat004_tshark.cpp.

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cat004_test_support.hpp"

namespace kew::protocol {
namespace {

using namespace cat004_test;

AlertEvent apw_warning() {
  AlertEvent e = alert_about_a("7d01e2");
  e.kind = AlertKind::Apw;
  e.volume = "EDR205A";  // t_los_s: the time to the entry into the volume
  e.volume_kind = "restricted";
  return e;
}

Cat004Record encode_and_read(const AlertEvent& e) {
  Cat004Reader reader;
  const auto records = read_all(encoded(e), reader);
  EXPECT_EQ(reader.rejections().total(), 0u);
  EXPECT_EQ(records.size(), 1u);
  return records.empty() ? Cat004Record{} : records[0];
}

TEST(Cat004Apw, RecordIsByteExact) {
  const auto expected = bytes({
      0x04, 0x00, 0x29,                    // CAT 4, LEN 41
      0xDD, 0xF1, 0x80,                    // FSPEC: 010 000 020 040 045 | 030 170 120 070 | 100
      0x19, 0x64,                          // 010 SAC 25 SIC 100
      0x05,                                // 000 APW
      0x64, 0x00, 0x20,                    // 020 51200.25 s × 128
      0x12, 0x34,                          // 040 alert number
      0x04,                                // 045 STAT 2 (warning) in bits 3–1
      0x00, 0x0C,                          // 030 track number 12
      0x80,                                // 170 FSPEC: AI
      'B', 'A', 'W', '1', '2', '3', ' ',   //   AI
      0x50,                                // 120 FSPEC: CC, CD
      0x13,                                //   CC: TID 1, CPC 1 (APW medium), CS HIGH
      0x00, 0x05, 0x00,                    //   CD 10 s × 128
      0x80,                                // 070 FSPEC: TC only
      0x00, 0x14, 0x80,                    //   TC 41 s × 128
      0x80,                                // 100 FSPEC: AN
      // AN "EDR205A ": E 5, D 4, R 18, '2' 50, '0' 48, '5' 53, A 1, space 32, 6 bits each:
      // 000101 000100 010010 110010 | 110000 110101 000001 100000
      0x14, 0x44, 0xB2, 0xC3, 0x50, 0x60,
  });
  EXPECT_EQ(hex(encoded(apw_warning())), hex(expected));
}

// End Of Conflict serves every safety net: an APW alert ends with it, with the one track
// number (I004/035 names the second track of a pair; an APW alert has none).
TEST(Cat004Apw, EndOfConflictCarriesTrackNumberOneOnly) {
  AlertEvent e = apw_warning();
  e.state = AlertState::End;
  e.end_reason = AlertEndReason::Cleared;
  EXPECT_EQ(hex(encoded(e)), hex(bytes({
                                 0x04, 0x00, 0x10,  // CAT 4, LEN 16
                                 0xDD, 0x80,        // 010 000 020 040 045 | 030
                                 0x19, 0x64,        // 010
                                 0x11,              // 000 End Of Conflict (17)
                                 0x64, 0x00, 0x20,  // 020
                                 0x12, 0x34,        // 040
                                 0x00,              // 045 STAT 0: ended
                                 0x00, 0x0C,        // 030
                             })));
}

TEST(Cat004Apw, ReaderReadsBackWhatWasEncoded) {
  const Cat004Record r = encode_and_read(apw_warning());
  EXPECT_EQ(r.message_type, 5);
  EXPECT_EQ(r.alert_id, 0x1234);
  EXPECT_EQ(r.alert_status, 2);
  EXPECT_EQ(r.track_number_1, 12);
  EXPECT_FALSE(r.track_number_2);
  ASSERT_TRUE(r.aircraft_1);
  EXPECT_EQ(r.aircraft_1->identifier, "BAW123");
  EXPECT_FALSE(r.aircraft_2);
  EXPECT_EQ(r.area_name, "EDR205A");
  EXPECT_EQ(r.conflict_classification, 0x13);
  EXPECT_EQ(r.apw_severity, 1);
  EXPECT_FALSE(r.stca_filters);
  EXPECT_EQ(r.conflict_duration_s, 10.0);
  EXPECT_EQ(r.time_to_conflict_s, 41.0);
  EXPECT_FALSE(r.time_to_closest_approach_s);
  EXPECT_FALSE(r.current_horizontal_separation_m);
  EXPECT_FALSE(r.minimum_horizontal_separation_m);
  EXPECT_FALSE(r.current_vertical_separation_ft);
  EXPECT_FALSE(r.minimum_vertical_separation_ft);
}

// CC case (5, 1): CPC 0 low, 1 medium, 2 high; CS HIGH from warning up, as for STCA.
TEST(Cat004Apw, ConflictClassificationCarriesTheApwSeverity) {
  struct Case {
    Severity severity;
    unsigned cc;
    std::uint8_t level;
  };
  for (const Case& c : {Case{Severity::Caution, 0x10, 0}, Case{Severity::Warning, 0x13, 1},
                        Case{Severity::Loss, 0x15, 2}}) {
    SCOPED_TRACE(std::string(to_string(c.severity)));
    AlertEvent e = apw_warning();
    e.severity = c.severity;
    const Cat004Record r = encode_and_read(e);
    EXPECT_EQ(r.conflict_classification, c.cc);
    EXPECT_EQ(r.apw_severity, c.level);
    EXPECT_EQ(r.alert_status, static_cast<std::uint8_t>(c.severity));
  }
}

TEST(Cat004Apw, InsideTheVolumeTheTimeToConflictIsZero) {
  AlertEvent e = apw_warning();
  e.severity = Severity::Loss;
  e.t_los_s = 0.0;
  EXPECT_EQ(encode_and_read(e).time_to_conflict_s, 0.0);
}

TEST(Cat004Apw, AreaNamesAreFittedToTheIcaoCharacterSet) {
  struct Case {
    std::string volume;
    std::optional<std::string> read;
  };
  const std::vector<Case> cases{
      {"lkr1", "LKR1"},                 // lower case is sent in capitals
      {"LK-D_12", "LK D 12"},           // outside the set: spaces
      {"Prague CTR 2", "PRAGUE C"},     // cut to 8 characters
      {"Zóna 5", "Z NA 5"},             // one space for a two-byte UTF-8 character
      {"  R7", "R7"},                   // left adjusted by the sender, trimmed by the reader
      {"", std::nullopt},               // AN is still sent (mandatory): 8 spaces
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.volume);
    AlertEvent e = apw_warning();
    e.volume = c.volume;
    const Cat004Record r = encode_and_read(e);
    EXPECT_EQ(r.area_name, c.read);
  }
  AlertEvent blank = apw_warning();
  blank.volume.clear();
  Cat004Encoder encoder(options());
  ASSERT_TRUE(encoder.add_alert(blank));
  const auto datagram = encoder.take_datagrams().at(0);
  ASSERT_EQ(datagram.size(), 41u);  // the same length: AN is there
  EXPECT_EQ(static_cast<unsigned>(datagram[34]), 0x80);  // 100 FSPEC: AN
  // Eight spaces (32 = 100000): 0x82 0x08 0x20 twice.
  EXPECT_EQ(hex(std::vector<std::byte>(datagram.begin() + 35, datagram.end())), "82 08 20 82 08 20");
}

TEST(Cat004Apw, AliveSaysWhetherTheApwFunctionRuns) {
  Cat004Encoder encoder(options());
  Cat004Alive alive{kT, false, false, false};
  alive.apw = true;
  ASSERT_TRUE(encoder.add_alive(alive));
  alive.degraded = true;
  ASSERT_TRUE(encoder.add_alive(alive));
  const auto datagram = encoder.take_datagrams().at(0);
  Cat004Reader reader;
  const auto records = read_all(datagram, reader);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].function_status, std::vector<std::uint8_t>{0x0A});  // APW, STCA
  EXPECT_EQ(records[1].function_status, (std::vector<std::uint8_t>{0x0B, 0x08}));  // + DG
}

// ---- Seeded random round trip of both kinds ----------------------------------------------

std::string random_text(std::mt19937& random, const std::string& alphabet, std::size_t longest) {
  std::uniform_int_distribution<std::size_t> length(0, longest);
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
  std::string text(length(random), ' ');
  for (char& c : text) c = alphabet[pick(random)];
  return text;
}

/// What the reader must return for a volume name: an independent statement of the
/// encoding rule (capitals, digits, spaces; one space per other character; 8 at most).
std::optional<std::string> expected_area_name(const std::string& volume) {
  std::string fitted;
  for (const char c : volume) {
    const auto octet = static_cast<unsigned char>(c);
    if (fitted.size() == 8) break;
    if (octet >= 0x80 && octet <= 0xBF) continue;
    if (std::isupper(octet) || std::isdigit(octet)) {
      fitted.push_back(c);
    } else if (std::islower(octet)) {
      fitted.push_back(static_cast<char>(std::toupper(octet)));
    } else {
      fitted.push_back(' ');
    }
  }
  const auto first = fitted.find_first_not_of(' ');
  if (first == std::string::npos) return std::nullopt;
  return fitted.substr(first, fitted.find_last_not_of(' ') + 1 - first);
}

std::optional<std::string> expected_identifier(const std::string& callsign) {
  if (callsign.empty()) return std::nullopt;
  std::string fitted = callsign.substr(0, 7);
  const auto first = fitted.find_first_not_of(' ');
  if (first == std::string::npos) return std::nullopt;
  return fitted.substr(first, fitted.find_last_not_of(' ') + 1 - first);
}

double quantised(double value, double lsb) { return std::round(value / lsb) * lsb; }

TEST(Cat004Apw, RandomAlertsOfBothKindsReadBackAsEncoded) {
  std::mt19937 random(20240515);
  std::uniform_real_distribution<double> seconds(0.0, 600.0);
  std::uniform_real_distribution<double> metres(0.0, 30000.0);
  std::uniform_real_distribution<double> feet(0.0, 5000.0);
  std::uniform_int_distribution<int> coin(0, 1);
  std::uniform_int_distribution<int> severity(1, 3);
  std::uniform_int_distribution<int> state(0, 2);
  std::uniform_int_distribution<unsigned> u16(0, 65535);
  const std::string callsign_chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  const std::string volume_chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789 -_/.\xC3\xB3";

  constexpr int kEvents = 500;
  for (int i = 0; i < kEvents; ++i) {
    AlertEvent e;
    e.id = std::to_string(i);
    e.number = static_cast<std::uint16_t>(u16(random));
    e.kind = coin(random) ? AlertKind::Apw : AlertKind::Stca;
    e.state = static_cast<AlertState>(state(random));
    e.severity = static_cast<Severity>(severity(random));
    e.t = kT + seconds(random);
    e.opened_t = e.t - seconds(random);
    e.a.callsign = random_text(random, callsign_chars, 8);
    e.a.track_number = static_cast<std::uint16_t>(u16(random));
    e.hypothesis = static_cast<Hypothesis>(std::uniform_int_distribution<int>(0, 3)(random));
    e.t_los_s = seconds(random);
    if (e.kind == AlertKind::Apw) {
      // A UTF-8 "ó" may be cut in two by random_text: the rule holds for any bytes.
      e.volume = random_text(random, volume_chars, 12);
      e.volume_kind = "danger";
    } else {
      e.b.callsign = random_text(random, callsign_chars, 8);
      e.b.track_number = static_cast<std::uint16_t>(u16(random));
      e.t_cpa_s = e.t_los_s + seconds(random);
      e.cpa_h_m = metres(random);
      e.cpa_v_ft = feet(random);
      e.sep_h_m = metres(random);
      e.sep_v_ft = feet(random);
    }
    SCOPED_TRACE("event " + std::to_string(i) + " kind " + std::string(to_string(e.kind)) +
                 " state " + std::string(to_string(e.state)) + " volume \"" + e.volume + "\"");
    const Cat004Record r = encode_and_read(e);
    const bool apw = e.kind == AlertKind::Apw;
    const bool end = e.state == AlertState::End;

    EXPECT_EQ(r.message_type, end ? 17 : apw ? 5 : 7);
    EXPECT_EQ(r.alert_id, e.number);
    EXPECT_EQ(r.alert_status, end ? 0 : static_cast<int>(e.severity));
    EXPECT_DOUBLE_EQ(*r.time_of_day_s, quantised(cat004_time_of_day(e.t), 1.0 / 128.0));
    EXPECT_EQ(r.track_number_1, e.a.track_number);
    EXPECT_EQ(r.track_number_2, apw ? std::nullopt : std::optional<std::uint16_t>(e.b.track_number));
    EXPECT_FALSE(r.aircraft_2 && apw);
    if (end) {
      EXPECT_FALSE(r.aircraft_1);
      EXPECT_FALSE(r.aircraft_2);
      EXPECT_FALSE(r.has_conflict_characteristics);
      EXPECT_FALSE(r.time_to_conflict_s);
      EXPECT_FALSE(r.area_name);
      continue;
    }
    EXPECT_EQ(r.aircraft_1 ? r.aircraft_1->identifier : std::nullopt, expected_identifier(e.a.callsign));
    if (!apw) {
      EXPECT_EQ(r.aircraft_2 ? r.aircraft_2->identifier : std::nullopt, expected_identifier(e.b.callsign));
    }
    EXPECT_DOUBLE_EQ(*r.time_to_conflict_s, quantised(e.t_los_s, 1.0 / 128.0));
    EXPECT_DOUBLE_EQ(*r.conflict_duration_s, quantised(e.t - e.opened_t, 1.0 / 128.0));
    ASSERT_TRUE(r.conflict_classification);
    EXPECT_EQ(*r.conflict_classification & 0x01, e.severity >= Severity::Warning ? 1 : 0);
    if (apw) {
      EXPECT_EQ(r.apw_severity, static_cast<int>(e.severity) - 1);
      EXPECT_FALSE(r.stca_filters);
      EXPECT_EQ(r.area_name, expected_area_name(e.volume));
      EXPECT_FALSE(r.time_to_closest_approach_s);
      EXPECT_FALSE(r.current_horizontal_separation_m);
      EXPECT_FALSE(r.minimum_vertical_separation_ft);
    } else {
      EXPECT_TRUE(r.stca_filters);
      EXPECT_FALSE(r.apw_severity);
      EXPECT_FALSE(r.area_name);
      EXPECT_DOUBLE_EQ(*r.time_to_closest_approach_s, quantised(e.t_cpa_s, 1.0 / 128.0));
      EXPECT_DOUBLE_EQ(*r.current_horizontal_separation_m, quantised(e.sep_h_m, 0.5));
      EXPECT_DOUBLE_EQ(*r.minimum_horizontal_separation_m, quantised(e.cpa_h_m, 0.5));
      EXPECT_DOUBLE_EQ(*r.current_vertical_separation_ft, quantised(e.sep_v_ft, 25.0));
      EXPECT_DOUBLE_EQ(*r.minimum_vertical_separation_ft, quantised(e.cpa_v_ft, 25.0));
    }
  }
}

}  // namespace
}  // namespace kew::protocol
