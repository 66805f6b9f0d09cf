// readsb-style JSON lines (recordings/adsb_actions-readsb); the format is described in
// readsb.hpp.
#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "json_object.hpp"
#include "kew/protocol/readsb.hpp"
#include "line_decoder.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

/// The members of one line (or of its "flightdict") that make a report.
struct ReadsbMembers {
  std::optional<double> now, lat, lon, alt_baro, alt_geom, gs, gscp, track, baro_rate, geom_rate;
  std::optional<double> nav_altitude_mcp, nav_altitude_fms, track_rate;
  std::optional<std::string_view> hex, flight;
  std::optional<std::uint16_t> squawk;
  bool alt_baro_ground = false;

  /// Fills what this (top-level) set lacks from `nested` (the flightdict).
  void complete_from(const ReadsbMembers& nested) {
    if (!alt_geom) alt_geom = nested.alt_geom;
    if (!baro_rate) baro_rate = nested.baro_rate;
    if (!geom_rate) geom_rate = nested.geom_rate;
    if (!squawk) squawk = nested.squawk;
    if (!nav_altitude_mcp) nav_altitude_mcp = nested.nav_altitude_mcp;
    if (!nav_altitude_fms) nav_altitude_fms = nested.nav_altitude_fms;
    if (!track_rate) track_rate = nested.track_rate;
  }
};

class ReadsbDecoder final : public text::LineDecoder {
 public:
  explicit ReadsbDecoder(const ReadsbOptions& options)
      : LineDecoder(options.max_line_bytes), json_(max_message_bytes()) {}

  std::string_view format_name() const override { return "readsb"; }

 private:
  LineResult decode_line(std::string_view line, const ReportSink& sink) override {
    ReadsbMembers top;
    ReadsbMembers nested;
    LineResult result = json_.parse(line, [&](std::string_view key, auto& value) -> LineResult {
      if (key == "flightdict") return read_flightdict(value, nested);
      return read_member(key, value, top);
    });
    if (result) return result;
    top.complete_from(nested);
    if (!top.lat || !top.lon) return text::problem("no_position", "no lat/lon");
    if (!top.now) return text::problem("missing_field", "no \"now\"");
    if (!top.hex) return text::problem("missing_field", "no \"hex\"");
    if (LineResult bad = fill_report(top)) return bad;
    if (LineResult bad = text::check_report(report_)) return bad;
    sink(report_);
    return std::nullopt;
  }

  static LineResult read_member(std::string_view key, simdjson::dom::element value,
                                ReadsbMembers& m) {
    if (key == "now") return text::read_number(value, key, m.now);
    if (key == "lat") return text::read_number(value, key, m.lat);
    if (key == "lon") return text::read_number(value, key, m.lon);
    if (key == "alt_baro") return read_alt_baro(value, m);
    if (key == "alt_geom") return text::read_number(value, key, m.alt_geom);
    if (key == "gs") return text::read_number(value, key, m.gs);
    if (key == "gscp") return text::read_number(value, key, m.gscp);
    if (key == "track") return text::read_number(value, key, m.track);
    if (key == "baro_rate") return text::read_number(value, key, m.baro_rate);
    if (key == "geom_rate") return text::read_number(value, key, m.geom_rate);
    if (key == "nav_altitude_mcp") return text::read_number(value, key, m.nav_altitude_mcp);
    if (key == "nav_altitude_fms") return text::read_number(value, key, m.nav_altitude_fms);
    if (key == "track_rate") return text::read_number(value, key, m.track_rate);
    if (key == "hex") return text::read_string(value, key, m.hex);
    if (key == "flight") return text::read_string(value, key, m.flight);
    if (key == "squawk") return text::read_mode3a(value, key, m.squawk);
    return std::nullopt;
  }

  /// The members a flightdict may supply (ReadsbMembers::complete_from).
  static constexpr std::array<std::string_view, 7> kNestedKeys{
      "alt_geom", "baro_rate", "geom_rate", "squawk", "nav_altitude_mcp", "nav_altitude_fms", "track_rate"};
  static LineResult read_flightdict(simdjson::dom::element value, ReadsbMembers& nested) {
    if (value.is_null()) return std::nullopt;
    simdjson::dom::object object;
    if (value.get_object().get(object) != simdjson::SUCCESS)
      return text::problem("wrong_type", "\"flightdict\" must be an object");
    for (const simdjson::dom::key_value_pair member : object) {
      const std::string_view key = member.key;
      if (std::ranges::find(kNestedKeys, key) != kNestedKeys.end()) {
        if (LineResult r = read_member(key, member.value, nested)) return r;
      }
    }
    return std::nullopt;
  }

  // readsb writes "ground" for targets reporting on-ground; adsb_actions also writes
  // numbers as strings ("0") in this member.
  static LineResult read_alt_baro(simdjson::dom::element value, ReadsbMembers& m) {
    if (!value.is_string()) return text::read_number(value, "alt_baro", m.alt_baro);
    std::optional<std::string_view> word;
    if (LineResult r = text::read_string(value, "alt_baro", word)) return r;
    if (*word == "ground") {
      m.alt_baro_ground = true;
      return std::nullopt;
    }
    double number = 0;
    if (!text::parse_finite_double(*word, number))
      return text::problem("bad_number", "\"alt_baro\" is neither a number nor \"ground\"");
    m.alt_baro = number;
    return std::nullopt;
  }

  LineResult fill_report(const ReadsbMembers& m) {
    text::clear_report(report_);
    std::uint32_t key = 0;
    if (!text::parse_address(*m.hex, report_.id, key))
      return text::problem("bad_address", fmt::format("hex \"{}\" is not 6 hex digits", *m.hex));
    report_.address = text::icao_address(key);  // none for '~' (non-ICAO) addresses
    report_.source = "readsb";
    report_.t = *m.now;
    report_.lat_deg = *m.lat;
    report_.lon_deg = *m.lon;
    if (m.alt_baro_ground) {
      report_.on_ground = true;
      report_.alt_ft = m.alt_geom.value_or(0.0);
    } else if (m.alt_baro || m.alt_geom) {
      report_.alt_ft = m.alt_baro ? *m.alt_baro : *m.alt_geom;
    } else {
      return text::problem("no_altitude", "no alt_baro or alt_geom");
    }
    report_.gs_kt = m.gs ? m.gs : m.gscp;
    report_.trk_deg = m.track;
    report_.vr_fpm = m.baro_rate ? m.baro_rate : m.geom_rate;
    // The MCP/FCU selected altitude when given, else the FMS one (design §5.2). readsb's
    // nav_modes ("vnav"...) would tell which one the aircraft flies to; kew does not
    // guess from them.
    if (m.nav_altitude_mcp) {
      report_.sel_ft = m.nav_altitude_mcp;
    } else if (m.nav_altitude_fms) {
      report_.sel_ft = m.nav_altitude_fms;
      report_.sel_src = SelectedAltitudeSource::Fms;
    }
    report_.tar_dps = m.track_rate;
    report_.mode3a = m.squawk;
    if (m.flight) {
      const std::string_view callsign = text::trim(*m.flight);
      if (callsign != "N/A") report_.callsign.assign(callsign);
    }
    return std::nullopt;
  }

  text::JsonObjectParser json_;
  TrackReport report_;
};

}  // namespace

std::unique_ptr<Decoder> make_readsb_decoder(const ReadsbOptions& options) {
  return std::make_unique<ReadsbDecoder>(options);
}

}  // namespace kew::protocol
