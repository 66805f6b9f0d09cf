#include "kew/protocol/encoders/cat004.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string_view>
#include <utility>

namespace kew::protocol {
namespace {

constexpr std::byte kCategory{4};
constexpr std::size_t kBlockHeaderBytes = 3;  // CAT, LEN (16 bits, header included)
constexpr double kSecondsPerDay = 86400.0;

// Field reference numbers of the CAT004 1.12 UAP (FRN 19 is spare).
enum Frn : unsigned {
  kFrn010 = 1, kFrn000 = 2, kFrn015 = 3, kFrn020 = 4, kFrn040 = 5, kFrn045 = 6,
  kFrn060 = 7, kFrn030 = 8, kFrn170 = 9, kFrn120 = 10, kFrn070 = 11, kFrn100 = 15,
  kFrn035 = 16, kFrn171 = 17,
};

/// The octets of an FSPEC (of a record or of a compound item) announcing the items whose
/// FRN bit (1 << (frn − 1)) is set in `present`: seven items per octet, most significant
/// bit first, FX (bit 1) set on every octet but the last.
template <typename Sink>
void write_fspec(std::uint32_t present, Sink&& sink) {
  unsigned octets = 1;
  while (octets * 7 < 32 && (present >> (octets * 7)) != 0) ++octets;
  for (unsigned k = 0; k < octets; ++k) {
    unsigned octet = 0;
    for (unsigned j = 0; j < 7; ++j) {
      if (present & (1u << (7 * k + j))) octet |= 0x80u >> j;
    }
    if (k + 1 < octets) octet |= 0x01;
    sink(static_cast<std::uint8_t>(octet));
  }
}

/// Big-endian writer into a fixed buffer: a CAT004 record as kew writes it is at most 56
/// bytes, so nothing is allocated while a record is built. Writes past the capacity are
/// dropped rather than overrun it (they cannot happen with the items kew writes).
class Octets {
 public:
  void u8(unsigned v) {
    if (size_ < data_.size()) data_[size_++] = static_cast<std::byte>(v & 0xFF);
  }
  void u16(unsigned v) {
    u8(v >> 8);
    u8(v);
  }
  void u24(std::uint32_t v) {
    u8(v >> 16);
    u16(v & 0xFFFF);
  }
  void fspec(std::uint32_t present) {
    write_fspec(present, [this](std::uint8_t octet) { u8(octet); });
  }
  void append(const Octets& other) {
    for (std::size_t i = 0; i < other.size_; ++i) u8(static_cast<unsigned>(other.data_[i]));
  }
  std::span<const std::byte> bytes() const { return {data_.data(), size_}; }

 private:
  std::array<std::byte, 192> data_{};
  std::size_t size_ = 0;
};

/// Items (or compound subfields) written in FRN order, FSPEC computed at the end.
class FieldList {
 public:
  /// Marks field `frn` present; its octets are to be written to the returned buffer now,
  /// before any later field.
  Octets& field(unsigned frn) {
    present_ |= 1u << (frn - 1);
    return body_;
  }
  bool empty() const { return present_ == 0; }
  /// FSPEC followed by the fields, into `out`.
  void write_to(Octets& out) const {
    out.fspec(present_);
    out.append(body_);
  }

 private:
  std::uint32_t present_ = 0;
  Octets body_;
};

/// round(value / lsb) limited to [0, 2^bits − 1]: CAT004 quantities are unsigned and an
/// out-of-range figure is better sent as the largest value than wrapped.
std::uint32_t saturated(double value, double lsb, unsigned bits) {
  const double largest = static_cast<double>((std::uint32_t{1} << bits) - 1);
  const double steps = std::round(value / lsb);
  return static_cast<std::uint32_t>(std::clamp(steps, 0.0, largest));
}

std::uint32_t time_of_day_128(double t) {
  const std::uint32_t steps = saturated(cat004_time_of_day(t), 1.0 / 128.0, 24);
  // A time a hair before midnight rounds to 24:00:00, which is 00:00:00.
  return steps >= static_cast<std::uint32_t>(kSecondsPerDay * 128.0) ? 0 : steps;
}

/// I004/170 or I004/171 for one aircraft: AI, the callsign in 7 ASCII characters (left
/// adjusted, space filled, longer callsigns cut, non-printable bytes as spaces). Nothing
/// when the callsign is unknown. MS (the Mode S identification, 6-bit ICAO characters)
/// is not sent: it would repeat AI, and Wireshark 4.0 shows it as raw octets.
void write_aircraft(FieldList& record, unsigned frn, const AlertParty& party) {
  if (party.callsign.empty()) return;
  constexpr unsigned kAi = 1;
  constexpr std::size_t kAiChars = 7;
  FieldList subfields;
  Octets& ai = subfields.field(kAi);
  for (std::size_t i = 0; i < kAiChars; ++i) {
    const char c = i < party.callsign.size() ? party.callsign[i] : ' ';
    ai.u8(c >= 0x20 && c < 0x7F ? static_cast<unsigned>(c) : ' ');
  }
  subfields.write_to(record.field(frn));
}

constexpr unsigned kTableOne = 1u << 4;  // TID (bits 8–5) = 1
constexpr unsigned kSeverityHigh = 1u;   // CS (bit 1)

/// CS is HIGH from warning up, whatever the safety net, so a receiver that reads CS only
/// ranks STCA and APW alerts alike.
unsigned conflict_severity(const AlertEvent& event) {
  return event.severity >= Severity::Warning ? kSeverityHigh : 0u;
}

/// The CC octet of I004/120 in an APW message: TID 1, the table whose Conflict Properties
/// Class (bits 4–2) is the APW severity: 0 low, 1 medium, 2 high (the CC case (5, 1) of
/// edition 1.12); kew's three severities map onto them in order.
unsigned apw_classification(const AlertEvent& event) {
  unsigned level = 0;
  switch (event.severity) {
    case Severity::None:
    case Severity::Caution:
      level = 0;
      break;
    case Severity::Warning:
      level = 1;
      break;
    case Severity::Loss:  // inside the volume
      level = 2;
      break;
  }
  return kTableOne | (level << 1) | conflict_severity(event);
}

/// The CC octet of I004/120 in an STCA message: TID 1, the table whose Conflict
/// Properties Class (bits 4–2) holds the filters that raised the alert: LPF (linear
/// prediction, bit 4), CPF (current proximity, bit 3), MHF (manoeuvre hazard, bit 2);
/// then CS.
unsigned stca_classification(const AlertEvent& event) {
  constexpr unsigned kLpf = 1u << 3, kCpf = 1u << 2, kMhf = 1u << 1;
  unsigned filter = kLpf;
  switch (event.hypothesis) {
    case Hypothesis::Linear:
    case Hypothesis::LevelOff:  // a straight-line prediction that stops at a level
      filter = kLpf;
      break;
    case Hypothesis::Proximity:
      filter = kCpf;
      break;
    case Hypothesis::Turn:
      filter = kMhf;
      break;
  }
  return kTableOne | filter | conflict_severity(event);
}

/// I004/120: CC (the filter that found the conflict or the APW severity, and CS) and CD
/// (time since the alert opened, 1/128 s).
void write_conflict_characteristics(FieldList& record, const AlertEvent& event) {
  constexpr unsigned kCc = 2, kCd = 4;
  FieldList subfields;
  subfields.field(kCc).u8(event.kind == AlertKind::Apw ? apw_classification(event)
                                                       : stca_classification(event));
  const double duration = event.t - event.opened_t;
  if (std::isfinite(duration)) subfields.field(kCd).u24(saturated(duration, 1.0 / 128.0, 24));
  subfields.write_to(record.field(kFrn120));
}

/// I004/070: TC, TCA (1/128 s), CHS (0.5 m, 24 bits), MHS (0.5 m, 16 bits), CVS and MVS
/// (25 ft); figures that are not finite are left out, the item too when none is. An APW
/// alert sends TC only (the time to entry into the volume): the other five describe a
/// pair, and their zeros in an APW event would read as aircraft closing to nothing.
void write_timing_and_separation(FieldList& record, const AlertEvent& event) {
  struct Figure {
    double value;
    double lsb;
    unsigned bits;
  };
  const std::array<Figure, 6> figures{{
      {event.t_los_s, 1.0 / 128.0, 24},
      {event.t_cpa_s, 1.0 / 128.0, 24},
      {event.sep_h_m, 0.5, 24},
      {event.cpa_h_m, 0.5, 16},
      {event.sep_v_ft, 25.0, 16},
      {event.cpa_v_ft, 25.0, 16},
  }};
  const std::size_t sent = event.kind == AlertKind::Apw ? 1 : figures.size();
  FieldList subfields;
  for (unsigned i = 0; i < sent; ++i) {
    const Figure& f = figures[i];
    if (!std::isfinite(f.value)) continue;
    Octets& out = subfields.field(i + 1);
    const std::uint32_t steps = saturated(f.value, f.lsb, f.bits);
    if (f.bits == 24) {
      out.u24(steps);
    } else {
      out.u16(steps);
    }
  }
  if (!subfields.empty()) subfields.write_to(record.field(kFrn070));
}

/// The 6-bit code of `c` in the ICAO character set (Annex 10 Vol IV 3.1.2.9: A–Z are 1–26,
/// space 32, 0–9 are 48–57); lower-case letters take their capital's code, and every other
/// character the space's, since the set has nothing else.
unsigned icao_code(char c) {
  if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  if (c >= 'A' && c <= 'Z') return static_cast<unsigned>(c - 'A' + 1);
  if (c >= '0' && c <= '9') return static_cast<unsigned>(c);
  return 32;
}

/// I004/100 with subfield AN only: the volume's name in 8 ICAO 6-bit characters (48 bits),
/// left adjusted and space filled; longer names are cut. A UTF-8 character outside the set
/// is one space: its continuation bytes (0x80–0xBF) are skipped.
void write_area_name(FieldList& record, std::string_view name) {
  constexpr unsigned kAn = 1;
  constexpr std::size_t kAnChars = 8;
  std::uint64_t bits = 0;
  std::size_t chars = 0;
  for (const char c : name) {
    if (chars == kAnChars) break;
    const auto octet = static_cast<unsigned char>(c);
    if (octet >= 0x80 && octet <= 0xBF) continue;
    bits = (bits << 6) | icao_code(c);
    ++chars;
  }
  for (; chars < kAnChars; ++chars) bits = (bits << 6) | icao_code(' ');
  FieldList subfields;
  Octets& an = subfields.field(kAn);
  an.u24(static_cast<std::uint32_t>(bits >> 24));
  an.u24(static_cast<std::uint32_t>(bits & 0xFFFFFF));
  subfields.write_to(record.field(kFrn100));
}

void write_header_items(FieldList& record, const Cat004Options& options,
                        Cat004MessageType type, double t) {
  Octets& source = record.field(kFrn010);
  source.u8(options.sac);
  source.u8(options.sic);
  record.field(kFrn000).u8(static_cast<unsigned>(type));
  if (options.sdps) {
    Octets& sdps = record.field(kFrn015);
    sdps.u8(1);  // repetition factor
    sdps.u8(options.sdps->sac);
    sdps.u8(options.sdps->sic);
  }
  record.field(kFrn020).u24(time_of_day_128(t));
}

/// The record: FSPEC then items.
Octets encoded(const FieldList& record) {
  Octets octets;
  record.write_to(octets);
  return octets;
}

}  // namespace

double cat004_time_of_day(double t) {
  const double tod = std::fmod(t, kSecondsPerDay);
  return tod < 0.0 ? tod + kSecondsPerDay : tod;
}

Cat004Encoder::Cat004Encoder(Cat004Options options) : options_(options) {
  options_.max_datagram_bytes =
      std::clamp<std::size_t>(options_.max_datagram_bytes, kCat004MinDatagramBytes, 65535);
}

bool Cat004Encoder::add_alive(const Cat004Alive& alive) {
  if (!std::isfinite(alive.t)) {
    rejections_.reject("cat004_bad_time", "Alive message with a time that is not finite");
    return false;
  }
  FieldList record;
  write_header_items(record, options_, Cat004MessageType::Alive, alive.t);
  // I004/060: STCA always runs, APW when the sender says so; the second octet carries
  // DG, OF and OL when set.
  constexpr unsigned kApw = 0x08, kStca = 0x02, kDg = 0x08, kOf = 0x04, kOl = 0x02, kFx = 0x01;
  const unsigned flags =
      (alive.degraded ? kDg : 0u) | (alive.overflow ? kOf : 0u) | (alive.overload ? kOl : 0u);
  Octets& status = record.field(kFrn060);
  status.u8(kStca | (alive.apw ? kApw : 0u) | (flags != 0 ? kFx : 0u));
  if (flags != 0) status.u8(flags);
  append_record(encoded(record).bytes());
  return true;
}

bool Cat004Encoder::add_alert(const AlertEvent& event) {
  if (!std::isfinite(event.t)) {
    rejections_.reject("cat004_bad_time", "alert " + event.id + " with a time that is not finite");
    return false;
  }
  const bool end = event.state == AlertState::End;
  const bool apw = event.kind == AlertKind::Apw;
  // End Of Conflict is the one end message of every safety net (edition 1.12 has no
  // APW-specific one); I004/040 tells the receiver which alert ended.
  const Cat004MessageType type = end ? Cat004MessageType::EndOfConflict
                                 : apw ? Cat004MessageType::Apw
                                       : Cat004MessageType::Stca;
  FieldList record;
  write_header_items(record, options_, type, event.t);
  record.field(kFrn040).u16(event.number);
  // STAT (bits 3–1 of I004/045) carries kew's severity, 0 once the conflict has ended.
  const unsigned status = end ? 0u : static_cast<unsigned>(event.severity);
  record.field(kFrn045).u8((status & 0x7) << 1);
  record.field(kFrn030).u16(event.a.track_number);
  if (!end) {
    write_aircraft(record, kFrn170, event.a);
    write_conflict_characteristics(record, event);
    write_timing_and_separation(record, event);
    if (apw) write_area_name(record, event.volume);  // mandatory in APW (type 5)
  }
  // An APW alert has one aircraft: 035 and 171 are "X" (never present) in type 5, and
  // 035 is for the second track of a pair in End Of Conflict.
  if (!apw) {
    record.field(kFrn035).u16(event.b.track_number);
    if (!end) write_aircraft(record, kFrn171, event.b);
  }
  append_record(encoded(record).bytes());
  return true;
}

void Cat004Encoder::append_record(std::span<const std::byte> record) {
  if (datagrams_.empty() || datagrams_.back().size() + record.size() > options_.max_datagram_bytes) {
    std::vector<std::byte>& block = datagrams_.emplace_back();
    block.reserve(options_.max_datagram_bytes);
    block.assign(kBlockHeaderBytes, std::byte{0});
    block[0] = kCategory;
  }
  std::vector<std::byte>& block = datagrams_.back();
  block.insert(block.end(), record.begin(), record.end());
  block[1] = static_cast<std::byte>(block.size() >> 8);
  block[2] = static_cast<std::byte>(block.size() & 0xFF);
}

std::vector<std::vector<std::byte>> Cat004Encoder::take_datagrams() {
  return std::exchange(datagrams_, {});
}

}  // namespace kew::protocol
