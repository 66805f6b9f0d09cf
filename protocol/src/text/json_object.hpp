#pragma once
// One flat JSON object at a time, through simdjson's DOM parser: the NDJSON, readsb and
// OpenSky JSON decoders each hand it one line (or one array element) and map its
// members to a TrackReport. Internal to kew_protocol.
//
// DOM rather than On-Demand: the DOM parser is compiled into libsimdjson with runtime
// CPU dispatch (AVX2 kernels where available), while On-Demand is instantiated in our
// own translation units and, without -march flags, falls back to its generic kernel.
// DOM also validates the whole text, including the values of ignored keys and anything
// after the object.

#include <simdjson.h>

#include <array>
#include <cstring>
#include <optional>
#include <string_view>
#include <vector>

#include "text_fields.hpp"

namespace kew::protocol::text {

/// Problem for a simdjson error while reading `what` ("" for the document itself).
LineProblem json_problem(simdjson::error_code error, std::string_view what);

/// A number member; null → nullopt. `key` names the member in the problem.
LineResult read_number(simdjson::dom::element value, std::string_view key,
                       std::optional<double>& out);
/// A number member that must be present and not null.
LineResult read_required_number(simdjson::dom::element value, std::string_view key,
                                double& out);
/// A string member (unescaped; valid until the next parse); null → nullopt.
LineResult read_string(simdjson::dom::element value, std::string_view key,
                       std::optional<std::string_view>& out);
/// A boolean member; null → nullopt.
LineResult read_bool(simdjson::dom::element value, std::string_view key,
                     std::optional<bool>& out);
/// A Mode 3/A member: a string of 4 octal digits; null → nullopt.
LineResult read_mode3a(simdjson::dom::element value, std::string_view key,
                       std::optional<std::uint16_t>& out);
/// A 24-bit ICAO address member: a string of exactly 6 hex digits, either case
/// ("bad_address" otherwise); null → nullopt.
LineResult read_icao_address(simdjson::dom::element value, std::string_view key,
                             std::optional<std::uint32_t>& out);

/// The first N elements of the array `value` into `out`, and in `size` how many it has
/// (all of them, N or more); false when `value` is not an array. For arrays whose
/// elements are fields by position (OpenSky's state vectors, readsb's trace rows).
template <std::size_t N>
bool array_elements(simdjson::dom::element value, std::array<simdjson::dom::element, N>& out, std::size_t& size) {
  simdjson::dom::array array;
  if (value.get_array().get(array) != simdjson::SUCCESS) return false;
  size = 0;
  for (const simdjson::dom::element element : array) {
    if (size < N) out[size] = element;
    ++size;
  }
  return true;
}

class JsonObjectParser {
 public:
  /// `max_bytes`: the longest text parse() accepts (callers bound their input first).
  explicit JsonObjectParser(std::size_t max_bytes)
      : padded_(max_bytes + simdjson::SIMDJSON_PADDING) {}

  /// Parses `text` as one JSON object and calls `on_member(key, value)` for each member
  /// in order (`value` is a simdjson::dom::element); the first problem it returns
  /// stops the walk and is returned. Unknown keys: on_member simply does not read them.
  template <class OnMember>
  LineResult parse(std::string_view text, OnMember&& on_member);

 private:
  simdjson::dom::parser parser_;
  // simdjson reads up to SIMDJSON_PADDING bytes past the text: each text is copied into
  // this buffer, which is cheaper than padding every chunk of the stream.
  std::vector<char> padded_;
};

template <class OnMember>
LineResult JsonObjectParser::parse(std::string_view text, OnMember&& on_member) {
  if (text.size() + simdjson::SIMDJSON_PADDING > padded_.size())
    padded_.resize(text.size() + simdjson::SIMDJSON_PADDING);
  std::memcpy(padded_.data(), text.data(), text.size());
  simdjson::dom::element document;
  if (auto error = parser_.parse(padded_.data(), text.size(), false).get(document))
    return json_problem(error, "");
  simdjson::dom::object object;
  if (document.get_object().get(object) != simdjson::SUCCESS)
    return problem("bad_json", "not a JSON object");
  for (const simdjson::dom::key_value_pair member : object) {
    if (LineResult result = on_member(member.key, member.value)) return result;
  }
  return std::nullopt;
}

}  // namespace kew::protocol::text
