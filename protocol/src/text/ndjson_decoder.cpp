// Canonical NDJSON track records (design §5.1); the format is described in ndjson.hpp.
#include <fmt/format.h>

#include "json_object.hpp"
#include "kew/protocol/ndjson.hpp"
#include "line_decoder.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

class NdjsonDecoder final : public text::LineDecoder {
 public:
  explicit NdjsonDecoder(const NdjsonOptions& options)
      : LineDecoder(options.max_line_bytes), json_(max_message_bytes()) {}

  std::string_view format_name() const override { return "ndjson"; }

 private:
  // Bits of the required members seen on the current line.
  enum Required : unsigned { kT = 1, kId = 2, kLat = 4, kLon = 8, kAlt = 16, kAll = 31 };

  LineResult decode_line(std::string_view line, const ReportSink& sink) override {
    text::clear_report(report_);
    unsigned seen = 0;
    LineResult result = json_.parse(line, [&](std::string_view key, auto& value) {
      return read_member(key, value, seen);
    });
    if (result) return result;
    if (seen != kAll) return missing(seen);
    if (LineResult bad = text::check_report(report_)) return bad;
    sink(report_);
    return std::nullopt;
  }

  LineResult read_member(std::string_view key, simdjson::dom::element value, unsigned& seen) {
    if (key == "t") return required_number(value, key, report_.t, seen, kT);
    if (key == "lat") return required_number(value, key, report_.lat_deg, seen, kLat);
    if (key == "lon") return required_number(value, key, report_.lon_deg, seen, kLon);
    if (key == "alt_ft") return required_number(value, key, report_.alt_ft, seen, kAlt);
    if (key == "gs_kt") return text::read_number(value, key, report_.gs_kt);
    if (key == "trk_deg") return text::read_number(value, key, report_.trk_deg);
    if (key == "vr_fpm") return text::read_number(value, key, report_.vr_fpm);
    if (key == "sel_ft") return text::read_number(value, key, report_.sel_ft);
    if (key == "sel_src") return read_selected_altitude_source(value, key);
    if (key == "tar_dps") return text::read_number(value, key, report_.tar_dps);
    if (key == "sq") return text::read_mode3a(value, key, report_.mode3a);
    if (key == "addr") return text::read_icao_address(value, key, report_.address);
    if (key == "coast") return optional_flag(value, key, report_.coasting);
    if (key == "end") return optional_flag(value, key, report_.track_end);
    if (key == "gnd") return optional_flag(value, key, report_.on_ground);
    if (key == "id") {
      std::optional<std::string_view> id;
      if (LineResult r = text::read_string(value, key, id)) return r;
      if (!id) return text::problem("wrong_type", "\"id\" must be a string, not null");
      report_.id.assign(*id);
      seen |= kId;
      return std::nullopt;
    }
    if (key == "cs") return optional_string(value, key, report_.callsign);
    if (key == "src") return optional_string(value, key, report_.source);
    if (key == "pos_src") return optional_string(value, key, report_.position_source);
    return std::nullopt;
  }

  /// "mcp" or "fms"; absent and null mean "mcp" (meaningful only with sel_ft).
  LineResult read_selected_altitude_source(simdjson::dom::element value, std::string_view key) {
    std::optional<std::string_view> name;
    if (LineResult r = text::read_string(value, key, name)) return r;
    if (!name) {
      report_.sel_src = SelectedAltitudeSource::Mcp;
      return std::nullopt;
    }
    const auto source = kSelectedAltitudeSourceNames.parse(*name);
    if (!source) {
      return text::problem("bad_sel_src", fmt::format("\"sel_src\" \"{}\" is not one of {}", *name,
                                                      kSelectedAltitudeSourceNames.list()));
    }
    report_.sel_src = *source;
    return std::nullopt;
  }

  /// An optional boolean member; absent and null mean false.
  static LineResult optional_flag(simdjson::dom::element value, std::string_view key, bool& out) {
    std::optional<bool> flag;
    if (LineResult r = text::read_bool(value, key, flag)) return r;
    out = flag.value_or(false);
    return std::nullopt;
  }

  static LineResult required_number(simdjson::dom::element value, std::string_view key,
                                    double& out, unsigned& seen, Required bit) {
    if (LineResult r = text::read_required_number(value, key, out)) return r;
    seen |= bit;
    return std::nullopt;
  }

  static LineResult optional_string(simdjson::dom::element value, std::string_view key,
                                    std::string& out) {
    std::optional<std::string_view> text;
    if (LineResult r = text::read_string(value, key, text)) return r;
    out.assign(text.value_or(std::string_view{}));
    return std::nullopt;
  }

  static text::LineProblem missing(unsigned seen) {
    static constexpr std::pair<unsigned, std::string_view> kNames[] = {
        {kT, "t"}, {kId, "id"}, {kLat, "lat"}, {kLon, "lon"}, {kAlt, "alt_ft"}};
    for (const auto& [bit, name] : kNames)
      if ((seen & bit) == 0) return text::problem("missing_field", fmt::format("no \"{}\"", name));
    return text::problem("missing_field", "");
  }

  text::JsonObjectParser json_;
  TrackReport report_;
};

}  // namespace

std::unique_ptr<Decoder> make_ndjson_decoder(const NdjsonOptions& options) {
  return std::make_unique<NdjsonDecoder>(options);
}

}  // namespace kew::protocol
