// readsb's traces (trace_full_<hex>.json, trace_recent_<hex>.json); the format is
// described in readsb_trace.hpp.
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "kew/protocol/readsb_trace.hpp"
#include "readsb_members.hpp"
#include "snapshot_decoder.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

// The positions of a trace row's fields (readsb_trace.hpp).
enum Field : std::size_t {
  kOffset = 0,
  kLatitude = 1,
  kLongitude = 2,
  kAltitude = 3,
  kGroundSpeed = 4,
  kTrack = 5,
  kFlags = 6,
  kVerticalRate = 7,
  kDetails = 8,
  kSourceType = 9,
  kGeometricAltitude = 10,
  kGeometricRate = 11,
  kFields = 12,  // the rest (air speed, roll, what later versions add) is not read
};
constexpr std::size_t kRequiredFields = kAltitude + 1;

constexpr unsigned kFlagVerticalRateGeometric = 4;
constexpr unsigned kFlagAltitudeGeometric = 8;
// Larger flags are no bitfield readsb writes.
constexpr double kMaxFlags = 1 << 16;

using Row = std::array<simdjson::dom::element, kFields>;

/// The number at `field` of a row of `size` fields (nullopt when null or missing).
LineResult read_field(const Row& row, std::size_t size, std::size_t field, std::string_view name,
                      std::optional<double>& out) {
  out.reset();
  return field < size ? text::read_number(row[field], name, out) : std::nullopt;
}

class ReadsbTraceDecoder final : public text::SnapshotDecoder {
 public:
  explicit ReadsbTraceDecoder(const AircraftJsonOptions& options)
      : SnapshotDecoder("readsb trace", options.max_snapshot_bytes, {.same_position_s = kReadsbTraceSamePosition_s}) {}

  std::string_view format_name() const override { return "readsb-trace"; }

 private:
  std::optional<double> decode_snapshot(std::string_view text, const std::string& where) override {
    std::optional<std::string_view> icao;
    std::optional<double> timestamp;
    std::optional<simdjson::dom::element> trace;
    LineResult bad = json().parse(text, [&](std::string_view key, simdjson::dom::element value) -> LineResult {
      if (key == "icao") return text::read_string(value, key, icao);
      if (key == "timestamp") return text::read_number(value, key, timestamp);
      if (key == "trace") trace = value;
      return std::nullopt;
    });
    if (!bad && !icao) bad = text::problem("missing_field", "no \"icao\"");
    if (!bad && !timestamp) bad = text::problem("missing_field", "no \"timestamp\"");
    // What the trace's objects said last (strings valid until the next parse).
    flight_.reset();
    squawk_.reset();
    if (!bad)
      bad = decode_entries(trace, "\"trace\"", fmt::format("{} ({})", where, *icao), "row",
                           [&](simdjson::dom::element row) { return decode_row(row, *icao, *timestamp); });
    if (bad) {
      refuse(where, *bad);
      return std::nullopt;
    }
    return *timestamp;
  }

  LineResult decode_row(simdjson::dom::element entry, std::string_view icao, double timestamp) {
    Row row;
    std::size_t size = 0;
    if (!text::array_elements(entry, row, size)) return text::problem("wrong_type", "a row is not an array");
    if (size < kRequiredFields)
      return text::problem("missing_field", fmt::format("{} fields, fewer than {}", size, kRequiredFields));
    double offset = 0;
    if (LineResult bad = text::read_required_number(row[kOffset], "time offset", offset)) return bad;
    std::optional<double> flags_field;
    if (LineResult bad = read_field(row, size, kFlags, "flags", flags_field)) return bad;
    const double flags_number = flags_field.value_or(0.0);
    if (!(flags_number >= 0.0 && flags_number < kMaxFlags) || flags_number != std::floor(flags_number))
      return text::problem("bad_number", fmt::format("flags {} are no bitfield", flags_number));
    const auto flags = static_cast<unsigned>(flags_number);

    text::ReadsbMembers m;
    m.hex = icao;
    if (LineResult bad = text::read_number(row[kLatitude], "latitude", m.lat)) return bad;
    if (LineResult bad = text::read_number(row[kLongitude], "longitude", m.lon)) return bad;
    if (!m.lat || !m.lon) return text::problem("no_position", "latitude or longitude is null");
    // "ground" is never geometric; a number is, with flag 8.
    std::optional<double> altitude;
    if (LineResult bad = text::read_readsb_altitude(row[kAltitude], "altitude", altitude, m.alt_baro_ground)) return bad;
    ((flags & kFlagAltitudeGeometric) ? m.alt_geom : m.alt_baro) = altitude;
    if (LineResult bad = read_field(row, size, kGroundSpeed, "ground speed", m.gs)) return bad;
    if (LineResult bad = read_field(row, size, kTrack, "track", m.track)) return bad;
    std::optional<double> rate;
    if (LineResult bad = read_field(row, size, kVerticalRate, "vertical rate", rate)) return bad;
    ((flags & kFlagVerticalRateGeometric) ? m.geom_rate : m.baro_rate) = rate;
    if (LineResult bad = read_later_fields(row, size, m)) return bad;
    m.flight = flight_;
    m.squawk = squawk_;
    TrackReport report;
    if (LineResult bad = text::fill_readsb_report(m, timestamp + offset, "readsb-trace", report)) return bad;
    return offer(report);
  }

  /// The row's object of aircraft.json members (8), its source type (9), the geometric
  /// altitude (10) and rate (11) where 3 and 7 left them absent.
  LineResult read_later_fields(const Row& row, std::size_t size, text::ReadsbMembers& m) {
    text::ReadsbMembers details;
    if (kDetails < size && !row[kDetails].is_null()) {
      simdjson::dom::object object;
      if (row[kDetails].get_object().get(object) != simdjson::SUCCESS)
        return text::problem("wrong_type", "the details (field 8) are not an object");
      for (const simdjson::dom::key_value_pair member : object)
        if (LineResult bad = text::read_readsb_member(member.key, member.value, details)) return bad;
      if (details.flight) flight_ = details.flight;
      if (details.squawk) squawk_ = details.squawk;
      m.nav_altitude_mcp = details.nav_altitude_mcp;
      m.nav_altitude_fms = details.nav_altitude_fms;
      m.track_rate = details.track_rate;
    }
    if (kSourceType < size) {
      if (LineResult bad = text::read_string(row[kSourceType], "source type", m.type)) return bad;
    }
    if (!m.type) m.type = details.type;
    std::optional<double> geometric;
    if (LineResult bad = read_field(row, size, kGeometricAltitude, "geometric altitude", geometric)) return bad;
    if (!m.alt_geom) m.alt_geom = geometric ? geometric : details.alt_geom;
    if (LineResult bad = read_field(row, size, kGeometricRate, "geometric rate", geometric)) return bad;
    if (!m.geom_rate) m.geom_rate = geometric ? geometric : details.geom_rate;
    return std::nullopt;
  }

  std::optional<std::string_view> flight_;
  std::optional<std::uint16_t> squawk_;
};

}  // namespace

std::unique_ptr<Decoder> make_readsb_trace_decoder(const AircraftJsonOptions& options) {
  return std::make_unique<ReadsbTraceDecoder>(options);
}

}  // namespace kew::protocol
