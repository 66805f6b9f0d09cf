// CAT021 (ADS-B target reports) record → TrackReport, editions 2.x and 0.26.
// Items and scalings: ASTERIX Part 12; protocol/docs/asterix.md.

#include <initializer_list>

#include "bytes.hpp"
#include "kew/protocol/asterix/uap.hpp"
#include "record_context.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr double kLowResLsbDeg = 180.0 / 8388608.0;        // 180 / 2^23
constexpr double kV026PositionLsbDeg = 180.0 / 33554432.0; // 180 / 2^25
constexpr double kHighResLsbDeg = 180.0 / 1073741824.0;    // 180 / 2^30
constexpr double kSpeedLsbKt = 3600.0 / 16384.0;           // 2^-14 NM/s in knots
constexpr double kAngleLsbDeg = 360.0 / 65536.0;
constexpr double kQuarterFlightLevelFt = kFeetPerFlightLevel / 4.0;
constexpr double kHeightLsbFt = 6.25;
constexpr double kVerticalRateLsbFpm = 6.25;
constexpr double kTrackAngleRateLsbDps = 1.0 / 32.0;

/// Checks shared by both editions after the edition-specific items are read: identity,
/// altitude (ground targets may lack one), time, position.
struct Cat021Fields {
  const std::uint8_t* data_source = nullptr;
  const std::uint8_t* address = nullptr;
  const std::uint8_t* time_of_day = nullptr;
  bool has_altitude = false;
  bool has_position = false;
};

bool finish_common(const Cat021Fields& fields, RecordContext& context, TrackReport& report) {
  Rejections& rejections = context.rejections;
  if (fields.data_source == nullptr) {
    rejections.reject("asterix_missing_data_source", "CAT021 record without I021/010");
    return false;
  }
  if (fields.time_of_day == nullptr) {
    rejections.reject("asterix_missing_time", "CAT021 record without a time of day");
    return false;
  }
  if (!fields.has_position) {
    rejections.reject("asterix_missing_position", "CAT021 record without I021/130 or 131");
    return false;
  }
  if (!fields.has_altitude) {
    // Surface reports carry no altitude; they are kept (flagged on the ground) at 0 ft.
    if (!report.on_ground) {
      rejections.reject("asterix_missing_altitude", "CAT021 record without I021/145 or 140");
      return false;
    }
    report.alt_ft = 0;
  }
  if (fields.address == nullptr) {
    rejections.reject("asterix_missing_identity", "CAT021 record without I021/080");
    return false;
  }
  // ADS-B has no track number: the address is the identity and an attribute both.
  report.address = be24(fields.address);
  set_address_id(*report.address, report);
  if (!set_time_of_day(fields.time_of_day, context, report)) return false;
  if (!accept_position(context, report)) return false;
  set_source("cat021", fields.data_source, report);
  return true;
}

/// The first of the given time items present.
const std::uint8_t* first_present(const RecordItems& items, std::initializer_list<unsigned> frns) {
  for (const unsigned frn : frns) {
    if (items.has(frn)) return items.data(frn);
  }
  return nullptr;
}

const std::uint8_t* data_or_null(const RecordItems& items, unsigned frn) {
  return items.has(frn) ? items.data(frn) : nullptr;
}

void read_vertical_rate(const RecordItems& items, unsigned barometric, unsigned geometric,
                        unsigned value_bits, TrackReport& report) {
  const std::uint8_t* rate = first_present(items, {barometric, geometric});
  if (rate != nullptr) report.vr_fpm = sign_extend(be16(rate), value_bits) * kVerticalRateLsbFpm;
}

}  // namespace

bool decode_cat021(const RecordItems& items, RecordContext& context, TrackReport& report) {
  using namespace cat021;
  if (items.has(kDescriptor)) {
    const auto descriptor = items.item(kDescriptor);
    if (descriptor.size() >= 2) {
      if ((descriptor[1] & 0x20) != 0) {
        context.rejections.reject("asterix_simulated_target", "CAT021 descriptor SIM: simulated");
        return false;
      }
      if ((descriptor[1] & 0x10) != 0) {
        context.rejections.reject("asterix_test_target", "CAT021 descriptor TST: test target");
        return false;
      }
      report.on_ground = (descriptor[1] & 0x40) != 0;
    }
  }
  Cat021Fields fields;
  fields.data_source = data_or_null(items, kDataSource);
  fields.address = data_or_null(items, kAddress);
  // The time the position applies to, else when it was received, else when the report
  // was sent.
  fields.time_of_day = first_present(
      items, {kTimeOfPosition, kTimeOfPositionRx, kTimeOfVelocityRx, kTimeOfTransmission});
  if (items.has(kPositionHighRes)) {
    const std::uint8_t* position = items.data(kPositionHighRes);
    report.lat_deg = sign_extend(be32(position), 32) * kHighResLsbDeg;
    report.lon_deg = sign_extend(be32(position + 4), 32) * kHighResLsbDeg;
    fields.has_position = true;
  } else if (items.has(kPosition)) {
    const std::uint8_t* position = items.data(kPosition);
    report.lat_deg = sign_extend(be24(position), 24) * kLowResLsbDeg;
    report.lon_deg = sign_extend(be24(position + 3), 24) * kLowResLsbDeg;
    fields.has_position = true;
  }
  if (items.has(kFlightLevel)) {
    report.alt_ft = sign_extend(be16(items.data(kFlightLevel)), 16) * kQuarterFlightLevelFt;
    fields.has_altitude = true;
  } else if (items.has(kGeometricHeight)) {
    report.alt_ft = sign_extend(be16(items.data(kGeometricHeight)), 16) * kHeightLsbFt;
    fields.has_altitude = true;
  }
  if (!finish_common(fields, context, report)) return false;

  if (items.has(kGroundVector)) {
    const std::uint8_t* vector = items.data(kGroundVector);
    // Bit 16 is the range-exceeded flag; the speed is the 15 bits below it.
    report.gs_kt = (be16(vector) & 0x7FFF) * kSpeedLsbKt;
    report.trk_deg = be16(vector + 2) * kAngleLsbDeg;
  }
  read_vertical_rate(items, kBaroVerticalRate, kGeoVerticalRate, 15, report);
  if (items.has(kMode3A)) report.mode3a = static_cast<std::uint16_t>(be16(items.data(kMode3A)) & 0x0FFF);
  if (items.has(kIdentification)) decode_icao_characters(items.data(kIdentification), report.callsign);
  set_selected_altitude(items.item(kSelectedAltitude), items.item(kFinalSelectedAltitude), report);
  if (items.has(kTrackAngleRate)) {
    // Editions 2.x: 6 spare bits, then a 10-bit two's complement rate, LSB 1/32 deg/s,
    // positive turning right. No availability bit: present means given.
    report.tar_dps = sign_extend(be16(items.data(kTrackAngleRate)), 10) * kTrackAngleRateLsbDps;
  }
  return true;
}

bool decode_cat021_v026(const RecordItems& items, RecordContext& context, TrackReport& report) {
  using namespace cat021_v026;
  if (items.has(kDescriptor)) {
    const std::uint8_t descriptor = items.data(kDescriptor)[0];
    if ((descriptor & 0x20) != 0) {
      context.rejections.reject("asterix_simulated_target", "CAT021 descriptor SIM: simulated");
      return false;
    }
    if ((descriptor & 0x10) != 0) {
      context.rejections.reject("asterix_test_target", "CAT021 descriptor TST: test target");
      return false;
    }
    report.on_ground = (descriptor & 0x40) != 0;
  }
  Cat021Fields fields;
  fields.data_source = data_or_null(items, kDataSource);
  fields.address = data_or_null(items, kAddress);
  fields.time_of_day = data_or_null(items, kTimeOfDay);
  if (items.has(kPosition)) {
    const std::uint8_t* position = items.data(kPosition);
    report.lat_deg = sign_extend(be32(position), 32) * kV026PositionLsbDeg;
    report.lon_deg = sign_extend(be32(position + 4), 32) * kV026PositionLsbDeg;
    fields.has_position = true;
  }
  if (items.has(kFlightLevel)) {
    report.alt_ft = sign_extend(be16(items.data(kFlightLevel)), 16) * kQuarterFlightLevelFt;
    fields.has_altitude = true;
  } else if (items.has(kGeometricAltitude)) {
    report.alt_ft = sign_extend(be16(items.data(kGeometricAltitude)), 16) * kHeightLsbFt;
    fields.has_altitude = true;
  }
  if (!finish_common(fields, context, report)) return false;

  if (items.has(kGroundVector)) {
    const std::uint8_t* vector = items.data(kGroundVector);
    // Two's complement in this edition; a negative speed is meaningless and is dropped.
    const std::int32_t speed = sign_extend(be16(vector), 16);
    if (speed >= 0) {
      report.gs_kt = speed * kSpeedLsbKt;
      report.trk_deg = be16(vector + 2) * kAngleLsbDeg;
    }
  }
  read_vertical_rate(items, kBaroVerticalRate, kGeoVerticalRate, 16, report);
  if (items.has(kMode3A)) report.mode3a = static_cast<std::uint16_t>(be16(items.data(kMode3A)) & 0x0FFF);
  if (items.has(kIdentification)) decode_icao_characters(items.data(kIdentification), report.callsign);
  set_selected_altitude(items.item(kSelectedAltitude), items.item(kFinalSelectedAltitude), report);
  // I021/165 Rate Of Turn: TI octet (FX), then the rate octet (FX), as I062/380 TAR.
  set_turn_indicator_rate(items.item(kRateOfTurn), report);
  return true;
}

}  // namespace kew::protocol::asterix
