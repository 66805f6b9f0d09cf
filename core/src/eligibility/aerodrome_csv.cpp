#include "kew/eligibility/aerodrome_csv.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

namespace kew::eligibility {

AerodromeCsvError::AerodromeCsvError(std::string_view origin, std::size_t line, std::string_view message)
    : std::runtime_error(fmt::format("{}:{}: {}", origin, line, message)), line_(line) {}

namespace {

// One line's fields (RFC 4180, without line breaks inside quotes); nullopt with `error`
// when a quote is not closed or text follows a closing quote.
std::optional<std::vector<std::string>> split_fields(std::string_view line, std::string& error) {
  std::vector<std::string> fields(1);
  std::size_t i = 0;
  while (i <= line.size()) {
    std::string& field = fields.back();
    // Spaces around an unquoted field, and before and after a quoted one, are not data.
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i < line.size() && line[i] == '"') {
      ++i;
      for (;;) {
        if (i >= line.size()) {
          error = "a quoted field is not closed on its line";
          return std::nullopt;
        }
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        field += line[i++];
      }
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i < line.size() && line[i] != ',') {
        error = "text after a quoted field";
        return std::nullopt;
      }
    } else {
      const std::size_t end = std::min(line.find(',', i), line.size());
      field.assign(line.substr(i, end - i));
      while (!field.empty() && (field.back() == ' ' || field.back() == '\t')) field.pop_back();
      i = end;
    }
    if (i >= line.size()) break;
    ++i;  // the comma
    fields.emplace_back();
  }
  return fields;
}

// The whole field as a finite number; nullopt otherwise ("", "1e", "nan", "12 ft").
std::optional<double> number(std::string_view field) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc() || end != field.data() + field.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

enum Column : std::size_t { Ident, Lat, Lon, Elevation, Name, kColumns };
constexpr std::array<std::string_view, kColumns> kColumnNames = {"ident", "lat_deg", "lon_deg", "elevation_ft", "name"};
constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);

}  // namespace

std::vector<Aerodrome> parse_aerodrome_csv(std::string_view text, std::string_view origin) {
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (text.substr(0, kByteOrderMark.size()) == kByteOrderMark) text.remove_prefix(kByteOrderMark.size());
  std::vector<Aerodrome> rows;
  std::array<std::size_t, kColumns> index;
  index.fill(kAbsent);
  std::size_t header_fields = 0;  // 0: the header is still to come
  std::unordered_map<std::string, std::size_t> line_of;  // ident -> its line
  std::size_t line_number = 0;
  std::string error;
  while (!text.empty()) {
    const std::size_t end = std::min(text.find('\n'), text.size());
    std::string_view line = text.substr(0, end);
    text.remove_prefix(std::min(end + 1, text.size()));
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    const auto fail = [&](std::string_view message) { throw AerodromeCsvError(origin, line_number, message); };
    std::optional<std::vector<std::string>> fields = split_fields(line, error);
    if (!fields) fail(error);
    if (header_fields == 0) {
      for (std::size_t f = 0; f < fields->size(); ++f)
        for (std::size_t c = 0; c < kColumns; ++c)
          if ((*fields)[f] == kColumnNames[c]) {
            if (index[c] != kAbsent) fail(fmt::format("the header names the column {} twice", kColumnNames[c]));
            index[c] = f;
          }
      for (std::size_t c = Ident; c <= Elevation; ++c)
        if (index[c] == kAbsent)
          fail(fmt::format("the header has no column {} (it needs ident, lat_deg, lon_deg and elevation_ft)",
                           kColumnNames[c]));
      header_fields = fields->size();
      continue;
    }
    if (fields->size() != header_fields)
      fail(fmt::format("{} fields where the header has {}", fields->size(), header_fields));
    Aerodrome a;
    a.ident = std::move((*fields)[index[Ident]]);
    const auto figure = [&](Column c) {
      const std::optional<double> value = number((*fields)[index[c]]);
      if (!value) fail(fmt::format("{} = \"{}\" is not a number", kColumnNames[c], (*fields)[index[c]]));
      return *value;
    };
    a.lat_deg = figure(Lat);
    a.lon_deg = figure(Lon);
    a.elevation_ft = figure(Elevation);
    if (index[Name] != kAbsent) a.name = std::move((*fields)[index[Name]]);
    if (const std::string p = problem(a); !p.empty()) fail(a.ident.empty() ? p : fmt::format("{}: {}", a.ident, p));
    if (const auto [it, added] = line_of.emplace(a.ident, line_number); !added)
      fail(fmt::format("{} is already on line {}", a.ident, it->second));
    rows.push_back(std::move(a));
  }
  if (header_fields == 0) throw AerodromeCsvError(origin, std::max<std::size_t>(line_number, 1), "no header row");
  if (rows.empty())
    throw AerodromeCsvError(origin, line_number,
                            "no aerodrome: the lower limit would ignore every aerodrome (to measure it from the "
                            "sea alone, set aerodrome_height_ft = 0)");
  return rows;
}

}  // namespace kew::eligibility
