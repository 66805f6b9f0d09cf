#pragma once
// A reader of ASTERIX CAT004 edition 1.12 (Safety Net Messages): every item of the UAP is
// walked (with the ASTERIX decoder's record walker) so any valid record parses; the items
// kew sends, and a few more, are decoded into plain values in the units of the
// specification. It checks kew's encoder, and lets a client (or a test) read a
// safety-net feed. Malformed input is counted, never thrown.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kew/protocol/encoders/cat004.hpp"
#include "kew/util/rejections.hpp"

namespace kew::protocol {

/// I004/170 or I004/171.
struct Cat004Aircraft {
  /// AI: aircraft identifier, 7 ASCII characters, spaces trimmed; absent when blank or
  /// not printable ASCII.
  std::optional<std::string> identifier;
  /// M3: Mode 3/A code, 12 bits (four octal digits).
  std::optional<std::uint16_t> mode3a;
  /// CPW: predicted conflict position, degrees and feet.
  std::optional<double> predicted_lat_deg;
  std::optional<double> predicted_lon_deg;
  std::optional<double> predicted_alt_ft;
  /// MS: Mode S aircraft identification, 8 ICAO 6-bit characters, spaces trimmed; absent
  /// when blank or holding a code outside the ICAO set.
  std::optional<std::string> mode_s_identification;
  /// CF: cleared flight level, FL.
  std::optional<double> cleared_flight_level;
};

/// The filters that raised an STCA alert: the Conflict Properties Class of I004/120 CC
/// under table TID = 1 of message type 7 (STCA).
struct Cat004StcaFilters {
  bool linear_prediction = false;  ///< LPF, CPC bit 3 (CC bit 4)
  bool current_proximity = false;  ///< CPF, CPC bit 2 (CC bit 3)
  bool manoeuvre_hazard = false;   ///< MHF, CPC bit 1 (CC bit 2)
};

struct Cat004Record {
  std::optional<Cat004SourceId> source;         ///< I004/010
  std::optional<std::uint8_t> message_type;     ///< I004/000
  std::vector<Cat004SourceId> sdps;             ///< I004/015
  std::optional<double> time_of_day_s;          ///< I004/020, [0, 131072)
  std::optional<std::uint16_t> alert_id;        ///< I004/040
  std::optional<std::uint8_t> alert_status;     ///< I004/045 STAT, 0–7
  std::vector<std::uint8_t> function_status;    ///< I004/060 octets as sent (FX included)
  std::optional<std::uint16_t> track_number_1;  ///< I004/030
  std::optional<std::uint16_t> track_number_2;  ///< I004/035
  std::optional<Cat004Aircraft> aircraft_1;     ///< I004/170
  std::optional<Cat004Aircraft> aircraft_2;     ///< I004/171
  // I004/070
  std::optional<double> time_to_conflict_s;
  std::optional<double> time_to_closest_approach_s;
  std::optional<double> current_horizontal_separation_m;
  std::optional<double> minimum_horizontal_separation_m;
  std::optional<double> current_vertical_separation_ft;
  std::optional<double> minimum_vertical_separation_ft;
  // I004/120 (present when has_conflict_characteristics)
  bool has_conflict_characteristics = false;
  std::vector<std::uint8_t> conflict_nature;          ///< CN octets as sent (FX included)
  std::optional<std::uint8_t> conflict_classification;  ///< CC octet: TID(4) CPC(3) CS(1)
  /// CC of an STCA message (type 7) with TID 1: its filter bits.
  std::optional<Cat004StcaFilters> stca_filters;
  /// CC of an APW message (type 5) with TID 1: the Conflict Properties Class, the APW
  /// severity: 0 low, 1 medium, 2 high (3–7 undefined by edition 1.12, kept as sent).
  std::optional<std::uint8_t> apw_severity;
  std::optional<double> conflict_probability_pct;
  std::optional<double> conflict_duration_s;
  // I004/074, 075, 076
  std::optional<double> longitudinal_deviation_m;
  std::optional<double> transversal_deviation_m;
  std::optional<double> vertical_deviation_ft;
  /// I004/100 AN: area name, 8 ICAO 6-bit characters, spaces trimmed; absent when blank
  /// or holding a code outside the ICAO set.
  std::optional<std::string> area_name;
};

class Cat004Reader {
 public:
  using RecordSink = std::function<void(const Cat004Record&)>;

  /// Reads one datagram holding one or more data blocks and calls `sink` for each record
  /// of each CAT004 block. Refusals are counted in rejections():
  ///  "cat004_bad_block_length": a block length below 3 or past the datagram's end
  ///    (the rest of the datagram is dropped);
  ///  "cat004_other_category": a block of another category (skipped);
  ///  "cat004_malformed_record": an FSPEC announcing nothing, the spare FRN or more than
  ///    the UAP, an item running past its block, an explicit item of length 0 (the rest
  ///    of the block is dropped; the message names the walker's reason and the FRN).
  void read(std::span<const std::byte> datagram, const RecordSink& sink);

  Rejections& rejections() { return rejections_; }
  const Rejections& rejections() const { return rejections_; }

 private:
  Rejections rejections_;
};

}  // namespace kew::protocol
