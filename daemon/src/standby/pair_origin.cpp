#include "pair_origin.hpp"

#include <limits>

#include <fmt/format.h>
#include <simdjson.h>

#include "kew/protocol/ndjson_writer.hpp"

namespace kew::daemon {

std::string to_json(const PairOrigin& origin) {
  std::string name;
  protocol::append_json_string(name, origin.created_by);
  return fmt::format(R"({{"feed_seq":{},"alerts_seq":{},"last_seq":{},"next_number":{},"created_by":{},"created_t":{:.3f}}})",
                     origin.feed_seq, origin.alerts_seq, origin.last_seq, origin.next_number, name,
                     origin.created_unix_s);
}

std::optional<PairOrigin> pair_origin_from_json(std::string_view text) {
  simdjson::dom::parser parser;
  simdjson::dom::element root;
  if (parser.parse(text.data(), text.size()).get(root)) return std::nullopt;
  PairOrigin origin;
  std::uint64_t number = 0;
  std::string_view name;
  if (root["feed_seq"].get(origin.feed_seq) || root["alerts_seq"].get(origin.alerts_seq) ||
      root["last_seq"].get(origin.last_seq) || root["next_number"].get(number) || root["created_by"].get(name) ||
      root["created_t"].get(origin.created_unix_s))
    return std::nullopt;
  if (origin.feed_seq == 0 || origin.alerts_seq == 0 || number == 0 ||
      number > std::numeric_limits<std::uint16_t>::max())
    return std::nullopt;
  origin.next_number = static_cast<std::uint16_t>(number);
  origin.created_by = std::string(name);
  return origin;
}

}  // namespace kew::daemon
