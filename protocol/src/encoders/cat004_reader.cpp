#include "kew/protocol/encoders/cat004_reader.hpp"

#include <array>
#include <string>

#include "../asterix/bytes.hpp"
#include "../asterix/record_context.hpp"
#include "kew/protocol/asterix/record_walker.hpp"

namespace kew::protocol {
namespace {

using asterix::be16;
using asterix::be24;
using asterix::be32;
using asterix::ItemFormat;
using asterix::sign_extend;

constexpr std::size_t kBlockHeaderBytes = 3;

// The CAT004 1.12 UAP with every item's format (EUROCONTROL ASTERIX Part 17; the same
// layout as zoranbosnjak/asterix-specs specs/cat004/cats/cat1.12/definition.ast).
// I004/170 and I004/171: AI, M3, CPW, CPC, TT, DT, AC | MS, FP, CF.
constexpr std::array<ItemFormat, 10> kAircraft{
    asterix::fixed(7), asterix::fixed(2), asterix::fixed(10), asterix::fixed(8),
    asterix::fixed(3), asterix::fixed(2), asterix::extended(), asterix::fixed(6),
    asterix::fixed(4), asterix::fixed(2)};
// I004/120: CN, CC, CP, CD.
constexpr std::array<ItemFormat, 4> kConflictCharacteristics{
    asterix::extended(), asterix::fixed(1), asterix::fixed(1), asterix::fixed(3)};
// I004/070: TC, TCA, CHS, MHS, CVS, MVS.
constexpr std::array<ItemFormat, 6> kTimingAndSeparation{
    asterix::fixed(3), asterix::fixed(3), asterix::fixed(3),
    asterix::fixed(2), asterix::fixed(2), asterix::fixed(2)};
// I004/100: AN (6 ICAO characters' worth of octets), CAN, RT1, RT2, SB, G.
constexpr std::array<ItemFormat, 6> kAreaDefinition{
    asterix::fixed(6), asterix::fixed(7), asterix::fixed(7),
    asterix::fixed(7), asterix::fixed(7), asterix::fixed(7)};

enum Frn : unsigned {
  kSource = 1, kMessageType = 2, kSdps = 3, kTimeOfMessage = 4, kAlertId = 5,
  kAlertStatus = 6, kFunctionStatus = 7, kTrackNumber1 = 8, kAircraft1 = 9,
  kConflict = 10, kTiming = 11, kVerticalDeviation = 12, kLongitudinalDeviation = 13,
  kTransversalDeviation = 14, kArea = 15, kTrackNumber2 = 16, kAircraft2 = 17,
};

constexpr std::array<ItemFormat, 21> kUap{
    asterix::fixed(2),                                  // 010
    asterix::fixed(1),                                  // 000
    asterix::repetitive(2),                             // 015
    asterix::fixed(3),                                  // 020
    asterix::fixed(2),                                  // 040
    asterix::fixed(1),                                  // 045
    asterix::extended(),                                // 060
    asterix::fixed(2),                                  // 030
    asterix::compound(kAircraft),                       // 170
    asterix::compound(kConflictCharacteristics),        // 120
    asterix::compound(kTimingAndSeparation),            // 070
    asterix::fixed(2),                                  // 076
    asterix::fixed(2),                                  // 074
    asterix::fixed(3),                                  // 075
    asterix::compound(kAreaDefinition),                 // 100
    asterix::fixed(2),                                  // 035
    asterix::compound(kAircraft),                       // 171
    asterix::repetitive(2),                             // 110
    asterix::undefined_item(),                          // spare
    asterix::explicit_length(),                         // RE
    asterix::explicit_length(),                         // SP
};
const asterix::Uap kCat004Uap{kUap};

std::optional<double> unsigned_quantity(std::span<const std::uint8_t> field, double lsb) {
  if (field.empty()) return std::nullopt;
  std::uint32_t raw = 0;
  for (const std::uint8_t octet : field) raw = (raw << 8) | octet;
  return raw * lsb;
}

std::optional<double> signed_quantity(std::span<const std::uint8_t> field, double lsb) {
  const auto raw = unsigned_quantity(field, 1.0);
  if (!raw) return std::nullopt;
  const auto bits = static_cast<unsigned>(8 * field.size());
  return sign_extend(static_cast<std::uint32_t>(*raw), bits) * lsb;
}

std::vector<std::uint8_t> octets(std::span<const std::uint8_t> field) {
  return {field.begin(), field.end()};
}

Cat004Aircraft read_aircraft(const ItemFormat& format, std::span<const std::uint8_t> item) {
  const auto subfield = [&](std::size_t index) {
    return asterix::compound_subfield(format, item, index);
  };
  Cat004Aircraft aircraft;
  std::string text;
  if (const auto ai = subfield(0); !ai.empty() && asterix::decode_ascii_characters(ai, text)) {
    aircraft.identifier = text;
  }
  if (const auto m3 = subfield(1); !m3.empty()) {
    aircraft.mode3a = static_cast<std::uint16_t>(be16(m3.data()) & 0x0FFF);
  }
  if (const auto cpw = subfield(2); !cpw.empty()) {
    constexpr double kDegreesPerLsb = 180.0 / 33554432.0;  // 180 / 2^25
    aircraft.predicted_lat_deg = sign_extend(be32(cpw.data()), 32) * kDegreesPerLsb;
    aircraft.predicted_lon_deg = sign_extend(be32(cpw.data() + 4), 32) * kDegreesPerLsb;
    aircraft.predicted_alt_ft = sign_extend(be16(cpw.data() + 8), 16) * 25.0;
  }
  if (const auto ms = subfield(7); !ms.empty() && asterix::decode_icao_characters(ms.data(), text)) {
    aircraft.mode_s_identification = text;
  }
  aircraft.cleared_flight_level = unsigned_quantity(subfield(9), 0.25);
  return aircraft;
}

void read_items(const asterix::RecordItems& items, Cat004Record& r) {
  if (items.has(kSource)) r.source = Cat004SourceId{items.data(kSource)[0], items.data(kSource)[1]};
  if (items.has(kMessageType)) r.message_type = items.data(kMessageType)[0];
  if (const auto sdps = items.item(kSdps); !sdps.empty()) {
    for (std::size_t i = 1; i + 1 < sdps.size(); i += 2) r.sdps.push_back({sdps[i], sdps[i + 1]});
  }
  r.time_of_day_s = unsigned_quantity(items.item(kTimeOfMessage), 1.0 / 128.0);
  if (items.has(kAlertId)) r.alert_id = static_cast<std::uint16_t>(be16(items.data(kAlertId)));
  if (items.has(kAlertStatus)) {
    r.alert_status = static_cast<std::uint8_t>((items.data(kAlertStatus)[0] >> 1) & 0x7);
  }
  r.function_status = octets(items.item(kFunctionStatus));
  if (items.has(kTrackNumber1)) {
    r.track_number_1 = static_cast<std::uint16_t>(be16(items.data(kTrackNumber1)));
  }
  if (items.has(kTrackNumber2)) {
    r.track_number_2 = static_cast<std::uint16_t>(be16(items.data(kTrackNumber2)));
  }
  if (items.has(kAircraft1)) r.aircraft_1 = read_aircraft(kUap[kAircraft1 - 1], items.item(kAircraft1));
  if (items.has(kAircraft2)) r.aircraft_2 = read_aircraft(kUap[kAircraft2 - 1], items.item(kAircraft2));

  if (items.has(kConflict)) {
    const auto subfield = [&](std::size_t index) {
      return asterix::compound_subfield(kUap[kConflict - 1], items.item(kConflict), index);
    };
    r.has_conflict_characteristics = true;
    r.conflict_nature = octets(subfield(0));
    if (const auto cc = subfield(1); !cc.empty()) {
      r.conflict_classification = cc[0];
      constexpr std::uint8_t kApw = 5, kStca = 7;
      constexpr unsigned kTableOne = 1;
      // The CPC bits mean something only under a (message type, TID) case of the edition.
      if (r.message_type == kStca && (cc[0] >> 4) == kTableOne) {
        r.stca_filters = Cat004StcaFilters{(cc[0] & 0x08) != 0, (cc[0] & 0x04) != 0,
                                           (cc[0] & 0x02) != 0};
      }
      if (r.message_type == kApw && (cc[0] >> 4) == kTableOne) {
        r.apw_severity = static_cast<std::uint8_t>((cc[0] >> 1) & 0x7);
      }
    }
    r.conflict_probability_pct = unsigned_quantity(subfield(2), 0.5);
    r.conflict_duration_s = unsigned_quantity(subfield(3), 1.0 / 128.0);
  }
  if (items.has(kTiming)) {
    const auto subfield = [&](std::size_t index) {
      return asterix::compound_subfield(kUap[kTiming - 1], items.item(kTiming), index);
    };
    r.time_to_conflict_s = unsigned_quantity(subfield(0), 1.0 / 128.0);
    r.time_to_closest_approach_s = unsigned_quantity(subfield(1), 1.0 / 128.0);
    r.current_horizontal_separation_m = unsigned_quantity(subfield(2), 0.5);
    r.minimum_horizontal_separation_m = unsigned_quantity(subfield(3), 0.5);
    r.current_vertical_separation_ft = unsigned_quantity(subfield(4), 25.0);
    r.minimum_vertical_separation_ft = unsigned_quantity(subfield(5), 25.0);
  }
  r.vertical_deviation_ft = signed_quantity(items.item(kVerticalDeviation), 25.0);
  r.longitudinal_deviation_m = signed_quantity(items.item(kLongitudinalDeviation), 32.0);
  r.transversal_deviation_m = signed_quantity(items.item(kTransversalDeviation), 0.5);
  if (items.has(kArea)) {
    const auto an = asterix::compound_subfield(kUap[kArea - 1], items.item(kArea), 0);
    std::string text;
    if (!an.empty() && asterix::decode_icao_characters(an.data(), text)) r.area_name = text;
  }
}

}  // namespace

void Cat004Reader::read(std::span<const std::byte> datagram, const RecordSink& sink) {
  const std::uint8_t* bytes = asterix::as_uint8(datagram);
  std::size_t offset = 0;
  while (offset < datagram.size()) {
    const std::size_t left = datagram.size() - offset;
    if (left < kBlockHeaderBytes) {
      rejections_.reject("cat004_bad_block_length", "data block header cut short");
      return;
    }
    const unsigned category = bytes[offset];
    const std::size_t length = be16(bytes + offset + 1);
    if (length < kBlockHeaderBytes || length > left) {
      rejections_.reject("cat004_bad_block_length",
                         "data block length " + std::to_string(length) + " with " +
                             std::to_string(left) + " bytes left");
      return;
    }
    const std::size_t block_end = offset + length;
    std::size_t position = offset + kBlockHeaderBytes;
    offset = block_end;
    if (category != 4) {
      rejections_.reject("cat004_other_category",
                         "data block of category " + std::to_string(category));
      continue;
    }
    asterix::RecordItems items;
    while (position < block_end) {
      const asterix::RecordWalk walk =
          asterix::walk_record(kCat004Uap, bytes + position, block_end - position, items);
      if (walk.error != asterix::WalkError::None) {
        rejections_.reject("cat004_malformed_record",
                           std::string(asterix::walk_error_reason(walk.error)) + " at FRN " +
                               std::to_string(walk.frn) + "; rest of the block dropped");
        break;
      }
      Cat004Record record;
      read_items(items, record);
      sink(record);
      position += walk.bytes;
    }
  }
}

}  // namespace kew::protocol
