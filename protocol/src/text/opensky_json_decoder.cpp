// The traffic library's OpenSky state-vector JSON; the format is described in opensky.hpp.
#include <fmt/format.h>

#include "json_object.hpp"
#include "json_object_cutter.hpp"
#include "kew/protocol/opensky.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

// Above this a timestamp is taken as milliseconds: 1e11 s is in the year 5138, 1e11 ms
// in 1973, before any state vector.
constexpr double kMillisecondTimestampAbove = 1e11;

/// The members of one element that make a report.
struct StateVector {
  std::optional<double> timestamp, latitude, longitude, altitude, geoaltitude, groundspeed,
      track, vertical_rate;
  std::optional<std::string_view> icao24, callsign;
  std::optional<bool> onground;
  std::optional<std::uint16_t> squawk;
};

LineResult read_member(std::string_view key, simdjson::dom::element value, StateVector& s) {
  if (key == "timestamp") return text::read_number(value, key, s.timestamp);
  if (key == "latitude") return text::read_number(value, key, s.latitude);
  if (key == "longitude") return text::read_number(value, key, s.longitude);
  if (key == "altitude") return text::read_number(value, key, s.altitude);
  if (key == "geoaltitude") return text::read_number(value, key, s.geoaltitude);
  if (key == "groundspeed") return text::read_number(value, key, s.groundspeed);
  if (key == "track") return text::read_number(value, key, s.track);
  if (key == "vertical_rate") return text::read_number(value, key, s.vertical_rate);
  if (key == "icao24") return text::read_string(value, key, s.icao24);
  if (key == "callsign") return text::read_string(value, key, s.callsign);
  if (key == "onground") return text::read_bool(value, key, s.onground);
  if (key == "squawk") return text::read_mode3a(value, key, s.squawk);
  return std::nullopt;
}

class OpenskyJsonDecoder final : public Decoder {
 public:
  explicit OpenskyJsonDecoder(const OpenskyJsonOptions& options)
      : max_object_bytes_(std::max<std::size_t>(options.max_object_bytes, 16)),
        cutter_("opensky-json element", max_object_bytes_),
        json_(max_object_bytes_) {}

  std::string_view format_name() const override { return "opensky-json"; }
  std::size_t max_message_bytes() const override { return max_object_bytes_; }

  void feed(std::span<const std::byte> bytes, const ReportSink& sink) override {
    cutter_.feed(
        bytes,
        [&](std::string_view element) {
          if (LineResult bad = decode_object(element, sink))
            rejections().reject(bad->reason, fmt::format("opensky-json element {}: {}: {}", cutter_.object_number(),
                                                         bad->reason, bad->detail));
        },
        [&](std::string_view reason, std::string message) { rejections().reject(reason, message); });
  }

  void finish(const ReportSink& /*sink*/) override {
    const std::uint64_t element = cutter_.object_number();
    if (cutter_.finish())
      rejections().reject("truncated", fmt::format("opensky-json element {}: cut by the end of the stream", element));
  }

 private:
  LineResult decode_object(std::string_view element, const ReportSink& sink) {
    StateVector s;
    LineResult result = json_.parse(element, [&](std::string_view key, auto value) {
      return read_member(key, value, s);
    });
    if (result) return result;
    if (!s.timestamp) return text::problem("missing_field", "no \"timestamp\"");
    if (!s.icao24) return text::problem("missing_field", "no \"icao24\"");
    if (!s.latitude || !s.longitude) return text::problem("no_position", "no latitude/longitude");
    if (!s.altitude && !s.geoaltitude) return text::problem("no_altitude", "no altitude");
    text::clear_report(report_);
    std::uint32_t key = 0;
    if (!text::parse_address(*s.icao24, report_.id, key))
      return text::problem("bad_address", fmt::format("icao24 \"{}\"", *s.icao24));
    report_.address = text::icao_address(key);
    report_.source = "opensky";
    report_.t = *s.timestamp > kMillisecondTimestampAbove ? *s.timestamp / 1000.0 : *s.timestamp;
    report_.lat_deg = *s.latitude;
    report_.lon_deg = *s.longitude;
    report_.alt_ft = s.altitude ? *s.altitude : *s.geoaltitude;
    report_.gs_kt = s.groundspeed;
    report_.trk_deg = s.track;
    report_.vr_fpm = s.vertical_rate;
    report_.callsign.assign(text::trim(s.callsign.value_or(std::string_view{})));
    report_.on_ground = s.onground.value_or(false);
    report_.mode3a = s.squawk;
    if (LineResult bad = text::check_report(report_)) return bad;
    sink(report_);
    return std::nullopt;
  }

  std::size_t max_object_bytes_;
  text::JsonObjectCutter cutter_;
  text::JsonObjectParser json_;
  TrackReport report_;
};

}  // namespace

std::unique_ptr<Decoder> make_opensky_json_decoder(const OpenskyJsonOptions& options) {
  return std::make_unique<OpenskyJsonDecoder>(options);
}

}  // namespace kew::protocol
