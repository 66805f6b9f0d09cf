// Round trip of the ASTERIX record reader: a test-only writer builds random CAT062 (with
// selected altitude and track angle rate, design §5.2) and CAT048 records with known
// values (and random items kew only skips), the decoder must return those values within
// the scaling's resolution. Also unit tests of the item walker
// and of the time-of-day clock.

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "kew/protocol/asterix/day_clock.hpp"
#include "kew/protocol/asterix/item_format.hpp"
#include "kew/protocol/asterix/record_walker.hpp"
#include "kew/protocol/asterix/uap.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "asterix_writer.hpp"

namespace kew::protocol {
namespace {

using namespace asterix_writer;

constexpr double kPi = std::numbers::pi;
constexpr double kFtPerM = 1.0 / 0.3048;
constexpr double kKtPerMs = 3600.0 / 1852.0;

/// 8 characters of 6-bit ICAO code in 6 bytes.
Bytes icao_characters(const std::string& text) {
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    const char c = i < text.size() ? text[i] : ' ';
    const unsigned code = c >= 'A' && c <= 'Z' ? static_cast<unsigned>(c - 'A' + 1) : static_cast<unsigned>(c);
    bits = (bits << 6) | (code & 0x3F);
  }
  Bytes out;
  put(out, bits, 6);
  return out;
}

// ---- Random CAT062 records --------------------------------------------------------------

/// The values a random CAT062 record carries, before quantisation.
struct Cat062Truth {
  std::uint8_t sac = 0, sic = 0;
  double tod_s = 0, lat = 0, lon = 0, alt_ft = 0;
  std::optional<double> vx, vy, vr_fpm;
  std::optional<std::uint32_t> address;
  std::uint16_t track_number = 0;
  std::optional<std::uint16_t> mode3a;
  std::string callsign;
  bool coasting = false, track_end = false;  // I062/080 CST, TSE
  std::optional<double> sel_ft, tar_dps;      // multiples of 25 ft and 1/4 deg/s
  bool sel_fms = false;                       // sel_ft is the FMS one (else MCP/FCU)
};

/// I062/380 SAL or FSS: 3 bits (SAS, SRC or MV, AH, AM) then 13-bit altitude of 25 ft.
Bytes altitude_subfield(std::uint32_t top_bits, double feet) {
  Bytes out;
  put(out, (top_bits << 13) | (static_cast<std::uint32_t>(quantize(feet, 25.0)) & 0x1FFF), 2);
  return out;
}

/// SAL, FSS and TAR subfields of I062/380 for `truth` (design §5.2): the selected altitude
/// by a valid route, with or beside ones the decoder must ignore (SAS 0, source unknown or
/// aircraft altitude, TI 0).
void add_intent_subfields(std::mt19937& random, const Cat062Truth& truth,
                          std::map<unsigned, Bytes>& derived) {
  using namespace asterix::cat062;
  const auto bits = [&](unsigned n) { return static_cast<std::uint32_t>(random() % n); };
  const auto ignored_sal = [&] { return altitude_subfield(bits(6), -1000.0); };  // SAS.SRC < 1.10
  if (truth.sel_ft && (truth.sel_fms || random() % 2 != 0)) {
    derived[k380SelectedAltitude] = altitude_subfield(truth.sel_fms ? 7 : 6, *truth.sel_ft);
    if (random() % 2 != 0) derived[k380FinalSelectedAltitude] = altitude_subfield(bits(8), 5000.0);
  } else if (truth.sel_ft) {
    derived[k380FinalSelectedAltitude] = altitude_subfield(bits(8), *truth.sel_ft);
    if (random() % 2 != 0) derived[k380SelectedAltitude] = ignored_sal();
  } else if (random() % 2 != 0) {
    derived[k380SelectedAltitude] = ignored_sal();
  }
  if (truth.tar_dps || random() % 2 != 0) {
    const std::uint32_t ti = truth.tar_dps ? 1 + bits(3) : 0;
    const auto rate = static_cast<std::uint32_t>(quantize(truth.tar_dps.value_or(1.0), 0.25));
    derived[k380TrackAngleRate] = {static_cast<std::uint8_t>(ti << 6 | (random() & 0x3F)),
                                   static_cast<std::uint8_t>((rate & 0x7F) << 1 | (random() & 1))};
  }
}

std::string random_callsign(std::mt19937& random) {
  static const std::string kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::string text(1, static_cast<char>('A' + random() % 26));
  const std::size_t length = 2 + random() % 6;
  while (text.size() < length) text += kAlphabet[random() % kAlphabet.size()];
  return text;
}

Bytes random_bytes(std::mt19937& random, std::size_t n) {
  Bytes out(n);
  for (auto& b : out) b = static_cast<std::uint8_t>(random());
  return out;
}

/// Random FX-chained item of 1-4 parts of `part_bytes` bytes.
Bytes random_extended(std::mt19937& random, std::size_t part_bytes) {
  Bytes out;
  const std::size_t parts = 1 + random() % 4;
  for (std::size_t p = 0; p < parts; ++p) {
    Bytes part = random_bytes(random, part_bytes);
    part.back() = static_cast<std::uint8_t>((part.back() & 0xFE) | (p + 1 < parts ? 1 : 0));
    out.insert(out.end(), part.begin(), part.end());
  }
  return out;
}

/// I062/080 of 1-6 random octets with CNF and SIM clear (the decoder would refuse the
/// record) and TSE (octet 2, bit 7) and CST (octet 4, bit 8) as `truth` says; octets are
/// added when a flag to be set needs them.
Bytes cat062_track_status(std::mt19937& random, const Cat062Truth& truth) {
  std::size_t octets = 1 + random() % 6;
  if (truth.track_end) octets = std::max<std::size_t>(octets, 2);
  if (truth.coasting) octets = std::max<std::size_t>(octets, 4);
  Bytes out = random_bytes(random, octets);
  out[0] &= 0xFD;
  if (octets >= 2) out[1] = static_cast<std::uint8_t>((out[1] & 0x3F) | (truth.track_end ? 0x40 : 0));
  if (octets >= 4) out[3] = static_cast<std::uint8_t>((out[3] & 0x7F) | (truth.coasting ? 0x80 : 0));
  for (std::size_t i = 0; i < octets; ++i) {
    out[i] = static_cast<std::uint8_t>((out[i] & 0xFE) | (i + 1 < octets ? 1 : 0));
  }
  return out;
}

/// A record announcing every item kind of the CAT062 UAP the decoder must skip.
Bytes random_cat062_record(std::mt19937& random, const Cat062Truth& truth) {
  using namespace asterix::cat062;
  RecordWriter w;
  Bytes item;
  put(item, truth.sac, 1);
  put(item, truth.sic, 1);
  w.set(kDataSource, item);
  w.set(kTimeOfTrack, {});
  {
    Bytes tod;
    put(tod, static_cast<std::uint64_t>(quantize(truth.tod_s, 1.0 / 128)), 3);
    w.set(kTimeOfTrack, tod);
  }
  Bytes position;
  put(position, static_cast<std::uint32_t>(quantize(truth.lat, 180.0 / 33554432.0)), 4);
  put(position, static_cast<std::uint32_t>(quantize(truth.lon, 180.0 / 33554432.0)), 4);
  w.set(kPositionWgs84, position);
  if (truth.vx) {
    Bytes velocity;
    put(velocity, static_cast<std::uint16_t>(quantize(*truth.vx, 0.25)), 2);
    put(velocity, static_cast<std::uint16_t>(quantize(*truth.vy, 0.25)), 2);
    w.set(kVelocity, velocity);
  }
  // Altitude through one of the three items the decoder accepts, by preference.
  Bytes altitude;
  switch (random() % 3) {
    case 0:
      put(altitude, static_cast<std::uint16_t>(quantize(truth.alt_ft, 25.0)), 2);
      w.set(kMeasuredFl, altitude);
      break;
    case 1:  // I062/135: bit 16 QNH flag, 15-bit two's complement in 1/4 FL.
      put(altitude, (static_cast<std::uint64_t>(quantize(truth.alt_ft, 25.0)) & 0x7FFF) | (random() % 2) << 15, 2);
      w.set(kBarometricAlt, altitude);
      break;
    default:
      put(altitude, static_cast<std::uint16_t>(quantize(truth.alt_ft, 6.25)), 2);
      w.set(kGeometricAlt, altitude);
  }
  if (truth.vr_fpm) {
    Bytes rate;
    put(rate, static_cast<std::uint16_t>(quantize(*truth.vr_fpm, 6.25)), 2);
    w.set(kRateOfClimb, rate);
  }
  Bytes number;
  put(number, truth.track_number, 2);
  w.set(kTrackNumber, number);
  if (truth.mode3a) {
    Bytes code;
    put(code, *truth.mode3a | (random() % 8) << 13, 2);  // V, G, CH flags above the code
    w.set(kMode3A, code);
  }
  // The callsign through I062/245, 380 ID or 390 CSN (the decoder's order of preference).
  std::map<unsigned, Bytes> derived;
  if (truth.address) {
    Bytes adr;
    put(adr, *truth.address, 3);
    derived[0] = adr;
  }
  const auto callsign_route = truth.callsign.empty() ? 3U : static_cast<unsigned>(random() % 3);
  if (callsign_route == 0) {
    Bytes target_id{static_cast<std::uint8_t>(random() & 0xC0)};  // STI, spare
    const Bytes chars = icao_characters(truth.callsign);
    target_id.insert(target_id.end(), chars.begin(), chars.end());
    w.set(kTargetId, target_id);
  } else if (callsign_route == 1) {
    derived[1] = icao_characters(truth.callsign);
  }
  // Subfields of I062/380 the decoder skips: fixed, extended (TIS), repetitive (TID, MB).
  if (random() % 2 != 0) derived[4] = random_bytes(random, 2);        // TAS
  if (random() % 2 != 0) derived[7] = random_extended(random, 1);     // TIS
  if (random() % 2 != 0) {                                            // TID
    Bytes tid{static_cast<std::uint8_t>(random() % 3)};
    const Bytes body = random_bytes(random, 15 * tid[0]);
    tid.insert(tid.end(), body.begin(), body.end());
    derived[8] = tid;
  }
  if (random() % 2 != 0) derived[19] = random_bytes(random, 8);       // MET
  if (random() % 2 != 0) {                                            // MB
    Bytes mb{static_cast<std::uint8_t>(1 + random() % 2)};
    const Bytes body = random_bytes(random, 8 * mb[0]);
    mb.insert(mb.end(), body.begin(), body.end());
    derived[24] = mb;
  }
  add_intent_subfields(random, truth, derived);
  if (!derived.empty()) w.set(kAircraftDerived, compound_item(derived));

  std::map<unsigned, Bytes> plan;
  if (callsign_route == 2) {
    Bytes csn(truth.callsign.begin(), truth.callsign.end());
    csn.resize(7, ' ');
    plan[1] = csn;
  }
  if (random() % 2 != 0) plan[0] = random_bytes(random, 2);             // TAG
  if (random() % 2 != 0) plan[11] = Bytes{0};                           // TOD, REP 0
  if (random() % 2 != 0) plan[17] = random_bytes(random, 7);            // PEC
  if (!plan.empty()) w.set(kFlightPlan, compound_item(plan));

  // Items the decoder only walks past.
  if (random() % 2 != 0) w.set(3, random_bytes(random, 1));                        // 015
  if (random() % 2 != 0) w.set(6, random_bytes(random, 6));                        // 100
  if (random() % 2 != 0) w.set(8, random_bytes(random, 2));                        // 210
  if (truth.coasting || truth.track_end || random() % 2 != 0) w.set(kTrackStatus, cat062_track_status(random, truth));
  if (random() % 2 != 0) {                                                         // 290
    w.set(14, compound_item({{0, random_bytes(random, 1)}, {4, random_bytes(random, 2)},
                             {9, random_bytes(random, 1)}}));
  }
  if (random() % 2 != 0) w.set(16, compound_item({{2, random_bytes(random, 1)}, {30, random_bytes(random, 1)}}));
  if (random() % 2 != 0) w.set(22, random_extended(random, 1));                    // 270
  if (random() % 2 != 0) w.set(26, random_extended(random, 3));                    // 510
  if (random() % 2 != 0) w.set(27, compound_item({{0, random_bytes(random, 4)}, {7, random_bytes(random, 1)}}));
  if (random() % 2 != 0) w.set(28, compound_item({{1, random_bytes(random, 4)}, {5, random_bytes(random, 1)}}));
  for (const unsigned explicit_frn : {34U, 35U}) {                                 // RE, SP
    if (random() % 3 == 0) {
      Bytes field{static_cast<std::uint8_t>(1 + random() % 20)};
      const Bytes body = random_bytes(random, field[0] - 1U);
      field.insert(field.end(), body.begin(), body.end());
      w.set(explicit_frn, field);
    }
  }
  return w.bytes();
}

Cat062Truth random_cat062_truth(std::mt19937& random, double tod_s) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Cat062Truth t;
  t.sac = static_cast<std::uint8_t>(random());
  t.sic = static_cast<std::uint8_t>(random());
  t.tod_s = tod_s;
  t.lat = -89.9 + 179.8 * unit(random);
  t.lon = -179.9 + 359.8 * unit(random);
  t.alt_ft = -1000 + 60000 * unit(random);
  if (random() % 4 != 0) {
    t.vx = -400 + 800 * unit(random);
    t.vy = -400 + 800 * unit(random);
  }
  if (random() % 3 != 0) t.vr_fpm = -6000 + 12000 * unit(random);
  if (random() % 2 != 0) t.address = static_cast<std::uint32_t>(random() & 0xFFFFFF);
  t.track_number = static_cast<std::uint16_t>(random());
  if (random() % 2 != 0) t.mode3a = static_cast<std::uint16_t>(random() & 07777);
  if (random() % 4 != 0) t.callsign = random_callsign(random);
  t.coasting = random() % 4 == 0;
  t.track_end = random() % 8 == 0;
  if (random() % 2 != 0) {
    t.sel_ft = 25.0 * (static_cast<int>(random() % 4053) - 52);  // -1,300 to 100,000 ft
    t.sel_fms = random() % 2 == 0;
  }
  if (random() % 2 != 0) t.tar_dps = 0.25 * (static_cast<int>(random() % 128) - 64);
  return t;
}

void expect_matches(const TrackReport& r, const Cat062Truth& t) {
  EXPECT_EQ(r.source, "cat062/" + std::to_string(t.sac) + "." + std::to_string(t.sic));
  EXPECT_EQ(r.id, std::to_string(t.track_number));
  EXPECT_EQ(r.address, t.address);
  EXPECT_EQ(r.coasting, t.coasting);
  EXPECT_EQ(r.track_end, t.track_end);
  EXPECT_NEAR(r.t, t.tod_s, 1.0 / 256 + 1e-9);
  EXPECT_NEAR(r.lat_deg, t.lat, 90.0 / 33554432.0 + 1e-12);
  EXPECT_NEAR(r.lon_deg, t.lon, 90.0 / 33554432.0 + 1e-12);
  // Within half an LSB of whichever altitude item carried it (6.25 ft or 25 ft).
  EXPECT_NEAR(r.alt_ft, t.alt_ft, 12.5 + 1e-9);
  ASSERT_EQ(r.gs_kt.has_value(), t.vx.has_value());
  if (t.vx) {
    // Back to Cartesian components: each within half the 0.25 m/s LSB.
    const double speed_ms = *r.gs_kt / kKtPerMs;
    const double track = *r.trk_deg * kPi / 180.0;
    EXPECT_NEAR(speed_ms * std::sin(track), *t.vx, 0.125 + 1e-9);
    EXPECT_NEAR(speed_ms * std::cos(track), *t.vy, 0.125 + 1e-9);
    EXPECT_GE(*r.trk_deg, 0.0);
    EXPECT_LT(*r.trk_deg, 360.0);
  }
  ASSERT_EQ(r.vr_fpm.has_value(), t.vr_fpm.has_value());
  if (t.vr_fpm) {
    EXPECT_NEAR(*r.vr_fpm, *t.vr_fpm, 3.125 + 1e-9);
  }
  EXPECT_EQ(r.mode3a, t.mode3a);
  EXPECT_EQ(r.callsign, t.callsign);
  EXPECT_FALSE(r.on_ground);
  EXPECT_EQ(r.sel_ft, t.sel_ft);
  if (t.sel_ft) {
    EXPECT_EQ(r.sel_src, t.sel_fms ? SelectedAltitudeSource::Fms : SelectedAltitudeSource::Mcp);
  }
  EXPECT_EQ(r.tar_dps, t.tar_dps);
}

TEST(AsterixRoundTrip, RandomCat062RecordsDecodeToTheirValues) {
  std::mt19937 random(62);
  std::size_t checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // A block of 1-6 records with increasing times of day (no day rollover: t = tod).
    std::vector<Cat062Truth> truths;
    std::vector<Bytes> records;
    double tod = 40.0 * static_cast<double>(random() % 1000);
    const std::size_t count = 1 + random() % 6;
    for (std::size_t i = 0; i < count; ++i) {
      tod += static_cast<double>(random() % 1000) / 128.0;
      truths.push_back(random_cat062_truth(random, tod));
      records.push_back(random_cat062_record(random, truths.back()));
    }
    Rejections rejections;
    const auto reports = decode_bytes(data_block(62, records), {}, &rejections);
    SCOPED_TRACE("trial " + std::to_string(trial));
    EXPECT_EQ(rejections.total(), 0U) << (rejections.by_reason().empty() ? "" : rejections.by_reason().begin()->first);
    ASSERT_EQ(reports.size(), truths.size());
    for (std::size_t i = 0; i < reports.size(); ++i) {
      expect_matches(reports[i], truths[i]);
      ++checked;
    }
    if (HasFailure()) return;
  }
  EXPECT_GT(checked, 1000U);
}

TEST(AsterixRoundTrip, Cat062RecordWithoutPositionIsCounted) {
  std::mt19937 random(1);
  Cat062Truth truth = random_cat062_truth(random, 1000);
  RecordWriter w;
  w.set(asterix::cat062::kDataSource, {1, 2});
  w.set(asterix::cat062::kTimeOfTrack, {0, 0, 128});
  w.set(asterix::cat062::kTrackNumber, {0, 7});
  w.set(asterix::cat062::kMeasuredFl, {0, 100});
  const Bytes cartesian_only = [&] {
    RecordWriter c = w;
    c.set(asterix::cat062::kPositionCartesian, {0, 0, 1, 0, 0, 1});
    return c.bytes();
  }();
  Rejections rejections;
  const auto reports = decode_bytes(
      data_block(62, {w.bytes(), cartesian_only, random_cat062_record(random, truth)}), {}, &rejections);
  ASSERT_EQ(reports.size(), 1U);  // the records after the rejected ones still decode
  expect_matches(reports[0], truth);
  EXPECT_EQ(rejections.count("asterix_missing_position"), 1U);
  EXPECT_EQ(rejections.count("cat062_cartesian_only"), 1U);
}

TEST(AsterixCat062Identity, TrackNumberIsTheIdentityWhetherOrNotTheAddressIsSent) {
  // An SDPS sends I062/380 ADR in some updates of a track and not in others. Keyed by
  // the address when present, such a track became two kew tracks (the address, then the
  // track number) that alerted against each other. The identity is SAC/SIC + I062/040;
  // the address is an attribute of the update that carries it.
  using namespace asterix::cat062;
  RecordWriter with_address = minimal_cat062(128 * 1000, 2603);
  with_address.set(kAircraftDerived, compound_item({{k380Address, {0x4C, 0xA1, 0x23}}}));
  const RecordWriter without_address = minimal_cat062(128 * 1004, 2603);
  Rejections rejections;
  const auto reports =
      decode_bytes(data_block(62, {with_address.bytes(), without_address.bytes()}), {}, &rejections);
  EXPECT_EQ(rejections.total(), 0U);
  ASSERT_EQ(reports.size(), 2U);
  EXPECT_EQ(reports[0].source, "cat062/25.100");
  EXPECT_EQ(reports[0].id, "2603");
  EXPECT_EQ(reports[1].source, reports[0].source);
  EXPECT_EQ(reports[1].id, reports[0].id);
  EXPECT_EQ(reports[0].address, std::optional<std::uint32_t>(0x4CA123));
  EXPECT_FALSE(reports[1].address.has_value());
}

TEST(AsterixCat062Identity, RecordWithoutTrackNumberIsRefusedEvenWithAnAddress) {
  using namespace asterix::cat062;
  RecordWriter address_only = minimal_cat062(128 * 1000, std::nullopt);
  address_only.set(kAircraftDerived, compound_item({{k380Address, {0x4C, 0xA1, 0x23}}}));
  Rejections rejections;
  const auto reports = decode_bytes(
      data_block(62, {address_only.bytes(), minimal_cat062(128 * 1001, std::nullopt).bytes(),
                      minimal_cat062(128 * 1002, 7).bytes()}),
      {}, &rejections);
  ASSERT_EQ(reports.size(), 1U);
  EXPECT_EQ(reports[0].id, "7");
  EXPECT_EQ(rejections.count("asterix_missing_identity"), 2U);
  EXPECT_EQ(rejections.total(), 2U);
}

TEST(AsterixCat062TrackStatus, CoastingIsCstOfTheFourthOctetAndTrackEndTseOfTheSecond) {
  // I062/080, editions 1.16-1.21: MON SPI MRH SRC CNF FX | SIM TSE TSB FPC AFF STP KOS FX |
  // AMA MD4 ME MI MD5 FX | CST PSR SSR MDS ADS SUC AAC FX | ...
  using namespace asterix::cat062;
  struct Case {
    Bytes status;
    bool coasting, track_end;
  };
  const std::vector<Case> cases = {
      {{0x00}, false, false},
      {{0x01, 0x40}, false, true},                    // TSE
      {{0x01, 0x01, 0x01, 0x80}, true, false},        // CST
      {{0x01, 0x41, 0x01, 0x80}, true, true},
      {{0x01, 0x01, 0x80}, false, false},             // AMA, the first bit of octet 3
      // Every other bit set (CNF and SIM would refuse the record): neither flag.
      {{0xFD, 0x3F, 0xFF, 0x7F, 0xFE}, false, false},
  };
  std::vector<Bytes> records;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    RecordWriter w = minimal_cat062(128 * static_cast<std::uint32_t>(1000 + i), 1);
    w.set(kTrackStatus, cases[i].status);
    records.push_back(w.bytes());
  }
  Rejections rejections;
  const auto reports = decode_bytes(data_block(62, records), {}, &rejections);
  EXPECT_EQ(rejections.total(), 0U);
  ASSERT_EQ(reports.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    EXPECT_EQ(reports[i].coasting, cases[i].coasting);
    EXPECT_EQ(reports[i].track_end, cases[i].track_end);
  }
}

TEST(AsterixRoundTrip, TimeOfDayRollsOverToTheNextDay) {
  // 23:59:59, then 00:00:01 and 00:00:02 of the next day (a jump back by more than 12 h),
  // then a late record stamped 23:59:50 (more than 12 h after the latest time of day: it
  // belongs to the previous day and does not move the clock), then 00:00:03.
  std::mt19937 random(7);
  AsterixOptions options;
  options.day_start_utc_s = 1714348800;  // 2024-04-29T00:00:00Z
  Bytes stream;
  for (const double tod : {86399.0, 1.0, 2.0, 86390.0, 3.0}) {
    const Bytes block = data_block(62, {random_cat062_record(random, random_cat062_truth(random, tod))});
    stream.insert(stream.end(), block.begin(), block.end());
  }
  const auto reports = decode_bytes(stream, options);
  ASSERT_EQ(reports.size(), 5U);
  const double day = 1714348800;
  EXPECT_DOUBLE_EQ(reports[0].t, day + 86399);
  EXPECT_DOUBLE_EQ(reports[1].t, day + 86400 + 1);
  EXPECT_DOUBLE_EQ(reports[2].t, day + 86400 + 2);
  EXPECT_DOUBLE_EQ(reports[3].t, day + 86390);
  EXPECT_DOUBLE_EQ(reports[4].t, day + 86400 + 3);
}

TEST(AsterixRoundTrip, ALiveStreamIsDatedByWhenItsBytesArrived) {
  // A live feed started at 00:00:05 (kewd takes today's date) whose first record
  // is a late one stamped 23:59:58 was dated 23:59:58 *today*, a day ahead. Live inputs
  // now tell the decoder when the bytes arrived; each time of day takes the day within
  // 12 h of that, across midnight in both directions, for every framing.
  std::mt19937 random(11);
  const double today = 1714348800 + 86400;  // 2024-04-30T00:00:00Z
  AsterixOptions options;
  options.day_start_utc_s = today;
  for (const AsterixFraming framing : {AsterixFraming::Datagram, AsterixFraming::RawBlocks}) {
    SCOPED_TRACE(static_cast<int>(framing));
    auto decoder = make_asterix_decoder(framing, options);
    std::vector<TrackReport> reports;
    const auto sink = [&](const TrackReport& r) { reports.push_back(r); };
    for (const auto& [received, tod] : {std::pair{today + 5, 86398.0}, std::pair{today + 6, 1.0},
                                        std::pair{today + 86400 - 3, 86396.0}, std::pair{today + 86400 + 2, 1.0}}) {
      decoder->set_receive_time(received);
      const Bytes block = data_block(62, {random_cat062_record(random, random_cat062_truth(random, tod))});
      decoder->feed(std::as_bytes(std::span<const std::uint8_t>(block)), sink);
      decoder->end_message(sink);
    }
    ASSERT_EQ(reports.size(), 4U);
    EXPECT_DOUBLE_EQ(reports[0].t, today - 86400 + 86398);  // yesterday 23:59:58
    EXPECT_DOUBLE_EQ(reports[1].t, today + 1);
    EXPECT_DOUBLE_EQ(reports[2].t, today + 86396);
    EXPECT_DOUBLE_EQ(reports[3].t, today + 86400 + 1);  // tomorrow 00:00:01
  }
}

TEST(AsterixRoundTrip, ACat062FeedAcrossMidnightKeepsAlerting) {
  // A head-on pair 45 NM apart reported by one SDPS every 4 s from 23:59:20
  // UTC, closing at 900 kt: the conflict comes within the 120 s look-ahead after
  // midnight. Decoded as a stream (days counted from the
  // first record) and live (dated by arrival), the records cross midnight in order and
  // the conflict alerts.
  std::mt19937 random(5);
  const double day = 1714348800;  // 2024-04-29T00:00:00Z
  const double metres_per_degree = 111320.0 * std::cos(50.0 * std::numbers::pi / 180.0);
  for (const bool live : {false, true}) {
    SCOPED_TRACE(live ? "live" : "stream");
    AsterixOptions options;
    options.day_start_utc_s = day;
    auto decoder = make_asterix_decoder(AsterixFraming::RawBlocks, options);
    Pipeline pipeline;
    std::size_t opened = 0;
    double opened_at = 0.0;
    pipeline.set_alert_sink([&](const AlertEvent& e) {
      if (e.state != AlertState::New) return;
      ++opened;
      opened_at = e.t;
    });
    const ReportSink sink = [&](const TrackReport& r) { pipeline.process(r); };
    for (double dt = 0.0; dt < 100.0; dt += 4.0) {
      const double t = 86400.0 - 40.0 + dt;  // seconds since the first day's midnight
      for (const int side : {-1, 1}) {
        Cat062Truth truth;
        truth.sac = 1;
        truth.sic = 2;
        truth.tod_s = std::fmod(t, 86400.0);
        truth.track_number = static_cast<std::uint16_t>(side < 0 ? 1 : 2);
        truth.lat = 50.0;
        truth.lon = 8.0 + side * (22.5 * 1852.0 - 231.5 * dt) / metres_per_degree;
        truth.alt_ft = 35000.0;
        truth.vx = -side * 231.5;
        truth.vy = 0.0;
        truth.vr_fpm = 0.0;
        if (live) decoder->set_receive_time(day + t + 0.5);
        const Bytes block = data_block(62, {random_cat062_record(random, truth)});
        decoder->feed(std::as_bytes(std::span<const std::uint8_t>(block)), sink);
      }
    }
    decoder->finish(sink);
    pipeline.end_of_input();
    EXPECT_EQ(opened, 1u);
    EXPECT_GT(opened_at, day + 86400.0);  // after midnight, on the next day
    EXPECT_EQ(pipeline.rejections().total(), 0u);
    EXPECT_EQ(pipeline.statistics().accepted, 50u);
  }
}

TEST(AsterixDayClock, StreamRuleAndCaptureTimeRule) {
  const double day = 86400.0 * 10;
  asterix::DayClock clock(day);
  EXPECT_DOUBLE_EQ(clock.to_utc(3600), day + 3600);
  EXPECT_DOUBLE_EQ(clock.to_utc(43000), day + 43000);      // 10.9 h later: same day
  EXPECT_DOUBLE_EQ(clock.to_utc(42990), day + 42990);      // slightly late: same day
  EXPECT_DOUBLE_EQ(clock.to_utc(100), day + 100);          // back 11.9 h: still same day
  EXPECT_DOUBLE_EQ(clock.to_utc(86000), day + 86000 - 86400);  // 23.9 h ahead: previous day
  EXPECT_DOUBLE_EQ(clock.to_utc(200), day + 200);          // the clock did not move
  EXPECT_DOUBLE_EQ(clock.to_utc(40000), day + 40000);
  EXPECT_DOUBLE_EQ(clock.to_utc(80000), day + 80000);
  EXPECT_DOUBLE_EQ(clock.to_utc(10), day + 86400 + 10);    // back 22.2 h: next day
  EXPECT_DOUBLE_EQ(clock.to_utc(20), day + 86400 + 20);

  // Pcap: the day that puts the time of day within 12 h of the capture time.
  asterix::DayClock pcap_clock(0);
  pcap_clock.set_capture_time(day + 86400 + 100);           // 00:01:40 on day 11
  EXPECT_DOUBLE_EQ(pcap_clock.to_utc(86390), day + 86390);  // 23:59:50 on day 10
  EXPECT_DOUBLE_EQ(pcap_clock.to_utc(50), day + 86400 + 50);
  pcap_clock.set_capture_time(day + 50400);                 // 14:00 on day 10
  EXPECT_DOUBLE_EQ(pcap_clock.to_utc(10800), day + 10800);  // 03:00: 11 h before
  EXPECT_DOUBLE_EQ(pcap_clock.to_utc(3600), day + 86400 + 3600);  // 01:00: 11 h after
}

// ---- Random CAT048 records ----------------------------------------------------------------

TEST(AsterixRoundTrip, RandomCat048PolarPlotsLandWhereTheyWereMeasured) {
  // Targets are placed at random around a site, measured as the radar would (slant range
  // and azimuth of the straight line of sight in the site's local east-north-up frame),
  // quantised into I048/040, and must decode to within the quantisation of RHO and THETA
  // plus the 2 m by which kew's spherical slant-to-ground method may differ (documented in
  // test_asterix_golden.cpp).
  std::mt19937 random(48);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const RadarSite site{25, 7, 47.45, 8.56, 500.0};
  const GeographicLib::LocalCartesian enu(site.lat_deg, site.lon_deg, site.height_m);
  AsterixOptions options;
  options.radars.push_back(site);
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const double ground_m = (10 + 230 * unit(random)) * 1852.0;
    const double azimuth = 360 * unit(random);
    const double fl = std::round(20 + 400 * unit(random));  // whole FL: I048/090 is exact
    double lat = 0, lon = 0;
    GeographicLib::Geodesic::WGS84().Direct(site.lat_deg, site.lon_deg, azimuth, ground_m, lat, lon);
    double x = 0, y = 0, z = 0;
    enu.Forward(lat, lon, fl * 100 / kFtPerM, x, y, z);
    const double rho_nm = std::sqrt(x * x + y * y + z * z) / 1852.0;
    double theta = std::atan2(x, y) * 180 / kPi;
    if (theta < 0) theta += 360;
    if (rho_nm >= 256.0 - 1.0 / 256) continue;

    RecordWriter w;
    w.set(asterix::cat048::kDataSource, {site.sac, site.sic});
    w.set(asterix::cat048::kTimeOfDay, {0x10, 0x00, 0x00});
    w.set(asterix::cat048::kDescriptor, {0xA1, 0x00});  // TYP 5, FX; second octet: TST = 0
    Bytes polar;
    put(polar, static_cast<std::uint64_t>(quantize(rho_nm, 1.0 / 256)), 2);
    put(polar, static_cast<std::uint64_t>(quantize(theta, 360.0 / 65536)) & 0xFFFF, 2);
    w.set(asterix::cat048::kPolarPosition, polar);
    Bytes level;
    put(level, static_cast<std::uint64_t>(fl * 4), 2);
    w.set(asterix::cat048::kFlightLevel, level);
    w.set(7, compound_item({{0, random_bytes(random, 1)}, {6, random_bytes(random, 1)}}));  // 130
    w.set(asterix::cat048::kAddress, {0x4B, 0x18, static_cast<std::uint8_t>(trial)});
    w.set(10, {2, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16});  // 250, REP 2
    w.set(16, random_extended(random, 1));                                   // 030
    w.set(28, {3, 0xAA, 0xBB});                                              // RE
    Rejections rejections;
    const auto reports = decode_bytes(data_block(48, {w.bytes()}), options, &rejections);
    EXPECT_EQ(rejections.total(), 0U);
    ASSERT_EQ(reports.size(), 1U);
    double error_m = 0;
    GeographicLib::Geodesic::WGS84().Inverse(lat, lon, reports[0].lat_deg, reports[0].lon_deg, error_m);
    const double rho_m = rho_nm * 1852.0;
    const double tolerance_m = 1852.0 / 512 + rho_m * (kPi / 65536) + 2.0;
    EXPECT_LT(error_m, tolerance_m);
    EXPECT_EQ(reports[0].alt_ft, fl * 100);
    EXPECT_EQ(reports[0].source, "cat048/25.7");
    EXPECT_EQ(reports[0].address, std::optional<std::uint32_t>(0x4B1800 | static_cast<std::uint8_t>(trial)));
    if (HasFailure()) return;
  }
}

// ---- The item walker ----------------------------------------------------------------------

TEST(AsterixItemWalker, MeasuresEveryItemKind) {
  using namespace asterix;
  const std::uint8_t fx_chain[] = {0x01, 0x03, 0x02, 0xFF};
  EXPECT_EQ(measure_item(extended(), fx_chain, 4).bytes, 3U);
  EXPECT_EQ(measure_item(extended(), fx_chain, 2).error, WalkError::Overflow);
  EXPECT_EQ(measure_item(extended(1, 1, 2), fx_chain, 4).bytes, 2U);  // capped parts
  const std::uint8_t three_byte_parts[] = {0, 0, 1, 0, 0, 0};
  EXPECT_EQ(measure_item(extended(3, 3), three_byte_parts, 6).bytes, 6U);
  const std::uint8_t repetition[] = {2, 1, 2, 3, 4};
  EXPECT_EQ(measure_item(repetitive(2), repetition, 5).bytes, 5U);
  EXPECT_EQ(measure_item(repetitive(3), repetition, 5).error, WalkError::Overflow);
  const std::uint8_t explicit_field[] = {3, 9, 9, 9};
  EXPECT_EQ(measure_item(explicit_length(), explicit_field, 4).bytes, 3U);
  const std::uint8_t zero_length[] = {0, 1};
  EXPECT_EQ(measure_item(explicit_length(), zero_length, 2).error, WalkError::BadExplicitLength);
  EXPECT_EQ(measure_item(undefined_item(), zero_length, 2).error, WalkError::UnknownItem);
}

TEST(AsterixItemWalker, CompoundSubfieldsAreFoundByIndex) {
  using namespace asterix;
  static constexpr std::array subfields{fixed(1), repetitive(2), fixed(3)};
  // Primary 0xA0: subfields 0 and 2; then 1 byte, then 3 bytes.
  const std::uint8_t item[] = {0xA0, 0x11, 0x21, 0x22, 0x23};
  const ItemFormat format = compound(subfields);
  EXPECT_EQ(measure_item(format, item, sizeof item).bytes, 5U);
  const auto third = compound_subfield(format, item, 2);
  ASSERT_EQ(third.size(), 3U);
  EXPECT_EQ(third[0], 0x21);
  EXPECT_TRUE(compound_subfield(format, item, 1).empty());
  // A primary subfield announcing a subfield the format does not define.
  const std::uint8_t unknown[] = {0x10, 0x00};
  EXPECT_EQ(measure_item(format, unknown, sizeof unknown).error, WalkError::UnknownItem);
}

TEST(AsterixItemWalker, UnwalkableRecordEndsItsBlockOnly) {
  std::mt19937 random(3);
  const Cat062Truth truth = random_cat062_truth(random, 500);
  const Bytes good = random_cat062_record(random, truth);
  // FRN 2 of CAT062 is spare: the record cannot be walked, nor the rest of its block.
  const Bytes unknown_item{0x60, 1, 1};
  // An I062/105 announced but cut by the end of the block.
  const Bytes overflow{0x08, 1, 2, 3};
  Bytes stream = data_block(62, {unknown_item, good});
  const Bytes second = data_block(62, {overflow});
  const Bytes third = data_block(62, {good});
  stream.insert(stream.end(), second.begin(), second.end());
  stream.insert(stream.end(), third.begin(), third.end());
  Rejections rejections;
  const auto reports = decode_bytes(stream, {}, &rejections);
  ASSERT_EQ(reports.size(), 1U);
  expect_matches(reports[0], truth);
  EXPECT_EQ(rejections.count("asterix_unknown_item"), 1U);
  EXPECT_EQ(rejections.count("asterix_item_overflow"), 1U);
  EXPECT_EQ(rejections.total(), 2U);
}

}  // namespace
}  // namespace kew::protocol
