#pragma once
// `kew-replay --to`: streams records as canonical NDJSON to a daemon input over TCP
// (one connection, lines back to back), UDP (datagrams of whole lines, at most
// `max_datagram_bytes`) or NATS (messages of whole lines, as UDP's datagrams, published
// to a subject through the NATS C client), paced like the recording.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kew/replay/recording_reader.hpp"

namespace kew::replay {

struct StreamTarget {
  enum class Protocol { Tcp, Udp, Nats } protocol = Protocol::Tcp;
  std::string host;
  std::uint16_t port = 0;
  std::string subject;  ///< NATS only
  /// NATS only: the servers of one cluster, "nats://HOST:PORT" each; the first is also
  /// `host` and `port`.
  std::vector<std::string> nats_servers;
};

/// "tcp://HOST:PORT", "udp://HOST:PORT", "nats://HOST:PORT/SUBJECT" or "HOST:PORT" (TCP),
/// HOST:PORT as config::parse_host_port reads it (IPv6 in brackets, port 1–65535), the
/// subject one to publish to (config::valid_nats_subject). NATS may name several servers
/// of one cluster, comma-separated: "nats://h1:4222,h2:4222/SUBJECT" (each may repeat
/// "nats://"). Returns nullopt when malformed, with `*error` (when given) saying why.
std::optional<StreamTarget> parse_stream_target(std::string_view text, std::string* error = nullptr);

struct StreamFigures {
  std::uint64_t records = 0;
  std::uint64_t bytes = 0;
  std::uint64_t datagrams = 0;  ///< UDP datagrams or NATS messages
};

/// Sends every record of `recordings` to `target`, each no earlier than its due time at
/// `speed` (0: as fast as possible). Throws std::runtime_error when the connection fails.
StreamFigures stream_records(MergedRecordings& recordings, const StreamTarget& target, double speed,
                             std::size_t max_datagram_bytes = 1400);

}  // namespace kew::replay
