// The traffic library's OpenSky state-vector JSON; the format is described in opensky.hpp.
#include <fmt/format.h>

#include "json_object.hpp"
#include "kew/protocol/opensky.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

// Above this a timestamp is taken as milliseconds: 1e11 s is in the year 5138, 1e11 ms
// in 1973, before any state vector.
constexpr double kMillisecondTimestampAbove = 1e11;

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

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

/// Cuts top-level JSON objects out of a byte stream (the elements of an array, or
/// objects one after another) without parsing them: a bracket counter that skips
/// strings. Memory is bounded by the longest element accepted.
class OpenskyJsonDecoder final : public Decoder {
 public:
  explicit OpenskyJsonDecoder(const OpenskyJsonOptions& options)
      : max_object_bytes_(std::max<std::size_t>(options.max_object_bytes, 16)),
        json_(max_object_bytes_) {}

  std::string_view format_name() const override { return "opensky-json"; }
  std::size_t max_message_bytes() const override { return max_object_bytes_; }

  void feed(std::span<const std::byte> bytes, const ReportSink& sink) override {
    const char* const begin = reinterpret_cast<const char*>(bytes.data());
    const char* const end = begin + bytes.size();
    const char* object_begin = mode_ == Mode::InObject ? begin : nullptr;
    for (const char* p = begin; p < end; ++p) {
      switch (mode_) {
        case Mode::Between:
          between_elements(*p, static_cast<std::uint64_t>(p - begin));
          if (mode_ == Mode::InObject) object_begin = p;
          break;
        case Mode::InObject:
          if (inside_object(*p)) {
            complete_object(object_begin, p + 1, sink);
            object_begin = nullptr;
          } else if (object_.size() + static_cast<std::size_t>(p + 1 - object_begin) >
                     max_object_bytes_) {
            rejections().reject("object_too_long",
                                fmt::format("opensky-json element {}: longer than {} bytes, skipped",
                                            element_, max_object_bytes_));
            object_.clear();
            object_begin = nullptr;
            mode_ = Mode::Resync;
            resync_after_close_ = false;
          }
          break;
        case Mode::Resync:
          resync(*p);
          break;
      }
    }
    if (mode_ == Mode::InObject) object_.append(object_begin, end);
    stream_offset_ += bytes.size();
  }

  void finish(const ReportSink& /*sink*/) override {
    if (mode_ == Mode::InObject)
      rejections().reject("truncated", fmt::format("opensky-json element {}: cut by the end of "
                                                   "the stream", element_));
    mode_ = Mode::Between;
    object_.clear();
    element_ = 0;
    stream_offset_ = 0;
    garbage_reported_ = false;
  }

 private:
  enum class Mode { Between, InObject, Resync };

  void between_elements(char c, std::uint64_t offset_in_chunk) {
    if (c == '{') {
      mode_ = Mode::InObject;
      depth_ = 1;
      in_string_ = escaped_ = garbage_reported_ = false;
      ++element_;
    } else if (!is_blank(c) && c != ',' && c != '[' && c != ']' && !garbage_reported_) {
      // One count per run of garbage, not one per byte.
      rejections().reject("bad_json",
                          fmt::format("opensky-json: unexpected byte 0x{:02x} at offset {} "
                                      "after element {}",
                                      static_cast<unsigned char>(c),
                                      stream_offset_ + offset_in_chunk, element_));
      garbage_reported_ = true;
    }
  }

  /// Advances the bracket counter; true when `c` closes the element.
  bool inside_object(char c) {
    if (in_string_) {
      if (escaped_) {
        escaped_ = false;
      } else if (c == '\\') {
        escaped_ = true;
      } else if (c == '"') {
        in_string_ = false;
      }
      return false;
    }
    if (c == '"') {
      in_string_ = true;
    } else if (c == '{' || c == '[') {
      ++depth_;
    } else if (c == '}' || c == ']') {
      if (--depth_ == 0) {
        mode_ = Mode::Between;
        return true;
      }
    }
    return false;
  }

  // After an over-long element: its end is not known (it may be garbage), so skip to
  // what ends a flat element in an array or a JSON-lines file: "}," "}]" or "}\n".
  void resync(char c) {
    if (c == '}') {
      resync_after_close_ = true;
    } else if (resync_after_close_ && (c == ',' || c == ']' || c == '\n')) {
      mode_ = Mode::Between;
    } else if (!is_blank(c)) {
      resync_after_close_ = false;
    }
  }

  void complete_object(const char* begin, const char* end, const ReportSink& sink) {
    std::string_view element(begin, static_cast<std::size_t>(end - begin));
    if (!object_.empty()) {
      object_.append(element);
      element = object_;
    }
    if (LineResult bad = decode_object(element, sink))
      rejections().reject(bad->reason, fmt::format("opensky-json element {}: {}: {}", element_,
                                                   bad->reason, bad->detail));
    object_.clear();
  }

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
  text::JsonObjectParser json_;
  TrackReport report_;

  Mode mode_ = Mode::Between;
  std::size_t depth_ = 0;
  bool in_string_ = false;
  bool escaped_ = false;
  bool garbage_reported_ = false;
  bool resync_after_close_ = false;
  std::string object_;            // the start of an element begun in an earlier chunk
  std::uint64_t element_ = 0;     // 1-based number of the current (or last) element
  std::uint64_t stream_offset_ = 0;  // bytes before the current chunk
};

}  // namespace

std::unique_ptr<Decoder> make_opensky_json_decoder(const OpenskyJsonOptions& options) {
  return std::make_unique<OpenskyJsonDecoder>(options);
}

}  // namespace kew::protocol
