// CAT062 (SDPS track messages) record → TrackReport. Items and scalings: ASTERIX Part 9,
// editions 1.16-1.21; protocol/docs/asterix.md lists what is read and what is ignored.

#include "bytes.hpp"
#include "kew/protocol/asterix/uap.hpp"
#include "record_context.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr double kLatLonLsbDeg = 180.0 / 33554432.0;  // 180 / 2^25
constexpr double kVelocityLsbMs = 0.25;
constexpr double kQuarterFlightLevelFt = kFeetPerFlightLevel / 4.0;
constexpr double kGeometricAltitudeLsbFt = 6.25;
constexpr double kRateOfClimbLsbFpm = 6.25;

const ItemFormat& format_of(unsigned frn) { return cat062_uap().items[frn - 1]; }

/// Altitude in feet by preference: measured FL (I062/136), the tracker's barometric
/// altitude (I062/135), its geometric altitude (I062/130).
bool read_altitude(const RecordItems& items, double& alt_ft) {
  using namespace cat062;
  if (items.has(kMeasuredFl)) {
    alt_ft = sign_extend(be16(items.data(kMeasuredFl)), 16) * kQuarterFlightLevelFt;
    return true;
  }
  if (items.has(kBarometricAlt)) {
    // Bit 16 is the QNH correction flag; the altitude is 15-bit two's complement.
    alt_ft = sign_extend(be16(items.data(kBarometricAlt)), 15) * kQuarterFlightLevelFt;
    return true;
  }
  if (items.has(kGeometricAlt)) {
    alt_ft = sign_extend(be16(items.data(kGeometricAlt)), 16) * kGeometricAltitudeLsbFt;
    return true;
  }
  return false;
}

/// Callsign by preference: downlinked identification (I062/245), the identification in
/// aircraft derived data (I062/380 ID), the flight plan callsign (I062/390 CSN).
void read_callsign(const RecordItems& items, std::string& callsign) {
  using namespace cat062;
  if (items.has(kTargetId) && decode_icao_characters(items.data(kTargetId) + 1, callsign)) return;
  const auto derived_id = compound_subfield(format_of(kAircraftDerived),
                                            items.item(kAircraftDerived), k380Identification);
  if (derived_id.size() == 6 && decode_icao_characters(derived_id.data(), callsign)) return;
  const auto plan_callsign =
      compound_subfield(format_of(kFlightPlan), items.item(kFlightPlan), k390Callsign);
  if (!plan_callsign.empty()) decode_ascii_characters(plan_callsign, callsign);
}

/// Selected altitude (I062/380 SAL, else FSS) and track angle rate (I062/380 TAR).
void read_intent(const RecordItems& items, TrackReport& report) {
  using namespace cat062;
  const ItemFormat& format = format_of(kAircraftDerived);
  const auto derived = items.item(kAircraftDerived);
  if (derived.empty()) return;
  set_selected_altitude(compound_subfield(format, derived, k380SelectedAltitude),
                        compound_subfield(format, derived, k380FinalSelectedAltitude), report);
  set_turn_indicator_rate(compound_subfield(format, derived, k380TrackAngleRate), report);
}

}  // namespace

bool decode_cat062(const RecordItems& items, RecordContext& context, TrackReport& report) {
  using namespace cat062;
  Rejections& rejections = context.rejections;
  if (!items.has(kDataSource)) {
    rejections.reject("asterix_missing_data_source", "CAT062 record without I062/010");
    return false;
  }
  if (!items.has(kTimeOfTrack)) {
    rejections.reject("asterix_missing_time", "CAT062 record without I062/070");
    return false;
  }
  if (items.has(kTrackStatus)) {
    // I062/080 octets (editions 1.16-1.21): MON SPI MRH SRC(3) CNF FX | SIM TSE TSB FPC
    // AFF STP KOS FX | AMA MD4(2) ME MI MD5(2) FX | CST PSR SSR MDS ADS SUC AAC FX | ...
    // An extension absent from the record means its bits are 0.
    const auto status = items.item(kTrackStatus);
    if ((status[0] & 0x02) != 0) {
      rejections.reject("asterix_tentative_track", "CAT062 track status CNF: tentative");
      return false;
    }
    if (status.size() >= 2 && (status[1] & 0x80) != 0) {
      rejections.reject("asterix_simulated_target", "CAT062 track status SIM: simulated");
      return false;
    }
    report.track_end = status.size() >= 2 && (status[1] & 0x40) != 0;
    report.coasting = status.size() >= 4 && (status[3] & 0x80) != 0;
  }
  if (!items.has(kPositionWgs84)) {
    // I062/100 is relative to the SDPS's system reference point, which ASTERIX does not
    // carry: without I062/105 there is no usable position.
    if (items.has(kPositionCartesian)) {
      rejections.reject("cat062_cartesian_only", "CAT062 record with I062/100 but no I062/105");
    } else {
      rejections.reject("asterix_missing_position", "CAT062 record without I062/105");
    }
    return false;
  }
  if (!read_altitude(items, report.alt_ft)) {
    rejections.reject("asterix_missing_altitude", "CAT062 record without I062/136, 135 or 130");
    return false;
  }
  // The track is SAC/SIC + system track number. An SDPS need not send I062/380 ADR in
  // every update of a track, so the address keys nothing: it is an attribute.
  if (!items.has(kTrackNumber)) {
    rejections.reject("asterix_missing_identity", "CAT062 record without I062/040 track number");
    return false;
  }
  set_track_number_id(be16(items.data(kTrackNumber)), report);
  const auto address =
      compound_subfield(format_of(kAircraftDerived), items.item(kAircraftDerived), k380Address);
  if (address.size() == 3) report.address = be24(address.data());
  if (!set_time_of_day(items.data(kTimeOfTrack), context, report)) return false;

  const std::uint8_t* position = items.data(kPositionWgs84);
  report.lat_deg = sign_extend(be32(position), 32) * kLatLonLsbDeg;
  report.lon_deg = sign_extend(be32(position + 4), 32) * kLatLonLsbDeg;
  if (!accept_position(context, report)) return false;
  set_source("cat062", items.data(kDataSource), report);

  if (items.has(kVelocity)) {
    const std::uint8_t* velocity = items.data(kVelocity);
    set_velocity_from_cartesian(sign_extend(be16(velocity), 16) * kVelocityLsbMs,
                                sign_extend(be16(velocity + 2), 16) * kVelocityLsbMs, report);
  }
  if (items.has(kRateOfClimb)) {
    report.vr_fpm = sign_extend(be16(items.data(kRateOfClimb)), 16) * kRateOfClimbLsbFpm;
  }
  if (items.has(kMode3A)) report.mode3a = static_cast<std::uint16_t>(be16(items.data(kMode3A)) & 0x0FFF);
  read_callsign(items, report.callsign);
  read_intent(items, report);
  return true;
}

}  // namespace kew::protocol::asterix
