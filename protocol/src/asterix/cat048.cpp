// CAT048 (monoradar target reports) record → TrackReport. Items and scalings: ASTERIX
// Part 4, editions 1.15-1.32; the polar position is converted with RadarProjector.

#include <algorithm>

#include <fmt/format.h>

#include "bytes.hpp"
#include "kew/protocol/asterix/uap.hpp"
#include "record_context.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr double kRhoLsbNm = 1.0 / 256.0;
constexpr double kAngleLsbDeg = 360.0 / 65536.0;
constexpr double kSpeedLsbKt = 3600.0 / 16384.0;  // 2^-14 NM/s in knots
constexpr double kQuarterFlightLevelFt = kFeetPerFlightLevel / 4.0;

/// Flight level (I048/090) in feet, unless the code is garbled. The 14-bit value is two's
/// complement (ASTERIX Part 4 §5.2.8); non-validated codes are kept, as the radar's best
/// estimate.
bool read_flight_level(const RecordItems& items, double& alt_ft) {
  if (!items.has(cat048::kFlightLevel)) return false;
  const std::uint32_t raw = be16(items.data(cat048::kFlightLevel));
  if ((raw & 0x4000) != 0) return false;
  alt_ft = sign_extend(raw, 14) * kQuarterFlightLevelFt;
  return true;
}

/// Flight status (I048/230 STAT) 1 or 3: the transponder reports "on the ground".
bool reports_on_ground(const RecordItems& items) {
  if (!items.has(cat048::kCommsCapability)) return false;
  const std::uint32_t status = (be16(items.data(cat048::kCommsCapability)) >> 10) & 0x7;
  return status == 1 || status == 3;
}

// ---- I048/250 Mode S MB data (design §5.2) --------------------------------------------
// Each element: 56 bits of MB data, then BDS1 (4 bits) and BDS2 (4 bits) naming the
// register (0,0 for a Comm-B broadcast, which names none: ignored). Register layouts:
// ICAO Doc 9871 (Technical Provisions for Mode S Services), Tables A-2-64 (BDS 4,0) and
// A-2-80 (BDS 5,0); bit 1 is the most significant bit of the MB field.

constexpr std::size_t kMbElementBytes = 8;
constexpr double kSelectedAltitudeLsbFt = 16.0;
constexpr double kTrackAngleRateLsbDps = 8.0 / 256.0;

/// Bits `first`..`last` (1-based, inclusive, as Doc 9871 numbers them) of a 56-bit MB field.
std::uint32_t mb_bits(std::uint64_t mb, unsigned first, unsigned last) {
  const unsigned width = last - first + 1;
  return static_cast<std::uint32_t>((mb >> (56 - last)) & ((std::uint64_t{1} << width) - 1));
}

/// BDS 4,0 selected vertical intention: the FMS selected altitude when the target altitude
/// source is valid (bit 54) and says FMS (bits 55-56 = 11) and the FMS value is valid (bit
/// 14); else the MCP/FCU selected altitude when valid (bit 1). Nothing else is trusted.
void read_bds40(std::uint64_t mb, TrackReport& report) {
  const bool fms_targeted = mb_bits(mb, 54, 54) != 0 && mb_bits(mb, 55, 56) == 3;
  if (fms_targeted && mb_bits(mb, 14, 14) != 0) {
    report.sel_ft = mb_bits(mb, 15, 26) * kSelectedAltitudeLsbFt;
    report.sel_src = SelectedAltitudeSource::Fms;
  } else if (mb_bits(mb, 1, 1) != 0) {
    report.sel_ft = mb_bits(mb, 2, 13) * kSelectedAltitudeLsbFt;
    report.sel_src = SelectedAltitudeSource::Mcp;
  }
}

/// BDS 5,0 track and turn report: the track angle rate when its status (bit 35) is set;
/// sign (bit 36, 1 = left) and 9 bits (37-45) are one 10-bit two's complement value.
void read_bds50(std::uint64_t mb, TrackReport& report) {
  if (mb_bits(mb, 35, 35) == 0) return;
  report.tar_dps = sign_extend(mb_bits(mb, 36, 45), 10) * kTrackAngleRateLsbDps;
}

/// sel_ft from the first BDS 4,0 element that gives one, tar_dps from the first BDS 5,0.
void read_mode_s_registers(const RecordItems& items, TrackReport& report) {
  const auto item = items.item(cat048::kModeSMbData);
  if (item.empty()) return;
  const std::size_t elements = std::min<std::size_t>(item[0], (item.size() - 1) / kMbElementBytes);
  for (std::size_t i = 0; i < elements; ++i) {
    const std::uint8_t* element = item.data() + 1 + i * kMbElementBytes;
    const std::uint64_t mb = (std::uint64_t{be24(element)} << 32) | be32(element + 3);
    if (element[7] == 0x40 && !report.sel_ft) read_bds40(mb, report);
    if (element[7] == 0x50 && !report.tar_dps) read_bds50(mb, report);
  }
}

}  // namespace

bool decode_cat048(const RecordItems& items, RecordContext& context, TrackReport& report) {
  using namespace cat048;
  Rejections& rejections = context.rejections;
  if (!items.has(kDataSource)) {
    rejections.reject("asterix_missing_data_source", "CAT048 record without I048/010");
    return false;
  }
  if (!items.has(kTimeOfDay)) {
    rejections.reject("asterix_missing_time", "CAT048 record without I048/140");
    return false;
  }
  if (items.has(kDescriptor)) {
    const auto descriptor = items.item(kDescriptor);
    if ((descriptor[0] & 0x10) != 0) {
      rejections.reject("asterix_simulated_target", "CAT048 descriptor SIM: simulated");
      return false;
    }
    if (descriptor.size() >= 2 && (descriptor[1] & 0x80) != 0) {
      rejections.reject("asterix_test_target", "CAT048 descriptor TST: test target");
      return false;
    }
  }
  if (items.has(kTrackStatus)) {
    // I048/170 octets (editions 1.15-1.32): CNF RAD(2) DOU MAH CDM(2) FX | TRE GHO SUP TCC
    // spare(3) FX. No bit says the track is coasted, so CAT048 never sets `coasting`.
    const auto status = items.item(kTrackStatus);
    if ((status[0] & 0x80) != 0) {
      rejections.reject("asterix_tentative_track", "CAT048 track status CNF: tentative");
      return false;
    }
    report.track_end = status.size() >= 2 && (status[1] & 0x80) != 0;
  }
  const std::uint8_t* source = items.data(kDataSource);
  const int site = context.radars.find(source[0], source[1]);
  if (site < 0) {
    // Named so that the user knows which site to add (each radar's message once, as
    // every other refusal, rate-limited by the counter).
    rejections.reject("cat048_unknown_radar",
                      fmt::format("CAT048 plot of radar SAC {} SIC {}, which has no site: add a [[radar]] table "
                                  "with sac = {}, sic = {} and its position",
                                  source[0], source[1], source[0], source[1]));
    return false;
  }
  if (!items.has(kPolarPosition)) {
    rejections.reject("asterix_missing_position", "CAT048 record without I048/040");
    return false;
  }
  report.on_ground = reports_on_ground(items);
  if (!read_flight_level(items, report.alt_ft)) {
    // A ground target without Mode C is still placed (at height 0); an airborne one cannot
    // be: its slant range needs a height.
    if (!report.on_ground) {
      rejections.reject("asterix_missing_altitude", "CAT048 record without a usable I048/090");
      return false;
    }
    report.alt_ft = 0;
  }
  // Identity as in CAT062: SAC/SIC + track number, the address an attribute (a Mode S
  // address can come and go within one track). A plot of a radar that does not track has
  // no track number and is keyed by its address; the two never collide within a source,
  // track numbers having at most 4 digits (12 bits) and addresses always 6.
  if (items.has(kAddress)) report.address = be24(items.data(kAddress));
  if (items.has(kTrackNumber)) {
    set_track_number_id(be16(items.data(kTrackNumber)) & 0x0FFF, report);
  } else if (report.address) {
    set_address_id(*report.address, report);
  } else {
    rejections.reject("asterix_missing_identity", "CAT048 record without I048/161 or I048/220");
    return false;
  }
  if (!set_time_of_day(items.data(kTimeOfDay), context, report)) return false;

  const std::uint8_t* polar = items.data(kPolarPosition);
  const double slant_m = be16(polar) * kRhoLsbNm * kMetresPerNauticalMile;
  const double azimuth_deg = be16(polar + 2) * kAngleLsbDeg;
  const GeodeticPoint point =
      context.radars.project(site, slant_m, azimuth_deg, report.alt_ft * kMetresPerFoot);
  report.lat_deg = point.lat_deg;
  report.lon_deg = point.lon_deg;
  if (!accept_position(context, report)) return false;
  set_source("cat048", source, report);

  if (items.has(kVelocity)) {
    const std::uint8_t* velocity = items.data(kVelocity);
    report.gs_kt = be16(velocity) * kSpeedLsbKt;
    report.trk_deg = be16(velocity + 2) * kAngleLsbDeg;
  }
  if (items.has(kMode3A)) {
    // I048/070: V (bit 16) = code not validated, G (bit 15) = garbled. Such a code is no
    // identity and must not exclude a track (design §4.5): it is left out.
    const std::uint16_t word = static_cast<std::uint16_t>(be16(items.data(kMode3A)));
    if ((word & 0xC000) == 0) report.mode3a = static_cast<std::uint16_t>(word & 0x0FFF);
  }
  if (items.has(kIdentification)) decode_icao_characters(items.data(kIdentification), report.callsign);
  read_mode_s_registers(items, report);
  return true;
}

}  // namespace kew::protocol::asterix
