// CAT004 encoder: byte-exact records worked out by hand from the CAT004 1.12 item
// definitions, the reader reading them back, block packing, range handling. The check
// against Wireshark's decoder is in test_cat004_tshark.cpp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cat004_test_support.hpp"

namespace kew::protocol {
namespace {

using namespace cat004_test;

AlertEvent warning_alert() {
  AlertEvent e = alert_about_a("9f3c2a");
  e.seq = 7;
  e.b.id = "1042";
  e.b.source = "cat062/25.100";
  e.b.callsign = "EZY45AB";
  e.b.track_number = 513;
  e.t_cpa_s = 63.5;
  e.cpa_h_m = 1234.5;
  e.cpa_v_ft = 300.0;
  e.sep_h_m = 15000.0;
  e.sep_v_ft = 1000.0;
  return e;
}

TEST(Cat004Encoder, StcaRecordIsByteExact) {
  const auto expected = bytes({
      0x04, 0x00, 0x38,                    // CAT 4, LEN 56
      0xDD, 0xF1, 0x60,                    // FSPEC: 010 000 020 040 045 | 030 170 120 070 | 035 171
      0x19, 0x64,                          // 010 SAC 25 SIC 100
      0x07,                                // 000 STCA
      0x64, 0x00, 0x20,                    // 020 51200.25 s × 128
      0x12, 0x34,                          // 040 alert number
      0x04,                                // 045 STAT 2 (warning) in bits 3–1
      0x00, 0x0C,                          // 030 track number 12
      0x80,                                // 170 FSPEC: AI
      'B', 'A', 'W', '1', '2', '3', ' ',   //   AI
      0x50,                                // 120 FSPEC: CC, CD
      0x19,                                //   CC: TID 1, CPC LPF, CS HIGH
      0x00, 0x05, 0x00,                    //   CD 10 s × 128
      0xFC,                                // 070 FSPEC: TC TCA CHS MHS CVS MVS
      0x00, 0x14, 0x80,                    //   TC 41 s × 128
      0x00, 0x1F, 0xC0,                    //   TCA 63.5 s × 128
      0x00, 0x75, 0x30,                    //   CHS 15000 m × 2
      0x09, 0xA5,                          //   MHS 1234.5 m × 2
      0x00, 0x28,                          //   CVS 1000 ft / 25
      0x00, 0x0C,                          //   MVS 300 ft / 25
      0x02, 0x01,                          // 035 track number 513
      0x80,                                // 171 FSPEC: AI
      'E', 'Z', 'Y', '4', '5', 'A', 'B',   //   AI
  });
  EXPECT_EQ(hex(encoded(warning_alert())), hex(expected));
}

TEST(Cat004Encoder, EndOfConflictCarriesOnlyTheIdentifiers) {
  AlertEvent e = warning_alert();
  e.state = AlertState::End;
  e.end_reason = AlertEndReason::Cleared;
  EXPECT_EQ(hex(encoded(e)), hex(bytes({
                                 0x04, 0x00, 0x13,  // CAT 4, LEN 19
                                 0xDD, 0x81, 0x40,  // 010 000 020 040 045 | 030 | 035
                                 0x19, 0x64,        // 010
                                 0x11,              // 000 End Of Conflict (17)
                                 0x64, 0x00, 0x20,  // 020
                                 0x12, 0x34,        // 040
                                 0x00,              // 045 STAT 0: ended
                                 0x00, 0x0C,        // 030
                                 0x02, 0x01,        // 035
                             })));
}

TEST(Cat004Encoder, AliveRecordCarriesFunctionAndSystemStatus) {
  Cat004Options o = options();
  o.sdps = Cat004SourceId{25, 7};
  Cat004Encoder encoder(o);
  ASSERT_TRUE(encoder.add_alive({kT, false, false, false}));
  ASSERT_TRUE(encoder.add_alive({kT, true, false, true}));
  const auto datagrams = encoder.take_datagrams();
  ASSERT_EQ(datagrams.size(), 1u);  // both records in one data block
  EXPECT_EQ(hex(datagrams[0]), hex(bytes({
                                   0x04, 0x00, 0x1A,              // CAT 4, LEN 26
                                   0xF2,                          // 010 000 015 020 060
                                   0x19, 0x64, 0x01,              // 010, 000 Alive
                                   0x01, 0x19, 0x07,              // 015: 1 × SAC 25 SIC 7
                                   0x64, 0x00, 0x20,              // 020
                                   0x02,                          // 060: STCA
                                   0xF2, 0x19, 0x64, 0x01, 0x01, 0x19, 0x07, 0x64, 0x00, 0x20,
                                   0x03, 0x0A,                    // 060: STCA | DG, OL
                               })));
}

TEST(Cat004Encoder, ReaderReadsBackWhatWasEncoded) {
  Cat004Encoder encoder(options());
  ASSERT_TRUE(encoder.add_alive({kT + 1.0, true, true, false}));
  ASSERT_TRUE(encoder.add_alert(warning_alert()));
  const auto datagrams = encoder.take_datagrams();
  ASSERT_EQ(datagrams.size(), 1u);

  Cat004Reader reader;
  const auto records = read_all(datagrams[0], reader);
  EXPECT_EQ(reader.rejections().total(), 0u);
  ASSERT_EQ(records.size(), 2u);

  const Cat004Record& alive = records[0];
  EXPECT_EQ(alive.message_type, 1);
  ASSERT_TRUE(alive.time_of_day_s);
  EXPECT_DOUBLE_EQ(*alive.time_of_day_s, 51201.25);
  EXPECT_EQ(alive.function_status, (std::vector<std::uint8_t>{0x03, 0x0C}));

  const Cat004Record& r = records[1];
  ASSERT_TRUE(r.source);
  EXPECT_EQ(r.source->sac, 25);
  EXPECT_EQ(r.source->sic, 100);
  EXPECT_EQ(r.message_type, 7);
  EXPECT_EQ(r.alert_id, 0x1234);
  EXPECT_EQ(r.alert_status, 2);
  EXPECT_EQ(r.track_number_1, 12);
  EXPECT_EQ(r.track_number_2, 513);
  ASSERT_TRUE(r.aircraft_1 && r.aircraft_2);
  EXPECT_EQ(r.aircraft_1->identifier, "BAW123");
  EXPECT_FALSE(r.aircraft_1->mode_s_identification);
  EXPECT_EQ(r.aircraft_2->identifier, "EZY45AB");
  EXPECT_EQ(r.time_to_conflict_s, 41.0);
  EXPECT_EQ(r.time_to_closest_approach_s, 63.5);
  EXPECT_EQ(r.current_horizontal_separation_m, 15000.0);
  EXPECT_EQ(r.minimum_horizontal_separation_m, 1234.5);
  EXPECT_EQ(r.current_vertical_separation_ft, 1000.0);
  EXPECT_EQ(r.minimum_vertical_separation_ft, 300.0);
  EXPECT_EQ(r.conflict_classification, 0x19);
  ASSERT_TRUE(r.stca_filters);
  EXPECT_TRUE(r.stca_filters->linear_prediction);
  EXPECT_FALSE(r.stca_filters->current_proximity);
  EXPECT_FALSE(r.stca_filters->manoeuvre_hazard);
  EXPECT_EQ(r.conflict_duration_s, 10.0);
}

// I004/120 CC, TID 1 (bits 8–5): the Conflict Properties Class (bits 4–2) has one filter
// bit for the hypothesis that found the conflict; CS (bit 1) is HIGH from warning up.
TEST(Cat004Encoder, ConflictClassificationNamesTheFilterOfTheHypothesis) {
  struct Case {
    Hypothesis hypothesis;
    Severity severity;
    unsigned cc;
    Cat004StcaFilters filters;  // LPF, CPF, MHF
  };
  const std::vector<Case> cases{
      {Hypothesis::Linear, Severity::Warning, 0x19, {true, false, false}},
      {Hypothesis::LevelOff, Severity::Caution, 0x18, {true, false, false}},
      {Hypothesis::Turn, Severity::Warning, 0x13, {false, false, true}},
      {Hypothesis::Proximity, Severity::Loss, 0x15, {false, true, false}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(to_string(c.hypothesis)));
    AlertEvent e = warning_alert();
    e.hypothesis = c.hypothesis;
    e.severity = c.severity;
    e.region = "north";  // not in CAT004: the record is the same length
    Cat004Encoder encoder(options());
    ASSERT_TRUE(encoder.add_alert(e));
    const auto datagram = encoder.take_datagrams().at(0);
    ASSERT_EQ(datagram.size(), 56u);
    // Block header (3), FSPEC (3), 010 000 020 040 045 030 (11), 170 (8), 120's FSPEC (1).
    EXPECT_EQ(static_cast<unsigned>(datagram[26]), c.cc);

    Cat004Reader reader;
    const auto records = read_all(datagram, reader);
    ASSERT_EQ(records.size(), 1u);
    EXPECT_EQ(records[0].conflict_classification, c.cc);
    ASSERT_TRUE(records[0].stca_filters);
    EXPECT_EQ(records[0].stca_filters->linear_prediction, c.filters.linear_prediction);
    EXPECT_EQ(records[0].stca_filters->current_proximity, c.filters.current_proximity);
    EXPECT_EQ(records[0].stca_filters->manoeuvre_hazard, c.filters.manoeuvre_hazard);
  }
}

TEST(Cat004Encoder, FiguresAreRoundedToTheItemResolution) {
  AlertEvent e = warning_alert();
  e.t_los_s = 12.3456;  // 1/128 s
  e.sep_h_m = 100.26;   // 0.5 m
  e.cpa_v_ft = 312.4;   // 25 ft
  Cat004Encoder encoder(options());
  ASSERT_TRUE(encoder.add_alert(e));
  Cat004Reader reader;
  const auto records = read_all(encoder.take_datagrams().at(0), reader);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_DOUBLE_EQ(*records[0].time_to_conflict_s, 1580.0 / 128.0);
  EXPECT_DOUBLE_EQ(*records[0].current_horizontal_separation_m, 100.5);
  EXPECT_DOUBLE_EQ(*records[0].minimum_vertical_separation_ft, 300.0);
}

TEST(Cat004Encoder, OutOfRangeFiguresSaturateAndNonFiniteOnesAreLeftOut) {
  AlertEvent e = warning_alert();
  e.cpa_h_m = 1.0e6;  // MHS holds at most 32767.5 m
  e.sep_h_m = -5.0;   // separations are >= 0
  e.t_cpa_s = std::numeric_limits<double>::quiet_NaN();
  e.a.callsign.clear();  // no I004/170 at all
  Cat004Encoder encoder(options());
  ASSERT_TRUE(encoder.add_alert(e));
  Cat004Reader reader;
  const auto records = read_all(encoder.take_datagrams().at(0), reader);
  ASSERT_EQ(records.size(), 1u);
  const Cat004Record& r = records[0];
  EXPECT_EQ(r.minimum_horizontal_separation_m, 32767.5);
  EXPECT_EQ(r.current_horizontal_separation_m, 0.0);
  EXPECT_FALSE(r.time_to_closest_approach_s);
  EXPECT_EQ(r.time_to_conflict_s, 41.0);
  EXPECT_FALSE(r.aircraft_1);
  EXPECT_TRUE(r.aircraft_2);
}

TEST(Cat004Encoder, CallsignsAreFittedToTheirSubfields) {
  AlertEvent e = warning_alert();
  e.a.callsign = "ABCDEFGH";  // 8 characters: AI keeps 7
  e.b.callsign = "ab-1\x01";  // a control byte becomes a space
  Cat004Encoder encoder(options());
  ASSERT_TRUE(encoder.add_alert(e));
  Cat004Reader reader;
  const auto records = read_all(encoder.take_datagrams().at(0), reader);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].aircraft_1->identifier, "ABCDEFG");
  EXPECT_EQ(records[0].aircraft_2->identifier, "ab-1");
}

TEST(Cat004Encoder, TimeOfDayWrapsAtMidnight) {
  EXPECT_DOUBLE_EQ(cat004_time_of_day(86400.0 * 19000 + 5.5), 5.5);
  EXPECT_DOUBLE_EQ(cat004_time_of_day(-1.0), 86399.0);
  Cat004Encoder encoder(options());
  ASSERT_TRUE(encoder.add_alive({86400.0 * 19000 - 0.001, false, false, false}));
  Cat004Reader reader;
  const auto records = read_all(encoder.take_datagrams().at(0), reader);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].time_of_day_s, 0.0);  // 23:59:59.999 rounds to 24:00 = 00:00
}

TEST(Cat004Encoder, NonFiniteTimeIsRejectedAndCounted) {
  Cat004Encoder encoder(options());
  AlertEvent e = warning_alert();
  e.t = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(encoder.add_alert(e));
  EXPECT_FALSE(encoder.add_alive({std::nan(""), false, false, false}));
  EXPECT_TRUE(encoder.empty());
  EXPECT_EQ(encoder.rejections().count("cat004_bad_time"), 2u);
}

TEST(Cat004Encoder, RecordsArePackedIntoDatagramsUpToTheLimit) {
  Cat004Options o = options();
  o.max_datagram_bytes = 300;
  Cat004Encoder encoder(o);
  constexpr int kAlerts = 12;  // 53 bytes each: 5 per 300-byte datagram
  for (int i = 0; i < kAlerts; ++i) {
    AlertEvent e = warning_alert();
    e.number = static_cast<std::uint16_t>(i);
    ASSERT_TRUE(encoder.add_alert(e));
  }
  const auto datagrams = encoder.take_datagrams();
  EXPECT_TRUE(encoder.empty());
  ASSERT_EQ(datagrams.size(), 3u);  // 5 + 5 + 2
  Cat004Reader reader;
  std::vector<std::uint16_t> numbers;
  for (const auto& d : datagrams) {
    EXPECT_LE(d.size(), 300u);
    EXPECT_EQ(static_cast<std::size_t>(d[1]) << 8 | static_cast<std::size_t>(d[2]), d.size());
    for (const auto& r : read_all(d, reader)) numbers.push_back(*r.alert_id);
  }
  EXPECT_EQ(numbers, (std::vector<std::uint16_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
  EXPECT_EQ(datagrams[0].size(), 3u + 5u * 53u);
  EXPECT_EQ(datagrams[2].size(), 3u + 2u * 53u);
}

// Subfields kew does not send, worked out by hand from the item definitions.
TEST(Cat004Reader, DecodesModeSIdentificationModeAAndPredictedPosition) {
  Cat004Reader reader;
  const auto records = read_all(
      bytes({
          0x04, 0x00, 0x1E,                    // CAT 4, LEN 30
          0xC1, 0xC0,                          // 010 000 | 030 170
          0x00, 0x01, 0x07, 0x0C, 0x3A,        // SAC 0 SIC 1, STCA, track 3130
          0x61, 0x80,                          // 170 FSPEC: M3 CPW | MS
          0x0F, 0xC0,                          //   M3 7700 (octal)
          0x00, 0x80, 0x00, 0x00,              //   CPW lat 45° = 2^23 × 180/2^25
          0xFF, 0x00, 0x00, 0x00,              //       lon −90°
          0x05, 0x78,                          //       alt 1400 × 25 ft
          0x08, 0x15, 0xF1, 0xCB, 0x38, 0x20,  //   MS "BAW123  ", 6-bit ICAO characters
      }),
      reader);
  EXPECT_EQ(reader.rejections().total(), 0u);
  ASSERT_EQ(records.size(), 1u);
  ASSERT_TRUE(records[0].aircraft_1);
  const Cat004Aircraft& a = *records[0].aircraft_1;
  EXPECT_FALSE(a.identifier);
  EXPECT_EQ(a.mode3a, 07700);
  EXPECT_EQ(a.predicted_lat_deg, 45.0);
  EXPECT_EQ(a.predicted_lon_deg, -90.0);
  EXPECT_EQ(a.predicted_alt_ft, 35000.0);
  EXPECT_EQ(a.mode_s_identification, "BAW123");
  EXPECT_EQ(records[0].track_number_1, 3130);
}

// The CPC bits are LPF, CPF, MHF only under TID 1 of an STCA message.
TEST(Cat004Reader, DecodesStcaFiltersOnlyInTheirTable) {
  const auto record_with = [](unsigned message_type, unsigned cc) {
    return bytes({
        0x04, 0x00, 0x0A,           // CAT 4, LEN 10
        0xC1, 0x20,                 // 010 000 | 120
        0x00, 0x01, message_type,   // SAC 0 SIC 1, message type
        0x40, cc,                   // 120 FSPEC: CC
    });
  };
  Cat004Reader reader;
  auto records = read_all(record_with(7, 0x1E), reader);  // STCA, TID 1: all three
  ASSERT_EQ(records.size(), 1u);
  ASSERT_TRUE(records[0].stca_filters);
  EXPECT_TRUE(records[0].stca_filters->linear_prediction);
  EXPECT_TRUE(records[0].stca_filters->current_proximity);
  EXPECT_TRUE(records[0].stca_filters->manoeuvre_hazard);
  records = read_all(record_with(7, 0x08), reader);  // STCA, TID 0: another table
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].conflict_classification, 0x08);
  EXPECT_FALSE(records[0].stca_filters);
  records = read_all(record_with(5, 0x18), reader);  // APW, TID 1: APW severities
  ASSERT_EQ(records.size(), 1u);
  EXPECT_FALSE(records[0].stca_filters);
  EXPECT_EQ(reader.rejections().total(), 0u);
}

TEST(Cat004Reader, RejectsMalformedInputByReason) {
  Cat004Reader reader;
  std::vector<Cat004Record> records;
  const auto sink = [&](const Cat004Record& r) { records.push_back(r); };
  reader.read(bytes({0x04, 0x00, 0x09, 0x80, 0x01}), sink);  // length past the end
  reader.read(bytes({0x04, 0x00, 0x02}), sink);              // length below the header
  reader.read(bytes({0x30, 0x00, 0x04, 0x00}), sink);        // CAT048: not ours
  reader.read(bytes({0x04, 0x00, 0x05, 0xC0, 0x19}), sink);  // 010 cut short
  reader.read(bytes({0x04, 0x00, 0x06, 0x01, 0x01, 0x09}), sink);  // spare FRN 19
  reader.read(bytes({0x04, 0x00, 0x07, 0x01, 0x01, 0x01, 0x01}), sink);  // 4 FSPEC octets
  EXPECT_TRUE(records.empty());
  EXPECT_EQ(reader.rejections().count("cat004_bad_block_length"), 2u);
  EXPECT_EQ(reader.rejections().count("cat004_other_category"), 1u);
  EXPECT_EQ(reader.rejections().count("cat004_malformed_record"), 3u);
}

TEST(Cat004Reader, KeepsTheRecordsBeforeAMalformedOne) {
  Cat004Encoder encoder(options());
  ASSERT_TRUE(encoder.add_alive({kT, false, false, false}));
  auto datagram = encoder.take_datagrams().at(0);
  datagram.push_back(std::byte{0xC0});  // a second record announcing 010 and 000, then nothing
  datagram[2] = static_cast<std::byte>(datagram.size());
  Cat004Reader reader;
  EXPECT_EQ(read_all(datagram, reader).size(), 1u);
  EXPECT_EQ(reader.rejections().count("cat004_malformed_record"), 1u);
}

}  // namespace
}  // namespace kew::protocol
