#include "json_object.hpp"

#include <fmt/format.h>

namespace kew::protocol::text {

LineProblem json_problem(simdjson::error_code error, std::string_view what) {
  const std::string_view reason = error == simdjson::INCORRECT_TYPE ? "wrong_type"
                                  : error == simdjson::NUMBER_ERROR  ? "bad_number"
                                                                     : "bad_json";
  if (what.empty()) return problem(reason, simdjson::error_message(error));
  return problem(reason, fmt::format("{}: {}", what, simdjson::error_message(error)));
}

namespace {
LineProblem wrong_type(std::string_view key, std::string_view expected) {
  return problem("wrong_type", fmt::format("\"{}\" must be {}", key, expected));
}
}  // namespace

LineResult read_number(simdjson::dom::element value, std::string_view key,
                       std::optional<double>& out) {
  out.reset();
  if (value.is_null()) return std::nullopt;
  if (!value.is_number()) return wrong_type(key, "a number");
  double number = 0;
  if (auto error = value.get_double().get(number))
    return json_problem(error, fmt::format("\"{}\"", key));
  out = number;
  return std::nullopt;
}

LineResult read_required_number(simdjson::dom::element value, std::string_view key,
                                double& out) {
  if (!value.is_number()) return wrong_type(key, "a number");
  std::optional<double> number;
  if (LineResult r = read_number(value, key, number)) return r;
  out = *number;
  return std::nullopt;
}

LineResult read_string(simdjson::dom::element value, std::string_view key,
                       std::optional<std::string_view>& out) {
  out.reset();
  if (value.is_null()) return std::nullopt;
  std::string_view text;
  if (value.get_string().get(text) != simdjson::SUCCESS) return wrong_type(key, "a string");
  out = text;
  return std::nullopt;
}

LineResult read_bool(simdjson::dom::element value, std::string_view key,
                     std::optional<bool>& out) {
  out.reset();
  if (value.is_null()) return std::nullopt;
  bool flag = false;
  if (value.get_bool().get(flag) != simdjson::SUCCESS) return wrong_type(key, "true or false");
  out = flag;
  return std::nullopt;
}

namespace {
/// A string member whose text `parse` turns into a code; text it refuses is the problem
/// `reason` ("\"key\" must be <what>"); null → nullopt.
template <class Code>
LineResult read_coded_string(simdjson::dom::element value, std::string_view key,
                             std::optional<Code>& out, bool (*parse)(std::string_view, Code&),
                             std::string_view reason, std::string_view what) {
  std::optional<std::string_view> text;
  if (LineResult r = read_string(value, key, text)) return r;
  out.reset();
  if (!text) return std::nullopt;
  Code code{};
  if (!parse(*text, code)) return problem(reason, fmt::format("\"{}\" must be {}", key, what));
  out = code;
  return std::nullopt;
}
}  // namespace

LineResult read_mode3a(simdjson::dom::element value, std::string_view key,
                       std::optional<std::uint16_t>& out) {
  return read_coded_string(value, key, out, parse_mode3a, "bad_mode3a", "4 octal digits");
}

LineResult read_icao_address(simdjson::dom::element value, std::string_view key,
                             std::optional<std::uint32_t>& out) {
  return read_coded_string(value, key, out, parse_icao_address, "bad_address", "6 hex digits");
}

}  // namespace kew::protocol::text
