#include "pair_checkpoint.hpp"

#include <fmt/format.h>
#include <simdjson.h>
#include <zlib.h>

#include "kew/protocol/ndjson_writer.hpp"

namespace kew::daemon {

namespace {

std::uint32_t crc32_of(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  // zlib takes lengths as uInt: a state of several GiB is read in parts.
  constexpr std::size_t kPart = 1u << 30;
  for (std::size_t at = 0; at < bytes.size(); at += kPart) {
    const std::string_view part = bytes.substr(at, kPart);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(part.data()), static_cast<uInt>(part.size()));
  }
  return static_cast<std::uint32_t>(crc);
}

}  // namespace

std::string to_bytes(const PairCheckpoint& c) {
  std::string name;
  protocol::append_json_string(name, c.written_by);
  std::string out = fmt::format(
      R"({{"origin_feed_seq":{},"origin_created_t":{:.3f},"feed_seq":{},"alerts_seq":{},"last_seq":{},)"
      R"("written_by":{},"written_t":{:.3f},"state_bytes":{},"state_crc32":{}}})",
      c.origin_feed_seq, c.origin_created_unix_s, c.feed_seq, c.alerts_seq, c.last_seq, name, c.written_unix_s,
      c.pipeline.size(), crc32_of(c.pipeline));
  out += '\n';
  out += c.pipeline;
  return out;
}

std::optional<PairCheckpoint> pair_checkpoint_from_bytes(std::string_view bytes, std::string& why) {
  const std::size_t newline = bytes.find('\n');
  if (newline == std::string_view::npos || newline > 4096) {
    why = "no header line";
    return std::nullopt;
  }
  simdjson::dom::parser parser;
  simdjson::dom::element root;
  const std::string header(bytes.substr(0, newline));
  if (parser.parse(header).get(root)) {
    why = "a header that is not JSON";
    return std::nullopt;
  }
  PairCheckpoint c;
  std::string_view name;
  std::uint64_t size = 0, crc = 0;
  if (root["origin_feed_seq"].get(c.origin_feed_seq) || root["origin_created_t"].get(c.origin_created_unix_s) ||
      root["feed_seq"].get(c.feed_seq) || root["alerts_seq"].get(c.alerts_seq) || root["last_seq"].get(c.last_seq) ||
      root["written_by"].get(name) || root["written_t"].get(c.written_unix_s) || root["state_bytes"].get(size) ||
      root["state_crc32"].get(crc)) {
    why = "a header without every field";
    return std::nullopt;
  }
  const std::string_view state = bytes.substr(newline + 1);
  if (state.size() != size) {
    why = fmt::format("{} bytes of state where the header says {}", state.size(), size);
    return std::nullopt;
  }
  if (crc32_of(state) != crc) {
    why = "a state whose CRC-32 differs from the header's";
    return std::nullopt;
  }
  if (c.feed_seq < c.origin_feed_seq || c.alerts_seq == 0) {
    why = "a feed message before the pair's origin, or no alert stream message";
    return std::nullopt;
  }
  c.written_by = std::string(name);
  c.pipeline = std::string(state);
  return c;
}

}  // namespace kew::daemon
