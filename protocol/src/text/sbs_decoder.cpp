// SBS-1 BaseStation messages merged per address; the format is described in sbs.hpp.
#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <unordered_map>

#include "kew/protocol/sbs.hpp"
#include "line_decoder.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

// 0-based field positions of the 22 comma-separated SBS fields.
enum Field : std::size_t {
  kMessageType = 0,
  kTransmissionType = 1,
  kHexIdent = 4,
  kDateGenerated = 6,
  kTimeGenerated = 7,
  kDateLogged = 8,
  kTimeLogged = 9,
  kCallsign = 10,
  kAltitude = 11,
  kGroundSpeed = 12,
  kTrack = 13,
  kLatitude = 14,
  kLongitude = 15,
  kVerticalRate = 16,
  kSquawk = 17,
  kIsOnGround = 21,
  kFieldCount = 22,
};

/// What one address has said lately, merged into its MSG,3 positions.
struct AircraftState {
  std::string callsign;
  std::optional<double> gs_kt, trk_deg, vr_fpm;
  double velocity_t = 0.0;
  bool has_velocity = false;
  std::optional<std::uint16_t> mode3a;
  double last_seen_t = 0.0;
};

/// Splits at commas into at most kFieldCount fields (extra fields are ignored).
std::size_t split_fields(std::string_view line, std::array<std::string_view, kFieldCount>& fields) {
  std::size_t count = 0;
  while (count < kFieldCount) {
    const auto comma = line.find(',');
    fields[count++] = line.substr(0, comma);
    if (comma == std::string_view::npos) break;
    line.remove_prefix(comma + 1);
  }
  return count;
}

bool parse_unsigned(std::string_view text, unsigned& out) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

/// "2022/01/08" (or with '-') and "22:42:15.605" → seconds since 1970 as if UTC.
bool parse_sbs_time(std::string_view date, std::string_view time, double& seconds) {
  date = text::trim(date);
  time = text::trim(time);
  if (date.size() != 10 || (date[4] != '/' && date[4] != '-') || date[7] != date[4]) return false;
  unsigned year = 0, month = 0, day = 0;
  if (!parse_unsigned(date.substr(0, 4), year) || !parse_unsigned(date.substr(5, 2), month) ||
      !parse_unsigned(date.substr(8, 2), day))
    return false;
  if (month < 1 || month > 12 || day < 1 || day > 31) return false;
  if (time.size() < 8 || time[2] != ':' || time[5] != ':') return false;
  unsigned hours = 0, minutes = 0;
  double secs = 0;
  if (!parse_unsigned(time.substr(0, 2), hours) || !parse_unsigned(time.substr(3, 2), minutes) ||
      !text::parse_finite_double(time.substr(6), secs))
    return false;
  if (hours > 23 || minutes > 59 || secs < 0.0 || secs >= 61.0) return false;
  const std::int64_t days = text::days_from_civil(year, month, day);
  seconds = static_cast<double>(days * 86400 + hours * 3600 + minutes * 60) + secs;
  return true;
}

/// An optional numeric field: empty → nullopt; false when present but not a number. NaN
/// and infinities are numbers here: the track table drops such a field (design §4.3).
bool parse_optional(std::string_view field, std::optional<double>& out) {
  out.reset();
  if (text::trim(field).empty()) return true;
  double value = 0;
  if (!text::parse_double(field, value)) return false;
  out = value;
  return true;
}

bool is_other_transmission_type(std::string_view kind) {
  return kind == "SEL" || kind == "ID" || kind == "AIR" || kind == "STA" || kind == "CLK";
}

class SbsDecoder final : public text::LineDecoder {
 public:
  explicit SbsDecoder(const SbsOptions& options)
      : LineDecoder(options.max_line_bytes), options_(options) {}

  std::string_view format_name() const override { return "sbs"; }

 private:
  LineResult decode_line(std::string_view line, const ReportSink& sink) override {
    std::array<std::string_view, kFieldCount> f{};
    const std::size_t n = split_fields(line, f);
    if (f[kMessageType] != "MSG") {
      if (is_other_transmission_type(f[kMessageType]))
        return text::problem("ignored_message_type", std::string(f[kMessageType]));
      return text::problem("malformed_line", "not an SBS message");
    }
    if (n < 2 || f[kTransmissionType].size() != 1) return text::problem("malformed_line", "no MSG type");
    const char type = f[kTransmissionType][0];
    if (type == '2' || type == '5' || type == '7' || type == '8')
      return text::problem("ignored_message_type", fmt::format("MSG,{}", type));
    if (type != '1' && type != '3' && type != '4' && type != '6')
      return text::problem("malformed_line", fmt::format("unknown MSG type {}", f[1]));
    if (n <= kTimeLogged) return text::problem("malformed_line", fmt::format("only {} fields", n));

    std::uint32_t key = 0;
    if (!text::parse_address(f[kHexIdent], address_id_, key))
      return text::problem("bad_address", fmt::format("\"{}\" is not 6 hex digits", f[kHexIdent]));
    double t = 0;
    const bool generated = !text::trim(f[kDateGenerated]).empty();
    if (!parse_sbs_time(f[generated ? kDateGenerated : kDateLogged],
                        f[generated ? kTimeGenerated : kTimeLogged], t))
      return text::problem("bad_time", "bad date or time field");
    t -= options_.utc_offset_s;
    AircraftState* state = find_or_add(key, t);

    switch (type) {
      case '1':
        if (state != nullptr && n > kCallsign) state->callsign.assign(text::trim(f[kCallsign]));
        return std::nullopt;
      case '4':
        return read_velocity(f, n, t, state);
      case '6':
        return read_squawk(f, n, state);
      default:
        return emit_position(f, n, t, key, state, sink);
    }
  }

  LineResult read_velocity(const std::array<std::string_view, kFieldCount>& f, std::size_t n,
                           double t, AircraftState* state) {
    std::optional<double> gs, track, vertical_rate;
    if (!parse_optional(n > kGroundSpeed ? f[kGroundSpeed] : "", gs) ||
        !parse_optional(n > kTrack ? f[kTrack] : "", track) ||
        !parse_optional(n > kVerticalRate ? f[kVerticalRate] : "", vertical_rate))
      return text::problem("bad_number", "bad ground speed, track or vertical rate");
    if (state != nullptr) {
      state->gs_kt = gs;
      state->trk_deg = track;
      state->vr_fpm = vertical_rate;
      state->velocity_t = t;
      state->has_velocity = true;
    }
    return std::nullopt;
  }

  static LineResult read_squawk(const std::array<std::string_view, kFieldCount>& f, std::size_t n,
                                AircraftState* state) {
    if (n <= kSquawk || text::trim(f[kSquawk]).empty()) return std::nullopt;
    std::uint16_t code = 0;
    if (!text::parse_mode3a(f[kSquawk], code))
      return text::problem("bad_mode3a", fmt::format("squawk \"{}\"", f[kSquawk]));
    if (state != nullptr) state->mode3a = code;
    return std::nullopt;
  }

  LineResult emit_position(const std::array<std::string_view, kFieldCount>& f, std::size_t n,
                           double t, std::uint32_t key, const AircraftState* state,
                           const ReportSink& sink) {
    if (n <= kLongitude || text::trim(f[kLatitude]).empty() || text::trim(f[kLongitude]).empty())
      return text::problem("no_position", "MSG,3 without latitude/longitude");
    if (text::trim(f[kAltitude]).empty()) return text::problem("no_altitude", "MSG,3 without altitude");
    text::clear_report(report_);
    if (!text::parse_finite_double(f[kLatitude], report_.lat_deg) ||
        !text::parse_finite_double(f[kLongitude], report_.lon_deg) ||
        !text::parse_finite_double(f[kAltitude], report_.alt_ft))
      return text::problem("bad_number", "bad latitude, longitude or altitude");
    report_.t = t;
    report_.id = address_id_;
    report_.address = text::icao_address(key);
    report_.source = "sbs";
    if (n > kIsOnGround) {
      const std::string_view on_ground = text::trim(f[kIsOnGround]);
      report_.on_ground = on_ground == "-1" || on_ground == "1";
    }
    if (state != nullptr) {
      report_.callsign = state->callsign;
      report_.mode3a = state->mode3a;
      if (state->has_velocity && std::abs(t - state->velocity_t) <= options_.velocity_max_age_s) {
        report_.gs_kt = state->gs_kt;
        report_.trk_deg = state->trk_deg;
        report_.vr_fpm = state->vr_fpm;
      }
    }
    if (LineResult bad = text::check_report(report_)) return bad;
    sink(report_);
    return std::nullopt;
  }

  /// The state of `key`, created when new; nullptr when the table is full of live
  /// addresses (counted).
  AircraftState* find_or_add(std::uint32_t key, double t) {
    auto it = aircraft_.find(key);
    if (it == aircraft_.end()) {
      if (aircraft_.size() >= options_.max_addresses) forget_stale(t);
      if (aircraft_.size() >= options_.max_addresses) {
        rejections().reject("address_table_full",
                            fmt::format("sbs: {} addresses tracked, {} not merged",
                                        aircraft_.size(), address_id_));
        return nullptr;
      }
      it = aircraft_.emplace(key, AircraftState{}).first;
    }
    it->second.last_seen_t = t;
    return &it->second;
  }

  void forget_stale(double t) {
    std::erase_if(aircraft_, [&](const auto& entry) {
      return t - entry.second.last_seen_t > options_.address_stale_after_s;
    });
  }

  void end_of_stream(const ReportSink& /*sink*/) override { aircraft_.clear(); }

  SbsOptions options_;
  std::unordered_map<std::uint32_t, AircraftState> aircraft_;
  std::string address_id_;  // canonical id of the current line's address
  TrackReport report_;
};

}  // namespace

std::unique_ptr<Decoder> make_sbs_decoder(const SbsOptions& options) {
  return std::make_unique<SbsDecoder>(options);
}

}  // namespace kew::protocol
