#pragma once
// The text of an aerodrome table (data/aerodromes.csv; its columns in data/README.md):
// parsed here, without I/O, so that kew_config reads the file and tests hand in text.
//
// The format: CSV (RFC 4180) in UTF-8, one header row naming the columns, one row an
// aerodrome. The columns ident, lat_deg, lon_deg and elevation_ft are required, name is
// optional, in any order; others are ignored. A field may be quoted ("a, b" and "" for a
// double quote), but not across lines. Blank lines are skipped; a trailing CR (CRLF
// lines) and a leading byte order mark are dropped.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "kew/eligibility/aerodromes.hpp"

namespace kew::eligibility {

/// Text that is no aerodrome table. what(): "origin:line: message", the line from 1.
class AerodromeCsvError : public std::runtime_error {
 public:
  AerodromeCsvError(std::string_view origin, std::size_t line, std::string_view message);
  std::size_t line() const { return line_; }

 private:
  std::size_t line_;
};

/// The rows of `text` in file order, each checked as AerodromeTable checks it (problem(),
/// idents unique). `origin` names the text in messages (the file's path). Throws
/// AerodromeCsvError at the first error: a missing required column, a row whose
/// fields are not as many as the header's, a figure that is no number or out of its range, a repeated
/// ident, an unclosed quote; and for a table without a row.
std::vector<Aerodrome> parse_aerodrome_csv(std::string_view text, std::string_view origin);

}  // namespace kew::eligibility
