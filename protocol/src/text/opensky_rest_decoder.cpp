// The OpenSky REST API's state vectors; the format is described in opensky_rest.hpp.
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "kew/protocol/opensky_rest.hpp"
#include "opensky_state.hpp"
#include "snapshot_decoder.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

// The positions of a state vector's fields (opensky_rest.hpp).
enum Field : std::size_t {
  kIcao24 = 0,
  kCallsign = 1,
  kTimePosition = 3,
  kLongitude = 5,
  kLatitude = 6,
  kBaroAltitude = 7,
  kOnGround = 8,
  kVelocity = 9,
  kTrueTrack = 10,
  kVerticalRate = 11,
  kGeoAltitude = 13,
  kSquawk = 14,
  kSpi = 15,
  kPositionSource = 16,
  kFirstLayoutPositionSource = 17,  // alert at 15, spi at 16
  kFields = 18,
};
// Fields 0 to on_ground must be there (null or not); the rest may be missing.
constexpr std::size_t kRequiredFields = kOnGround + 1;

constexpr std::array<std::string_view, 4> kPositionSources{"adsb", "asterix", "mlat", "flarm"};

/// The number at `field` of `v` (nullopt when null or missing) through `convert`.
LineResult read_field(const std::array<simdjson::dom::element, kFields>& v, std::size_t size, std::size_t field,
                      std::string_view name, double (*convert)(double), std::optional<double>& out) {
  out.reset();
  if (field >= size) return std::nullopt;
  if (LineResult bad = text::read_number(v[field], name, out)) return bad;
  if (out) out = convert(*out);
  return std::nullopt;
}

class OpenskyRestDecoder final : public text::SnapshotDecoder {
 public:
  explicit OpenskyRestDecoder(const AircraftJsonOptions& options)
      : SnapshotDecoder("opensky-rest response", options.max_snapshot_bytes,
                        {.same_position_s = 0.0, .forget_after_s = options.max_position_age_s}),
        max_position_age_s_(options.max_position_age_s) {}

  std::string_view format_name() const override { return "opensky-rest"; }

 private:
  std::optional<double> decode_snapshot(std::string_view text, const std::string& where) override {
    std::optional<double> time;
    std::optional<simdjson::dom::element> states;
    LineResult bad = json().parse(text, [&](std::string_view key, simdjson::dom::element value) -> LineResult {
      if (key == "time") return text::read_number(value, key, time);
      if (key == "states") states = value;
      return std::nullopt;
    });
    if (!bad && !time) bad = text::problem("missing_field", "no \"time\"");
    if (!bad && states && states->is_null()) return *time;  // no aircraft
    if (!bad)
      bad = decode_entries(states, "\"states\"", where, "state",
                           [&](simdjson::dom::element entry) { return decode_state(entry, *time); });
    if (bad) {
      refuse(where, *bad);
      return std::nullopt;
    }
    return *time;
  }

  LineResult decode_state(simdjson::dom::element entry, double time) {
    std::array<simdjson::dom::element, kFields> v;
    std::size_t size = 0;
    if (!text::array_elements(entry, v, size)) return text::problem("wrong_type", "a state vector is not an array");
    if (size < kRequiredFields)
      return text::problem("missing_field", fmt::format("{} fields, fewer than {}", size, kRequiredFields));
    text::OpenskyState s;
    std::optional<double> time_position;
    if (LineResult bad = text::read_string(v[kIcao24], "icao24", s.icao24)) return bad;
    if (LineResult bad = text::read_string(v[kCallsign], "callsign", s.callsign)) return bad;
    if (LineResult bad = text::read_number(v[kTimePosition], "time_position", time_position)) return bad;
    if (LineResult bad = text::read_number(v[kLongitude], "longitude", s.longitude)) return bad;
    if (LineResult bad = text::read_number(v[kLatitude], "latitude", s.latitude)) return bad;
    if (!s.icao24) return text::problem("missing_field", "no icao24");
    if (!time_position || !s.latitude || !s.longitude) return std::nullopt;  // no position: nothing to report
    const double age = time - *time_position;
    if (!(age >= 0.0) || age > max_position_age_s_) return std::nullopt;
    if (LineResult bad = text::read_bool(v[kOnGround], "on_ground", s.onground)) return bad;
    if (LineResult bad = read_field(v, size, kBaroAltitude, "baro_altitude", text::metres_to_feet, s.altitude)) return bad;
    if (LineResult bad = read_field(v, size, kGeoAltitude, "geo_altitude", text::metres_to_feet, s.geoaltitude)) return bad;
    if (LineResult bad = read_field(v, size, kVelocity, "velocity", text::metres_per_second_to_knots, s.groundspeed)) return bad;
    if (LineResult bad = read_field(v, size, kTrueTrack, "true_track", text::unchanged, s.track)) return bad;
    if (LineResult bad = read_field(v, size, kVerticalRate, "vertical_rate", text::metres_per_second_to_feet_per_minute,
                                    s.vertical_rate))
      return bad;
    if (kSquawk < size) {
      if (LineResult bad = text::read_mode3a(v[kSquawk], "squawk", s.squawk)) return bad;
    }
    // The ground, where surface positions carry no altitude: 0 ft, as aircraft-json's.
    if (s.onground.value_or(false) && !s.altitude && !s.geoaltitude) s.altitude = 0.0;
    TrackReport report;
    if (LineResult bad = text::fill_opensky_report(s, *time_position, report)) return bad;
    if (LineResult bad = read_position_source(v, size, report.position_source)) return bad;
    return offer(report);
  }

  /// position_source, at 16 (or at 17 in the first layout, where 16 is spi, a boolean).
  static LineResult read_position_source(const std::array<simdjson::dom::element, kFields>& v, std::size_t size,
                                         std::string& out) {
    const bool first_layout = kPositionSource < size && v[kPositionSource].is_bool();
    std::optional<double> source;
    const std::size_t field = first_layout ? kFirstLayoutPositionSource : kPositionSource;
    if (LineResult bad = read_field(v, size, field, "position_source", text::unchanged, source)) return bad;
    if (!source) return std::nullopt;
    const double number = *source;
    if (number >= 0 && number < static_cast<double>(kPositionSources.size()) && number == std::floor(number)) {
      out.assign(kPositionSources[static_cast<std::size_t>(number)]);
    } else {
      out = fmt::format("{}", number);
    }
    return std::nullopt;
  }

  double max_position_age_s_;
};

}  // namespace

std::unique_ptr<Decoder> make_opensky_rest_decoder(const AircraftJsonOptions& options) {
  return std::make_unique<OpenskyRestDecoder>(options);
}

}  // namespace kew::protocol
