// OpenSky historical state-vector CSV; the format is described in opensky.hpp.
#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "kew/protocol/opensky.hpp"
#include "line_decoder.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

/// Splits one CSV line (RFC 4180 quoting, no embedded newlines) into `fields`, reusing
/// their storage. False when a quote is left open.
bool split_csv(std::string_view line, std::vector<std::string>& fields, std::size_t& count) {
  count = 0;
  std::size_t i = 0;
  while (true) {
    if (count == fields.size()) fields.emplace_back();
    std::string& field = fields[count++];
    field.clear();
    if (i < line.size() && line[i] == '"') {
      ++i;
      while (true) {
        if (i >= line.size()) return false;
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field.push_back('"');
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        field.push_back(line[i++]);
      }
      // Text between the closing quote and the comma is kept, as spreadsheets do.
    }
    const auto comma = line.find(',', i);
    field.append(line.substr(i, comma == std::string_view::npos ? std::string_view::npos : comma - i));
    if (comma == std::string_view::npos) return true;
    i = comma + 1;
  }
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](char x, char y) {
    return (x | 0x20) == (y | 0x20);
  });
}

/// "true"/"false"/"1"/"0" in any case; empty → false.
bool parse_flag(std::string_view text, bool& flag) {
  text = text::trim(text);
  if (text.empty() || text == "0" || equals_ignoring_case(text, "false")) {
    flag = false;
    return true;
  }
  if (text == "1" || equals_ignoring_case(text, "true")) {
    flag = true;
    return true;
  }
  return false;
}

/// Column positions found in the header; kAbsent for a column the file does not have.
struct Columns {
  static constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);
  std::size_t time = kAbsent, icao24 = kAbsent, lat = kAbsent, lon = kAbsent,
              velocity = kAbsent, heading = kAbsent, vertrate = kAbsent, callsign = kAbsent,
              onground = kAbsent, squawk = kAbsent, baroaltitude = kAbsent,
              geoaltitude = kAbsent, lastposupdate = kAbsent;
  std::size_t count = 0;

  bool complete() const {
    return time != kAbsent && icao24 != kAbsent && lat != kAbsent && lon != kAbsent &&
           (baroaltitude != kAbsent || geoaltitude != kAbsent);
  }
};

class OpenskyCsvDecoder final : public text::LineDecoder {
 public:
  explicit OpenskyCsvDecoder(const OpenskyCsvOptions& options)
      : LineDecoder(options.max_line_bytes) {}

  std::string_view format_name() const override { return "opensky-csv"; }

 private:
  LineResult decode_line(std::string_view line, const ReportSink& sink) override {
    std::size_t n = 0;
    if (!split_csv(line, fields_, n)) return text::problem("malformed_line", "unclosed quote");
    if (is_header(n)) return read_header(n);
    if (!columns_) return text::problem("no_header", "data before the CSV header line");
    if (n != columns_->count)
      return text::problem("malformed_line",
                           fmt::format("{} fields, the header has {}", n, columns_->count));
    if (LineResult bad = fill_report()) return bad;
    if (LineResult bad = text::check_report(report_)) return bad;
    sink(report_);
    return std::nullopt;
  }

  // A data row holds a hex address in the icao24 column, never the word itself.
  bool is_header(std::size_t n) const {
    return std::any_of(fields_.begin(), fields_.begin() + static_cast<std::ptrdiff_t>(n),
                       [](const std::string& f) { return equals_ignoring_case(text::trim(f), "icao24"); });
  }

  LineResult read_header(std::size_t n) {
    Columns columns;
    columns.count = n;
    const std::pair<std::string_view, std::size_t Columns::*> kNames[] = {
        {"time", &Columns::time},         {"icao24", &Columns::icao24},
        {"lat", &Columns::lat},           {"lon", &Columns::lon},
        {"velocity", &Columns::velocity}, {"heading", &Columns::heading},
        {"vertrate", &Columns::vertrate}, {"callsign", &Columns::callsign},
        {"onground", &Columns::onground}, {"squawk", &Columns::squawk},
        {"baroaltitude", &Columns::baroaltitude}, {"geoaltitude", &Columns::geoaltitude},
        {"lastposupdate", &Columns::lastposupdate}};
    for (std::size_t i = 0; i < n; ++i)
      for (const auto& [name, member] : kNames)
        if (equals_ignoring_case(text::trim(fields_[i]), name)) columns.*member = i;
    if (!columns.complete()) {
      columns_.reset();
      return text::problem("bad_header",
                           "header lacks time, icao24, lat, lon or baroaltitude/geoaltitude");
    }
    columns_ = columns;
    return std::nullopt;
  }

  std::string_view field(std::size_t column) const {
    return column == Columns::kAbsent ? std::string_view{} : text::trim(fields_[column]);
  }

  /// An optional numeric column through `convert`; false when present but not a number.
  /// NaN and infinities are numbers here: check_report() refuses a non-finite time or
  /// altitude, the track table drops a non-finite velocity field (design §4.3).
  bool optional_number(std::size_t column, double (*convert)(double),
                       std::optional<double>& out) const {
    out.reset();
    const std::string_view text = field(column);
    if (text.empty()) return true;
    double value = 0;
    if (!text::parse_double(text, value)) return false;
    out = convert(value);
    return true;
  }

  LineResult fill_report() {
    const Columns& c = *columns_;
    text::clear_report(report_);
    std::uint32_t key = 0;
    if (!text::parse_address(field(c.icao24), report_.id, key))
      return text::problem("bad_address", fmt::format("icao24 \"{}\"", field(c.icao24)));
    report_.address = text::icao_address(key);
    report_.source = "opensky";
    if (field(c.lat).empty() || field(c.lon).empty())
      return text::problem("no_position", "empty lat/lon");
    std::optional<double> time, position_time, baro, geo;
    if (!optional_number(c.time, text::unchanged, time) || !optional_number(c.lastposupdate, text::unchanged, position_time) ||
        !text::parse_finite_double(field(c.lat), report_.lat_deg) ||
        !text::parse_finite_double(field(c.lon), report_.lon_deg) ||
        !optional_number(c.baroaltitude, text::metres_to_feet, baro) ||
        !optional_number(c.geoaltitude, text::metres_to_feet, geo) ||
        !optional_number(c.velocity, text::metres_per_second_to_knots, report_.gs_kt) ||
        !optional_number(c.heading, text::unchanged, report_.trk_deg) ||
        !optional_number(c.vertrate, text::metres_per_second_to_feet_per_minute, report_.vr_fpm))
      return text::problem("bad_number", "a numeric column is not a number");
    if (!time && !position_time) return text::problem("missing_field", "empty time");
    report_.t = position_time ? *position_time : *time;
    if (!baro && !geo) return text::problem("no_altitude", "empty baroaltitude and geoaltitude");
    report_.alt_ft = baro ? *baro : *geo;
    report_.callsign.assign(field(c.callsign));
    if (!parse_flag(field(c.onground), report_.on_ground))
      return text::problem("bad_value", fmt::format("onground \"{}\"", field(c.onground)));
    if (const std::string_view squawk = field(c.squawk); !squawk.empty()) {
      std::uint16_t code = 0;
      if (!text::parse_mode3a(squawk, code))
        return text::problem("bad_mode3a", fmt::format("squawk \"{}\"", squawk));
      report_.mode3a = code;
    }
    return std::nullopt;
  }

  void end_of_stream(const ReportSink& /*sink*/) override { columns_.reset(); }

  std::vector<std::string> fields_;
  std::optional<Columns> columns_;
  TrackReport report_;
};

}  // namespace

std::unique_ptr<Decoder> make_opensky_csv_decoder(const OpenskyCsvOptions& options) {
  return std::make_unique<OpenskyCsvDecoder>(options);
}

}  // namespace kew::protocol
