#pragma once
// What an input knows of its source's backlog (design §4.1 "Live mode", §5.9): a durable
// JetStream consumer can tell whether the stream holds records it has not yet delivered,
// and whether the server answers at all. The live tick counts a feed as silent only while
// every such source has nothing more for kewd.

#include <cstdint>

namespace kew::daemon {

enum class SourceState : std::uint8_t {
  CaughtUp,     ///< the source holds nothing undelivered (or cannot tell: UDP, TCP, files)
  Behind,       ///< the source holds records not yet delivered: a backlog on its way
  Unreachable,  ///< the source cannot be asked (its NATS server is away or does not answer)
};

}  // namespace kew::daemon
