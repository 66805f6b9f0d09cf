#pragma once
// Who gives way when a connection arrives at a full listener (design §6.6). A monitoring
// probe must always be answered, so no connection may keep a slot merely by holding it:
// a connection that is silent (it has asked nothing since `silent_since`: it connected
// and said nothing, or it was answered and went quiet, or it trickles a request) gives
// way to a newcomer, the one silent longest first. A connection that is being served
// (a watching subscriber, a WebSocket) never gives way here: the byte budgets and write
// time-outs judge it. One source address may hold at most `silent_per_address` silent
// connections: one more from it closes its own longest-silent one. When every slot is
// taken, the address holding the most silent connections pays first, so a client that
// keeps opening connections closes its own before anyone else's.
// Knows nothing of sockets: the servers describe their connections and act on the answer.

#include <chrono>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

namespace kew::daemon {

/// One connection as the policy sees it.
struct SlotHolder {
  std::string_view address;  ///< the peer's IP address (canonical text form)
  bool silent = false;       ///< asks nothing at the moment, so it may be closed for a newcomer
  std::chrono::steady_clock::time_point silent_since;  ///< when it last completed a request (or connected)
};

/// The holder to close before a connection from `address` is accepted, or none: the
/// longest-silent connection of `address` when that address already holds
/// `silent_per_address` silent ones (at least 1), else, when `every_slot_taken`, the
/// longest-silent connection of the address that holds the most silent ones (none when
/// no connection is silent). Ties go to the earlier holder in `holders`.
std::optional<std::size_t> connection_to_evict(std::span<const SlotHolder> holders, std::string_view address,
                                               std::size_t silent_per_address, bool every_slot_taken);

}  // namespace kew::daemon
