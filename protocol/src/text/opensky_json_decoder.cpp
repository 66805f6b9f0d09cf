// The traffic library's OpenSky state-vector JSON; the format is described in opensky.hpp.
#include <fmt/format.h>

#include "json_object.hpp"
#include "json_object_cutter.hpp"
#include "kew/protocol/opensky.hpp"
#include "opensky_state.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

// Above this a timestamp is taken as milliseconds: 1e11 s is in the year 5138, 1e11 ms
// in 1973, before any state vector.
constexpr double kMillisecondTimestampAbove = 1e11;

/// The members of one element that make a report.
struct StateVector {
  std::optional<double> timestamp;
  text::OpenskyState state;
};

LineResult read_member(std::string_view key, simdjson::dom::element value, StateVector& s) {
  text::OpenskyState& v = s.state;
  if (key == "timestamp") return text::read_number(value, key, s.timestamp);
  if (key == "latitude") return text::read_number(value, key, v.latitude);
  if (key == "longitude") return text::read_number(value, key, v.longitude);
  if (key == "altitude") return text::read_number(value, key, v.altitude);
  if (key == "geoaltitude") return text::read_number(value, key, v.geoaltitude);
  if (key == "groundspeed") return text::read_number(value, key, v.groundspeed);
  if (key == "track") return text::read_number(value, key, v.track);
  if (key == "vertical_rate") return text::read_number(value, key, v.vertical_rate);
  if (key == "icao24") return text::read_string(value, key, v.icao24);
  if (key == "callsign") return text::read_string(value, key, v.callsign);
  if (key == "onground") return text::read_bool(value, key, v.onground);
  if (key == "squawk") return text::read_mode3a(value, key, v.squawk);
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
    const double t = *s.timestamp > kMillisecondTimestampAbove ? *s.timestamp / 1000.0 : *s.timestamp;
    if (LineResult bad = text::fill_opensky_report(s.state, t, report_)) return bad;
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
