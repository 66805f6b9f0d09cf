// Selected altitude (sel_ft, sel_src) and track angle rate (tar_dps) from ASTERIX, design
// §5.2: hand-built records for each validity rule of CAT048 I048/250 (BDS 4,0 and 5,0),
// CAT062 I062/380 (SAL, FSS, TAR) and CAT021 I021/146, 148, 165 (editions 2.x and 0.26);
// then the same values checked against Wireshark's ASTERIX dissector (tshark) on the
// hand-built CAT062 and CAT021 records and on real recordings (the UPC Barcelona CAT048
// hour, read in place from the shared recordings, and the bundled CAT048 and CAT062
// fixtures). tshark 4.0 shows I048/250 only as raw MB data with its BDS1/BDS2: the
// register's bits are read from tshark's MB data here, by this file's own bit numbering
// (ICAO Doc 9871 Tables A-2-64 and A-2-80), independently of cat048.cpp.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "asterix_writer.hpp"
#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "kew/protocol/asterix/record_walker.hpp"
#include "kew/protocol/asterix/uap.hpp"
#include "test_formats_support.hpp"
#include "tshark.hpp"

namespace kew::protocol {
namespace {

using namespace asterix_writer;
using Source = SelectedAltitudeSource;

/// What a record should give: sel_ft (with sel_src) and tar_dps, each or neither.
struct Intent {
  std::optional<double> sel_ft;
  Source sel_src = Source::Mcp;
  std::optional<double> tar_dps;
};

std::string describe(const Intent& i) {
  std::string out = "sel_ft=" + (i.sel_ft ? std::to_string(*i.sel_ft) : std::string("-"));
  if (i.sel_ft) out += " sel_src=" + std::string(to_string(i.sel_src));
  out += " tar_dps=" + (i.tar_dps ? std::to_string(*i.tar_dps) : std::string("-"));
  return out;
}

void expect_intent(const TrackReport& r, const Intent& expected) {
  SCOPED_TRACE("expected " + describe(expected) + ", got " +
               describe({r.sel_ft, r.sel_src, r.tar_dps}));
  EXPECT_EQ(r.sel_ft, expected.sel_ft);
  if (expected.sel_ft && r.sel_ft) {
    EXPECT_EQ(r.sel_src, expected.sel_src);
  }
  EXPECT_EQ(r.tar_dps, expected.tar_dps);
}

Bytes word16(std::uint32_t value) {
  Bytes out;
  put(out, value & 0xFFFF, 2);
  return out;
}

// ---- CAT048 I048/250: BDS 4,0 and 5,0 ---------------------------------------------------

/// A 56-bit MB field built by Doc 9871's bit numbers (bit 1 = most significant).
struct MbField {
  std::uint64_t bits = 0;
  MbField& set(unsigned first, unsigned last, std::uint64_t value) {
    const unsigned width = last - first + 1;
    bits |= (value & ((std::uint64_t{1} << width) - 1)) << (56 - last);
    return *this;
  }
};

/// One I048/250 element: 7 bytes of MB data, then BDS1 BDS2.
Bytes mb_element(const MbField& mb, std::uint8_t bds) {
  Bytes out;
  put(out, mb.bits, 7);
  out.push_back(bds);
  return out;
}

Bytes mb_item(const std::vector<Bytes>& elements) {
  Bytes out{static_cast<std::uint8_t>(elements.size())};
  for (const Bytes& e : elements) out.insert(out.end(), e.begin(), e.end());
  return out;
}

struct Bds40Case {
  const char* name;
  bool mcp_status;
  unsigned mcp_ft;
  bool fms_status;
  unsigned fms_ft;
  bool source_status;
  unsigned source;  // 0 unknown, 1 aircraft altitude, 2 MCP/FCU, 3 FMS
  Intent expected;
};

MbField bds40(const Bds40Case& c) {
  MbField mb;
  mb.set(1, 1, c.mcp_status).set(2, 13, c.mcp_ft / 16);
  mb.set(14, 14, c.fms_status).set(15, 26, c.fms_ft / 16);
  mb.set(27, 27, 1).set(28, 39, 2132);  // barometric setting 1013.2 mb: not read
  mb.set(54, 54, c.source_status).set(55, 56, c.source);
  return mb;
}

TEST(AsterixIntentCat048, Bds40SelectedAltitudeOnlyWhenItsStatusSaysValid) {
  const std::vector<Bds40Case> cases = {
      {"MCP valid", true, 35008, false, 0, false, 0, {35008.0, Source::Mcp, {}}},
      {"MCP status 0: ignored", false, 35008, false, 0, false, 0, {}},
      {"FMS valid, target source status 0: MCP", true, 35008, true, 24000, false, 3,
       {35008.0, Source::Mcp, {}}},
      {"FMS valid, target source FMS: FMS", true, 35008, true, 24000, true, 3,
       {24000.0, Source::Fms, {}}},
      {"FMS valid, target source MCP: MCP", true, 35008, true, 24000, true, 2,
       {35008.0, Source::Mcp, {}}},
      {"FMS valid, target source aircraft altitude: MCP", true, 35008, true, 24000, true, 1,
       {35008.0, Source::Mcp, {}}},
      {"target source FMS, MCP invalid: FMS", false, 35008, true, 24000, true, 3,
       {24000.0, Source::Fms, {}}},
      {"target source FMS, FMS status 0: MCP", true, 35008, false, 24000, true, 3,
       {35008.0, Source::Mcp, {}}},
      {"target source FMS, neither valid: none", false, 35008, false, 24000, true, 3, {}},
      {"FMS valid without target source: none", false, 0, true, 24000, false, 0, {}},
      {"MCP at the top of its range", true, 65520, false, 0, false, 0, {65520.0, Source::Mcp, {}}},
      {"MCP 0 ft, valid", true, 0, false, 0, false, 0, {0.0, Source::Mcp, {}}},
  };
  std::vector<Bytes> records;
  for (const Bds40Case& c : cases) {
    RecordWriter w = minimal_cat048(static_cast<std::uint16_t>(100 + records.size()), std::nullopt);
    w.set(asterix::cat048::kModeSMbData, mb_item({mb_element(bds40(c), 0x40)}));
    records.push_back(w.bytes());
  }
  const auto reports = decode_every_record(48, records);
  ASSERT_EQ(reports.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].name);
    expect_intent(reports[i], cases[i].expected);
  }
}

TEST(AsterixIntentCat048, OnlyTheRegisterBdsCodeNamesIsRead) {
  const Bds40Case mcp{"", true, 12000, false, 0, false, 0, {}};
  MbField rate;
  rate.set(35, 35, 1).set(36, 45, 48);  // +1.5 deg/s
  const std::vector<std::pair<Bytes, Intent>> cases = {
      // A Comm-B broadcast (BDS 0,0) names no register: not read as 4,0.
      {mb_item({mb_element(bds40(mcp), 0x00)}), {}},
      // 4,0 bits in a register named 6,0 (heading and speed): not read.
      {mb_item({mb_element(bds40(mcp), 0x60)}), {}},
      // Several registers, 4,0 and 5,0 after others.
      {mb_item({mb_element(MbField{}, 0x60), mb_element(rate, 0x50), mb_element(bds40(mcp), 0x40)}),
       {12000.0, Source::Mcp, 1.5}},
      // The first valid 4,0 element wins.
      {mb_item({mb_element(bds40({"", false, 8000, false, 0, false, 0, {}}), 0x40),
                mb_element(bds40(mcp), 0x40),
                mb_element(bds40({"", true, 9008, false, 0, false, 0, {}}), 0x40)}),
       {12000.0, Source::Mcp, {}}},
  };
  std::vector<Bytes> records;
  for (const auto& [item, expected] : cases) {
    RecordWriter w = minimal_cat048(static_cast<std::uint16_t>(200 + records.size()), std::nullopt);
    w.set(asterix::cat048::kModeSMbData, item);
    records.push_back(w.bytes());
  }
  const auto reports = decode_every_record(48, records);
  ASSERT_EQ(reports.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    expect_intent(reports[i], cases[i].second);
  }
}

TEST(AsterixIntentCat048, Bds50TrackAngleRateSignedAndOnlyWhenValid) {
  struct Case {
    const char* name;
    bool status;
    std::uint32_t sign_and_value;  // bits 36-45: sign (1 = left), 9 bits of 1/32 deg/s
    std::optional<double> expected;
  };
  const std::vector<Case> cases = {
      {"right 1.5 deg/s", true, 48, 1.5},
      {"left 3 deg/s", true, 1024 - 96, -3.0},
      {"status 0: ignored", false, 48, {}},
      {"largest right", true, 511, 511 / 32.0},
      {"largest left", true, 512, -16.0},
      {"left 1/32 deg/s", true, 1023, -1 / 32.0},
      {"zero", true, 0, 0.0},
  };
  std::vector<Bytes> records;
  for (const Case& c : cases) {
    MbField mb;
    mb.set(1, 1, 1).set(2, 11, 100);     // roll angle (not read)
    mb.set(35, 35, c.status).set(36, 45, c.sign_and_value);
    mb.set(46, 46, 1).set(47, 56, 230);  // true airspeed (not read)
    RecordWriter w = minimal_cat048(static_cast<std::uint16_t>(300 + records.size()), std::nullopt);
    w.set(asterix::cat048::kModeSMbData, mb_item({mb_element(mb, 0x50)}));
    records.push_back(w.bytes());
  }
  const auto reports = decode_every_record(48, records);
  ASSERT_EQ(reports.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].name);
    expect_intent(reports[i], {{}, Source::Mcp, cases[i].expected});
  }
}

// ---- CAT062 I062/380 and CAT021 I021/146, 148: the same two layouts ---------------------

/// SAL (I062/380) and I021/146: SAS, SRC (2), 13-bit two's complement altitude, 25 ft.
Bytes selected_altitude(bool sas, unsigned source, int feet) {
  return word16((sas ? 0x8000U : 0U) | (source << 13) | (static_cast<std::uint32_t>(feet / 25) & 0x1FFF));
}
/// FSS (I062/380) and I021/148: MV, AH, AM, 13-bit two's complement altitude, 25 ft.
Bytes final_state_altitude(unsigned modes, int feet) {
  return word16((modes << 13) | (static_cast<std::uint32_t>(feet / 25) & 0x1FFF));
}

struct AltitudeCase {
  const char* name;
  std::optional<Bytes> selected, final_state;
  Intent expected;
};

const std::vector<AltitudeCase>& altitude_cases() {
  static const std::vector<AltitudeCase> cases = {
      {"SAL MCP/FCU", selected_altitude(true, 2, 35000), {}, {35000.0, Source::Mcp, {}}},
      {"SAL FMS", selected_altitude(true, 3, 24000), {}, {24000.0, Source::Fms, {}}},
      {"SAL source unknown: ignored", selected_altitude(true, 0, 24000), {}, {}},
      {"SAL source aircraft altitude: ignored", selected_altitude(true, 1, 24000), {}, {}},
      {"SAL without source information (SAS 0): ignored", selected_altitude(false, 3, 24000), {}, {}},
      {"SAS 0, FSS used", selected_altitude(false, 2, 24000), final_state_altitude(0, 26000),
       {26000.0, Source::Mcp, {}}},
      {"SAL FMS wins over FSS", selected_altitude(true, 3, 24000), final_state_altitude(0, 26000),
       {24000.0, Source::Fms, {}}},
      {"SAL MCP wins over FSS", selected_altitude(true, 2, 23000), final_state_altitude(0, 26000),
       {23000.0, Source::Mcp, {}}},
      {"SAL aircraft altitude, FSS used", selected_altitude(true, 1, 24000),
       final_state_altitude(0, 26000), {26000.0, Source::Mcp, {}}},
      {"FSS alone, mode bits set", {}, final_state_altitude(7, 5000), {5000.0, Source::Mcp, {}}},
      {"FSS negative", {}, final_state_altitude(0, -1000), {-1000.0, Source::Mcp, {}}},
      {"SAL negative", selected_altitude(true, 2, -1300), {}, {-1300.0, Source::Mcp, {}}},
      {"neither", {}, {}, {}},
  };
  return cases;
}

/// TAR (I062/380) and the two octets of I021/165 in edition 0.26: TI (2 bits), then a
/// 7-bit two's complement rate of 1/4 deg/s at the top of the second octet.
Bytes turn_indicator_rate(unsigned ti, int quarter_dps, std::uint8_t low_bits) {
  return {static_cast<std::uint8_t>(ti << 6 | low_bits),
          static_cast<std::uint8_t>((static_cast<unsigned>(quarter_dps) & 0x7F) << 1)};
}

struct RateCase {
  const char* name;
  unsigned ti;
  int quarter_dps;
  std::optional<double> expected;
};

const std::vector<RateCase>& rate_cases() {
  static const std::vector<RateCase> cases = {
      {"right 3 deg/s", 2, 12, 3.0},   {"left 3 deg/s", 1, -12, -3.0},
      {"TI 0: not available", 0, 12, {}}, {"straight", 3, 0, 0.0},
      {"largest right", 2, 63, 15.75}, {"largest left", 1, -64, -16.0},
  };
  return cases;
}

Bytes cat062_with(const std::optional<Bytes>& sal, const std::optional<Bytes>& fss,
                  const std::optional<Bytes>& tar, std::uint16_t track_number) {
  using namespace asterix::cat062;
  std::map<unsigned, Bytes> derived;
  if (sal) derived[k380SelectedAltitude] = *sal;
  if (fss) derived[k380FinalSelectedAltitude] = *fss;
  if (tar) derived[k380TrackAngleRate] = *tar;
  RecordWriter w = minimal_cat062(128U * 1000U + track_number, track_number);
  if (!derived.empty()) w.set(kAircraftDerived, compound_item(derived));
  return w.bytes();
}

/// Every hand-built CAT062 record, one a block, and what each must give.
std::vector<std::pair<Bytes, Intent>> cat062_cases() {
  std::vector<std::pair<Bytes, Intent>> out;
  for (const AltitudeCase& c : altitude_cases()) {
    const auto number = static_cast<std::uint16_t>(out.size() + 1);
    out.emplace_back(data_block(62, {cat062_with(c.selected, c.final_state, {}, number)}), c.expected);
  }
  for (const RateCase& c : rate_cases()) {
    const auto number = static_cast<std::uint16_t>(out.size() + 1);
    const Bytes tar = turn_indicator_rate(c.ti, c.quarter_dps, 0);
    out.emplace_back(data_block(62, {cat062_with({}, {}, tar, number)}), Intent{{}, Source::Mcp, c.expected});
  }
  return out;
}

/// A CAT021 2.x record of 25/21 that the decoder accepts (address 4CA123, FL350).
RecordWriter minimal_cat021() {
  using namespace asterix::cat021;
  RecordWriter w;
  w.set(kDataSource, {25, 21});
  w.set(kTimeOfPosition, {0x10, 0x00, 0x00});
  w.set(kPosition, {0x24, 0x9A, 0x2B, 0xFF, 0xEB, 0x80});
  w.set(kAddress, {0x4C, 0xA1, 0x23});
  w.set(kFlightLevel, {0x05, 0x78});
  return w;
}

/// Every hand-built CAT021 (2.x) record, one a block, and what each must give.
std::vector<std::pair<Bytes, Intent>> cat021_cases() {
  using namespace asterix::cat021;
  std::vector<std::pair<Bytes, Intent>> out;
  for (const AltitudeCase& c : altitude_cases()) {
    RecordWriter w = minimal_cat021();
    if (c.selected) w.set(kSelectedAltitude, *c.selected);
    if (c.final_state) w.set(kFinalSelectedAltitude, *c.final_state);
    out.emplace_back(data_block(21, {w.bytes()}), c.expected);
  }
  // I021/165: 6 spare bits, a 10-bit two's complement rate of 1/32 deg/s; no indicator.
  const std::vector<std::pair<std::uint32_t, double>> rates = {
      {80, 2.5}, {0x3FF, -1 / 32.0}, {0x200, -16.0}, {0x1FF, 511 / 32.0}, {0xFC00 | 80, 2.5}};
  for (const auto& [word, dps] : rates) {
    RecordWriter w = minimal_cat021();
    w.set(kTrackAngleRate, word16(word));
    out.emplace_back(data_block(21, {w.bytes()}), Intent{{}, Source::Mcp, dps});
  }
  return out;
}

void expect_cases(const std::vector<std::pair<Bytes, Intent>>& cases, std::size_t altitude_count) {
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(i < altitude_count ? altitude_cases()[i].name
                                    : "rate case " + std::to_string(i - altitude_count));
    Rejections rejections;
    const auto reports = decode_bytes(cases[i].first, {}, &rejections);
    EXPECT_EQ(rejections.total(), 0U);
    ASSERT_EQ(reports.size(), 1U);
    expect_intent(reports[0], cases[i].second);
  }
}

TEST(AsterixIntentCat062, SalFssAndTarValidityRules) {
  expect_cases(cat062_cases(), altitude_cases().size());
}

TEST(AsterixIntentCat062, TarSpareBitsAreIgnored) {
  const auto reports = decode_bytes(
      data_block(62, {cat062_with({}, {}, Bytes{0xBF, 0x19}, 7)}));  // TI 2, spare 1s, 12, spare 1
  ASSERT_EQ(reports.size(), 1U);
  EXPECT_EQ(reports[0].tar_dps, std::optional<double>(3.0));
}

TEST(AsterixIntentCat021, Items146And148And165OfEditions2) {
  expect_cases(cat021_cases(), altitude_cases().size());
}

TEST(AsterixIntentCat021, Edition026RateOfTurnAndSelectedAltitudes) {
  // Edition 0.26: I021/146 and 148 as in 2.x; I021/165 is FX-extended: TI (2), spare (5),
  // FX, then the rate (7 bits, 1/4 deg/s) and FX.
  using namespace asterix::cat021_v026;
  const auto record = [](const std::optional<Bytes>& rate_of_turn, const std::optional<Bytes>& sal,
                         const std::optional<Bytes>& fss) {
    RecordWriter w;
    w.set(kDataSource, {0, 5});
    w.set(kDescriptor, {0x00, 0x00});
    w.set(kTimeOfDay, {0x1c, 0x29, 0x3e});
    w.set(kPosition, {0x00, 0x6e, 0x4c, 0xc9, 0xff, 0xe6, 0x06, 0xd6});
    w.set(kAddress, {0x49, 0x6c, 0x2e});
    w.set(kFlightLevel, {0x05, 0x78});
    if (rate_of_turn) w.set(kRateOfTurn, *rate_of_turn);
    if (sal) w.set(kSelectedAltitude, *sal);
    if (fss) w.set(kFinalSelectedAltitude, *fss);
    return data_block(21, {w.bytes()});
  };
  const std::vector<std::pair<Bytes, Intent>> cases = {
      {record(turn_indicator_rate(2, 12, 0x01), {}, {}), {{}, Source::Mcp, 3.0}},
      {record(turn_indicator_rate(1, -12, 0x01), {}, {}), {{}, Source::Mcp, -3.0}},
      {record(turn_indicator_rate(0, 12, 0x01), {}, {}), {}},
      {record(Bytes{0x80}, {}, {}), {}},  // TI right but no rate octet
      {record({}, selected_altitude(true, 3, 31000), final_state_altitude(0, 33000)),
       {31000.0, Source::Fms, {}}},
      {record({}, selected_altitude(false, 0, 31000), final_state_altitude(0, 33000)),
       {33000.0, Source::Mcp, {}}},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const auto reports = decode_bytes(cases[i].first);
    ASSERT_EQ(reports.size(), 1U);
    EXPECT_EQ(reports[0].callsign, "");  // decoded under 0.26: 2.x would misread the items
    EXPECT_EQ(reports[0].id, "496C2E");
    EXPECT_EQ(reports[0].alt_ft, 35000.0);
    expect_intent(reports[0], cases[i].second);
  }
}

// ---- Against tshark --------------------------------------------------------------------

std::optional<double> number_of(const tshark::FieldValues& f, const std::string& field) {
  const auto& values = f.at(field);
  if (values.empty()) return std::nullopt;
  return std::stod(values.front());
}

/// kew's rules (design §5.2) applied to tshark's fields of one CAT062 or CAT021 record.
Intent intent_from_sal_fss(const tshark::FieldValues& f, const std::string& sal,
                           const std::string& source, const std::string& fss) {
  Intent i;
  const auto sas = number_of(f, sal + "_SAS");
  const auto src = number_of(f, sal + "_" + source);
  if (sas == 1.0 && (src == 2.0 || src == 3.0)) {
    i.sel_ft = number_of(f, sal + "_ALT");
    i.sel_src = src == 3.0 ? Source::Fms : Source::Mcp;
  } else {
    i.sel_ft = number_of(f, fss + "_ALT");
  }
  return i;
}

const std::vector<std::string> kCat062Fields = {
    "asterix.062_380_SAL_SAS", "asterix.062_380_SAL_SRC", "asterix.062_380_SAL_ALT",
    "asterix.062_380_FSS_ALT", "asterix.062_380_TAR_TI",  "asterix.062_380_TAR_ROT"};

Intent cat062_intent_of(const tshark::FieldValues& f) {
  Intent i = intent_from_sal_fss(f, "asterix.062_380_SAL", "SRC", "asterix.062_380_FSS");
  const auto ti = number_of(f, "asterix.062_380_TAR_TI");
  if (ti && *ti != 0.0) i.tar_dps = number_of(f, "asterix.062_380_TAR_ROT");
  return i;
}

const std::vector<std::string> kCat021Fields = {
    "asterix.021_146_SAS", "asterix.021_146_S", "asterix.021_146_ALT", "asterix.021_148_ALT",
    "asterix.021_165_TAR"};

Intent cat021_intent_of(const tshark::FieldValues& f) {
  Intent i = intent_from_sal_fss(f, "asterix.021_146", "S", "asterix.021_148");
  i.tar_dps = number_of(f, "asterix.021_165_TAR");
  return i;
}

const std::vector<std::string> kCat048Fields = {
    "asterix.048_250_MBDATA", "asterix.048_250_BDS1", "asterix.048_250_BDS2"};

/// Bits first..last (Doc 9871 numbering, bit 1 first) of tshark's 56-bit MB data.
std::uint64_t mb_bits(std::uint64_t mb, unsigned first, unsigned last) {
  return (mb >> (56 - last)) & ((std::uint64_t{1} << (last - first + 1)) - 1);
}

/// kew's rules (design §5.2) applied to tshark's I048/250 elements of one record.
Intent cat048_intent_of(const tshark::FieldValues& f) {
  Intent i;
  const auto& data = f.at("asterix.048_250_MBDATA");
  for (std::size_t k = 0; k < data.size(); ++k) {
    const std::uint64_t mb = std::stoull(data[k], nullptr, 16);
    const int bds1 = std::stoi(f.at("asterix.048_250_BDS1").at(k));
    const int bds2 = std::stoi(f.at("asterix.048_250_BDS2").at(k));
    if (bds1 == 4 && bds2 == 0 && !i.sel_ft) {
      if (mb_bits(mb, 54, 54) == 1 && mb_bits(mb, 55, 56) == 3 && mb_bits(mb, 14, 14) == 1) {
        i.sel_ft = 16.0 * static_cast<double>(mb_bits(mb, 15, 26));
        i.sel_src = Source::Fms;
      } else if (mb_bits(mb, 1, 1) == 1) {
        i.sel_ft = 16.0 * static_cast<double>(mb_bits(mb, 2, 13));
      }
    }
    if (bds1 == 5 && bds2 == 0 && !i.tar_dps && mb_bits(mb, 35, 35) == 1) {
      const auto raw = static_cast<std::int64_t>(mb_bits(mb, 36, 45));
      i.tar_dps = static_cast<double>(raw >= 512 ? raw - 1024 : raw) / 32.0;
    }
  }
  return i;
}

struct CrossCheck {
  std::size_t records = 0;   ///< records (one a frame) tshark decoded
  std::size_t compared = 0;  ///< of which kew reported (and so were compared)
  std::size_t with_sel = 0, with_fms = 0, with_tar = 0;
};

/// Decodes each single-record block with kew and, wrapped one a UDP datagram, with
/// tshark; each record kew reports must carry what kew's rules give on tshark's fields.
template <class IntentOf>
CrossCheck cross_check(const std::vector<Bytes>& blocks, const AsterixOptions& options,
                       const std::vector<std::string>& fields, IntentOf intent_of,
                       const std::string& name) {
  std::vector<tshark::Datagram> datagrams;
  for (const Bytes& b : blocks) {
    const auto bytes = std::as_bytes(std::span<const std::uint8_t>(b));
    datagrams.emplace_back(bytes.begin(), bytes.end());
  }
  const std::string pcap = tshark::write_pcap(
      datagrams, ::testing::TempDir() + "kew_intent_" + name + "_" + std::to_string(::getpid()) + ".pcap");
  const auto frames = tshark::fields(pcap, fields);
  EXPECT_EQ(frames.size(), blocks.size()) << "tshark decoded another number of frames of " << name;
  EXPECT_EQ(tshark::problems(pcap), "") << name;
  std::remove(pcap.c_str());

  CrossCheck out;
  out.records = frames.size();
  auto decoder = make_asterix_decoder(AsterixFraming::Datagram, options);
  for (std::size_t i = 0; i < blocks.size() && i < frames.size(); ++i) {
    std::vector<TrackReport> reports;
    decoder->feed(datagrams[i], [&](const TrackReport& r) { reports.push_back(r); });
    if (reports.empty()) continue;  // refused (counted): nothing to compare
    EXPECT_EQ(reports.size(), 1U);
    const Intent expected = intent_of(frames[i]);
    SCOPED_TRACE(name + " record " + std::to_string(i) + " id " + reports[0].id);
    expect_intent(reports[0], expected);
    if (::testing::Test::HasFailure()) return out;
    ++out.compared;
    out.with_sel += expected.sel_ft ? 1 : 0;
    out.with_fms += expected.sel_ft && expected.sel_src == Source::Fms ? 1 : 0;
    out.with_tar += expected.tar_dps ? 1 : 0;
  }
  return out;
}

std::vector<Bytes> blocks_of(const std::vector<std::pair<Bytes, Intent>>& cases) {
  std::vector<Bytes> out;
  for (const auto& c : cases) out.push_back(c.first);
  return out;
}

TEST(AsterixIntentTshark, HandBuiltCat062AndCat021Records) {
  KEW_REQUIRE_TSHARK("the selected altitude and track angle rate check");
  // tshark decodes CAT062 and CAT021 by its latest editions (1.19 and 2.6 in 4.0.17),
  // whose SAL, FSS, TAR, 146, 148 and 165 are those of every edition kew reads.
  const auto c62 = cross_check(blocks_of(cat062_cases()), {}, kCat062Fields, cat062_intent_of, "cat062");
  EXPECT_EQ(c62.compared, cat062_cases().size());
  const auto c21 = cross_check(blocks_of(cat021_cases()), {}, kCat021Fields, cat021_intent_of, "cat021");
  EXPECT_EQ(c21.compared, cat021_cases().size());
}

/// The data blocks of raw concatenated blocks, or of final-format frames (8-byte header,
/// 4-byte trailer).
std::vector<Bytes> data_blocks(const std::string& data, bool final_format) {
  std::vector<Bytes> out;
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(data.data());
  std::size_t i = 0;
  while (i + 3 <= data.size()) {
    if (final_format) {
      const std::size_t frame = (std::size_t{bytes[i]} << 8) | bytes[i + 1];
      if (frame < 12 || i + frame > data.size()) break;
      for (std::size_t j = i + 8; j + 3 <= i + frame - 4;) {
        const std::size_t length = (std::size_t{bytes[j + 1]} << 8) | bytes[j + 2];
        if (length < 3 || j + length > i + frame - 4) break;
        out.emplace_back(bytes + j, bytes + j + length);
        j += length;
      }
      i += frame;
    } else {
      const std::size_t length = (std::size_t{bytes[i + 1]} << 8) | bytes[i + 2];
      if (length < 3 || i + length > data.size()) break;
      out.emplace_back(bytes + i, bytes + i + length);
      i += length;
    }
  }
  return out;
}

/// Records `first` … `first + count - 1` of `blocks` (those of `category`, in order), each
/// as a block of its own.
std::vector<Bytes> single_record_blocks(const std::vector<Bytes>& blocks, std::uint8_t category,
                                        const asterix::Uap& uap, std::size_t first = 0,
                                        std::size_t count = SIZE_MAX) {
  std::vector<Bytes> out;
  std::size_t index = 0;
  for (const Bytes& block : blocks) {
    if (block[0] != category) continue;
    std::size_t at = 3;
    while (at < block.size() && out.size() < count) {
      asterix::RecordItems items;
      const auto walk = asterix::walk_record(uap, block.data() + at, block.size() - at, items);
      EXPECT_EQ(walk.error, asterix::WalkError::None);
      if (walk.error != asterix::WalkError::None) break;
      if (index++ >= first) {
        out.push_back(data_block(category, {Bytes(block.begin() + at, block.begin() + at + walk.bytes)}));
      }
      at += walk.bytes;
    }
  }
  return out;
}

std::string asterix_fixture(const std::string& name) {
  return test::read_file(std::string(KEW_TEST_DATA_DIR) + "/asterix/" + name);
}

TEST(AsterixIntentTshark, UpcBarcelonaCat048ExcerptBds40And50) {
  KEW_REQUIRE_TSHARK("the selected altitude and track angle rate check");
  // No licence: read from the shared directory only, never bundled (MANIFEST). Records
  // 8,000 to 15,999 of the hour (minutes 11 to 22), where some aircraft report the FMS as
  // their target altitude source.
  const std::string path =
      test::shared_path("upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast");
  if (!test::exists(path)) GTEST_SKIP() << "shared recording absent (never bundled, no licence): " << path;
  AsterixOptions options;
  options.radars.push_back({20, 129, 41.300702, 2.102058, 27.0});
  const auto blocks = single_record_blocks(data_blocks(test::read_file(path), false), 48,
                                           asterix::cat048_uap(), 8000, 8000);
  const CrossCheck c = cross_check(blocks, options, kCat048Fields, cat048_intent_of, "upc");
  std::printf("UPC CAT048 excerpt: %zu records, %zu reports compared with tshark, %zu with "
              "sel_ft (%zu fms), %zu with tar_dps\n", c.records, c.compared, c.with_sel, c.with_fms,
              c.with_tar);
  EXPECT_EQ(c.records, 8000U);
  EXPECT_GT(c.compared, 7800U);
  EXPECT_GT(c.with_sel, 5000U);  // BDS 4,0 is in most Mode S records of this radar
  EXPECT_GT(c.with_fms, 0U);
  EXPECT_GT(c.with_tar, 0U);
}

TEST(AsterixIntentTshark, BundledCat048AndCat062Fixtures) {
  KEW_REQUIRE_TSHARK("the selected altitude and track angle rate check");
  AsterixOptions nominal;  // the fixtures' radars at a nominal site (as in the golden tests)
  nominal.radars.push_back({0, 1, 45.0, 16.0, 100.0});
  nominal.radars.push_back({25, 201, 45.0, 16.0, 100.0});
  std::vector<Bytes> blocks48, blocks62;
  for (const char* name : {"croatiacontrol/cat048.raw", "jasterix/cat048ed1.15.bin",
                           "jasterix/cat048ed1.23.bin"}) {
    for (Bytes& b : single_record_blocks(data_blocks(asterix_fixture(name), false), 48,
                                         asterix::cat048_uap())) {
      blocks48.push_back(std::move(b));
    }
  }
  for (const auto& [name, ff] : {std::pair{"asterix4py/cat062.ast", false},
                                 std::pair{"jasterix/cat062ed1.12.bin", false},
                                 std::pair{"jade/final_frame_062_first3min.ff", true}}) {
    for (Bytes& b : single_record_blocks(data_blocks(asterix_fixture(name), ff), 62,
                                         asterix::cat062_uap())) {
      blocks62.push_back(std::move(b));
    }
  }
  const CrossCheck total48 = cross_check(blocks48, nominal, kCat048Fields, cat048_intent_of, "cat048");
  const CrossCheck total62 = cross_check(blocks62, {}, kCat062Fields, cat062_intent_of, "cat062");
  std::printf("bundled CAT048: %zu records, %zu compared, %zu with sel_ft; CAT062: %zu records, "
              "%zu compared, %zu with sel_ft, %zu with tar_dps\n", total48.records, total48.compared,
              total48.with_sel, total62.records, total62.compared, total62.with_sel, total62.with_tar);
  EXPECT_GT(total48.with_sel, 0U);
  EXPECT_GT(total62.with_sel, 0U);
}

}  // namespace
}  // namespace kew::protocol
