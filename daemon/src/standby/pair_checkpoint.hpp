#pragma once
// A checkpoint of a hot-standby pair's computation (design §5.9): the pipeline's state
// (Pipeline::checkpoint) after the feed message `feed_seq`, with where an instance that
// loads it continues: the feed from the next message, the active's alert stream from
// message `alerts_seq`, the numbering from `last_seq`. The active writes one every
// [nats] checkpoint_interval_s, and the pair's origin moves to it: an instance that
// starts judges the feed from the latest checkpoint instead of from the origin.
//
// Byte form: one line of JSON (every field but the pipeline's state, with the state's
// size and CRC-32), a newline, then the state's bytes.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace kew::daemon {

struct PairCheckpoint {
  /// The pair it continues: its origin's first feed message and creation time (a
  /// checkpoint of an earlier pair under the same lease_key is not loaded).
  std::uint64_t origin_feed_seq = 0;
  double origin_created_unix_s = 0.0;
  /// JetStream stream sequence of the last feed message whose records are in the state.
  std::uint64_t feed_seq = 0;
  /// The alert stream's first message after everything the state's events and
  /// acknowledgements produced (≥ 1): where an instance loading it follows the active.
  std::uint64_t alerts_seq = 1;
  /// The seq of the state's last event (its alert manager's).
  std::uint64_t last_seq = 0;
  std::string written_by;  ///< the instance that wrote it (for operators)
  double written_unix_s = 0.0;
  std::string pipeline;  ///< Pipeline::checkpoint()'s bytes

  bool operator==(const PairCheckpoint&) const = default;
};

std::string to_bytes(const PairCheckpoint& checkpoint);
/// The checkpoint of to_bytes' output; nullopt, with `why` said, for anything else (a
/// truncated or altered one: its size or CRC-32 differs).
std::optional<PairCheckpoint> pair_checkpoint_from_bytes(std::string_view bytes, std::string& why);

}  // namespace kew::daemon
